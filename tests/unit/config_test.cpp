#include <fstream>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"

namespace mvw::config {
namespace {

namespace fs = std::filesystem;

fs::path writeConfig(const fs::path& dir, const std::string& text) {
  std::ofstream(dir / "anat.nii") << "x";
  std::ofstream(dir / "pet.nii") << "x";
  const fs::path p = dir / "study.json";
  std::ofstream(p) << text;
  return p;
}

std::string errorOf(const fs::path& p) {
  try {
    loadStudyConfig(p);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), p);
    return e.problem();
  }
  ADD_FAILURE() << "no InputError for " << p;
  return {};
}

TEST(StudyConfig, ResolvesPathsRelativeToTheConfig) {
  const fs::path dir = test::scratchDir();
  const auto p = writeConfig(dir, R"({"name": "x", "anatomical": {"path": "anat.nii"},
      "functional": {"path": "pet.nii", "kind": "pet", "series": "3"}})");
  const StudyConfig c = loadStudyConfig(p);
  EXPECT_EQ(c.name, "x");
  EXPECT_EQ(c.anatomical.path, dir / "anat.nii");
  ASSERT_TRUE(c.functional.has_value());
  EXPECT_EQ(c.functional->series, "3");
  EXPECT_EQ(c.functionalKind, FunctionalKind::Pet);
}

TEST(StudyConfig, RefusesTyposMissingKeysAndBadValues) {
  const fs::path dir = test::scratchDir();
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"}, "fucntional": {}})"))
                .find("unknown key 'fucntional'"), std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"pth": "anat.nii"}})")).find("anatomical.pth"),
            std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"name": "x"})")).find("missing key 'anatomical'"), std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": "nope.nii"}})")).find("does not exist"),
            std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": 3}})")).find("must be a string"),
            std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"},
      "functional": {"path": "pet.nii", "kind": "xray"}})")).find("functional.kind"), std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": )")).find("not valid JSON"), std::string::npos);
}

}  // namespace
}  // namespace mvw::config
