// The validation suite file (validate Suite): cases parsed with their defaults and overrides,
// and refused, naming the file, where `mvw validate` could not run them.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/validate/Suite.h"

namespace mvw::validate {
namespace {

namespace fs = std::filesystem;
fs::path writeSuite(const fs::path& dir, const std::string& text) {
  std::ofstream(dir / "study.json") << "{}";
  const fs::path p = dir / "suite.json";
  std::ofstream(p) << text;
  return p;
}

std::string problemOf(const fs::path& suite) {
  try {
    loadSuite(suite);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), suite);
    return e.problem();
  }
  ADD_FAILURE() << "no InputError for " << suite;
  return {};
}
TEST(Suite, ParsesCasesWithDefaultsAndOverrides) {
  const fs::path dir = test::scratchDir();
  const Suite s = loadSuite(writeSuite(dir, R"({"name": "n", "study": "study.json",
      "tolerance": {"psnr": 30},
      "cases": [{"name": "a", "view": "bone", "reference": "golden/a.png"},
                {"name": "b", "view": {"mode": "mip"}, "tolerance": {"ssim": 0.9},
                 "checks": [{"type": "mip_equals_max_projection", "axis": "y"}]}]})"));
  EXPECT_EQ(s.name, "n");
  ASSERT_EQ(s.cases.size(), 2u);
  EXPECT_EQ(s.cases[0].study, (dir / "study.json").lexically_normal());
  EXPECT_EQ(*s.cases[0].reference, (dir / "golden/a.png").lexically_normal());
  EXPECT_EQ(s.cases[0].viewLabel, "bone");
  EXPECT_EQ(s.cases[0].tolerance.psnr, 30.0);
  EXPECT_EQ(s.cases[1].tolerance.psnr, 30.0);
  EXPECT_EQ(s.cases[1].tolerance.ssim, 0.9);
  EXPECT_EQ(s.cases[1].viewLabel, "(inline)");
  ASSERT_EQ(s.cases[1].checks.size(), 1u);
  EXPECT_EQ(s.cases[1].checks[0].axis, 1);
}

TEST(Suite, RefusesWhatItCannotRun) {
  const fs::path dir = test::scratchDir();
  auto problem = [&](const std::string& text) { return problemOf(writeSuite(dir, text)); };
  EXPECT_NE(problem(R"({"cases": [], "nmae": 1})").find("unknown key \"nmae\""), std::string::npos);
  EXPECT_NE(problem(R"({"cases": []})").find("non-empty list"), std::string::npos);
  EXPECT_NE(problem(R"({"study": "study.json", "cases": [{"name": "a/b", "view": "v",
      "reference": "r.png"}]})")
                .find("\"name\" is required"),
            std::string::npos);
  EXPECT_NE(problem(R"({"study": "study.json", "cases": [{"name": "a", "view": "v",
      "reference": "r.png"}, {"name": "a", "view": "v", "reference": "r.png"}]})")
                .find("used twice"),
            std::string::npos);
  EXPECT_NE(problem(R"({"cases": [{"name": "a", "view": "v", "reference": "r.png"}]})")
                .find("no \"study\""),
            std::string::npos);
  EXPECT_NE(problem(R"({"study": "study.json", "cases": [{"name": "a", "view": "v"}]})")
                .find("\"reference\" image, \"checks\", or both"),
            std::string::npos);
  ::unsetenv("MVW_TEST_UNSET_VARIABLE");
  EXPECT_NE(problem(R"({"study": "${MVW_TEST_UNSET_VARIABLE}/s.json", "cases": [{"name": "a",
      "view": "v", "reference": "r.png"}]})")
                .find("MVW_TEST_UNSET_VARIABLE is not set"),
            std::string::npos);
  EXPECT_NE(problem(R"({"study": "study.json", "cases": [{"name": "a", "view": "v",
      "checks": [{"type": "mip_equals_max_projection", "axis": "w"}]}]})")
                .find("\"axis\""),
            std::string::npos);
  EXPECT_NE(problem("{").find("not valid JSON"), std::string::npos);
  EXPECT_TRUE(isGoodCaseName("mip-left_2.x"));
  EXPECT_FALSE(isGoodCaseName(".hidden"));
  EXPECT_FALSE(isGoodCaseName("a b"));
}

}  // namespace
}  // namespace mvw::validate
