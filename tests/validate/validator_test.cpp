// runValidate (`mvw validate`'s engine): the renders happen in child processes, not the
// caller's, and a render that throws fails its cases with the exit code and the message. The
// renders themselves (output::renderStudy) are the golden suites' (tests/render/suite.json);
// here the render fails before any GL work, as MVW_GL names no backend.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Image.h"
#include "mvw/io/Png.h"
#include "mvw/validate/Validator.h"

namespace mvw::validate {
namespace {

namespace fs = std::filesystem;

// Sets an environment variable for the scope (the render processes inherit it), then restores
// it.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* before = std::getenv(name)) before_ = before;
    ::setenv(name, value, 1);
  }
  ~ScopedEnvironment() {
    if (before_)
      ::setenv(name_, before_->c_str(), 1);
    else
      ::unsetenv(name_);
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

 private:
  const char* name_;
  std::optional<std::string> before_;
};

TEST(Validate, ARenderThatThrowsInItsChildProcessFailsItsCases) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "ct.nii") << "not read: the render fails first";
  std::ofstream(dir / "study.json") << R"({"anatomical": {"path": "ct.nii"},
      "render": {"views": [{"name": "a", "width": 8, "height": 6},
                           {"name": "b", "width": 8, "height": 6}]}})";
  Image grey(8, 6);
  for (std::size_t i = 0; i < grey.rgba.size(); ++i) grey.rgba[i] = i % 4 == 3 ? 255 : 100;
  io::writePng(grey, dir / "ref.png");
  std::ofstream(dir / "suite.json") << R"({"study": "study.json", "cases": [
      {"name": "one", "view": "a", "reference": "ref.png"},
      {"name": "two", "view": "b", "reference": "ref.png"}]})";
  ValidateOptions o;
  o.suite = dir / "suite.json";
  o.outDir = dir / "failed";
  o.jobs = 2;
  o.timeoutS = 60.0;
  bool passed = true;
  {
    // Thrown in the caller's process, it would leave runValidate instead of failing the cases.
    const ScopedEnvironment gl("MVW_GL", "no-such-gl");
    passed = runValidate(o);
  }
  EXPECT_FALSE(passed);
  std::ifstream report(dir / "failed" / "report.json");
  std::stringstream text;
  text << report.rdbuf();
  EXPECT_NE(text.str().find("mvw render exited with 2: mvw: error: "), std::string::npos);
  EXPECT_NE(text.str().find("no-such-gl"), std::string::npos);
}

}  // namespace
}  // namespace mvw::validate
