// runValidate (`mvw validate`'s engine) through an injected render function: the renders happen
// in child processes, not the caller's, and a render that throws fails its cases with the exit
// code and the message.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Image.h"
#include "mvw/io/Png.h"
#include "mvw/validate/Validator.h"

namespace mvw::validate {
namespace {

namespace fs = std::filesystem;

TEST(Validate, RendersThroughTheInjectedFunctionInChildProcesses) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "ct.nii") << "not read: no analytic checks";
  std::ofstream(dir / "study.json") << R"({"anatomical": {"path": "ct.nii"},
      "render": {"views": [{"name": "a", "width": 8, "height": 6},
                           {"name": "b", "width": 8, "height": 6}]}})";
  Image grey(8, 6);
  for (std::size_t i = 0; i < grey.rgba.size(); ++i) grey.rgba[i] = i % 4 == 3 ? 255 : 100;
  io::writePng(grey, dir / "ref.png");
  std::ofstream(dir / "suite.json") << R"({"study": "study.json", "cases": [
      {"name": "one", "view": "a", "reference": "ref.png"},
      {"name": "two", "view": "b", "reference": "ref.png"}]})";
  const pid_t caller = ::getpid();
  ValidateOptions o;
  o.suite = dir / "suite.json";
  o.outDir = dir / "report";
  o.jobs = 2;
  o.timeoutS = 60.0;
  o.render = [caller, grey](const fs::path& study, const fs::path& out) {
    if (::getpid() == caller) throw std::logic_error("rendered in the caller's process");
    fs::create_directories(out);
    for (const config::ViewConfig& v : config::loadStudyConfig(study).render.views)
      io::writePng(grey, out / (v.name + ".png"));
  };
  EXPECT_TRUE(runValidate(o));

  o.outDir = dir / "failed";
  o.render = [](const fs::path& study, const fs::path&) {
    throw InputError(study, "cannot be rendered here");
  };
  EXPECT_FALSE(runValidate(o));
  std::ifstream report(dir / "failed" / "report.json");
  std::stringstream text;
  text << report.rdbuf();
  EXPECT_NE(text.str().find("mvw render exited with 2: mvw: error: "), std::string::npos);
  EXPECT_NE(text.str().find("cannot be rendered here"), std::string::npos);

  o.render = nullptr;
  EXPECT_THROW(runValidate(o), Error);
}

}  // namespace
}  // namespace mvw::validate
