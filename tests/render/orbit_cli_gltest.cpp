// `mvw render --orbit` and the colour maps through the shipped binary (headless): the frames,
// the movie (decoded by cv::VideoCapture), render.json, the stills the frames must equal, and
// the bad input that must leave nothing behind.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "../support/TestUtil.h"
#include "mvw/io/ColorPalettes.h"
#include "mvw/io/MovieWriter.h"
#include "mvw/io/Png.h"

namespace mvw {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int rc = -1;
  std::string err;
};

// mvw with `args` (a shell-quoted string); stderr captured.
// `env`, when given, is "NAME=VALUE" set for that run only.
CliRun mvw(const std::string& args, const fs::path& dir, const std::string& env = "") {
  const fs::path err = dir / "stderr.txt";
  const std::string cmd = (env.empty() ? std::string() : "env " + env + " ") +
                          std::string(MVW_BINARY) + " " + args + " > /dev/null 2> " + err.string();
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::ostringstream text;
  text << in.rdbuf();
  r.err = text.str();
  return r;
}

// mvw with `args` exits 0; otherwise the failure names the command, its exit code and stderr.
testing::AssertionResult ran(const std::string& args, const fs::path& dir) {
  const CliRun r = mvw(args, dir);
  if (r.rc == 0) return testing::AssertionSuccess();
  return testing::AssertionFailure() << "mvw " << args << " exited " << r.rc << ":\n" << r.err;
}

// A MIP study of the Cranium CT at an odd size (the movie pads it to even).
fs::path writeStudy(const fs::path& dir, const std::string& view) {
  const fs::path file = dir / "study.json";
  std::ofstream(file) << R"({ "anatomical": { "path": ")"
                      << test::sampleData("cranium/dicom").string()
                      << R"(" }, "render": { "views": [ )" << view << " ] } }";
  return file;
}

// A PNG as BGRA (OpenCV's channel order, as the checks below spell colours), read by io::readPng.
cv::Mat png(const fs::path& file) {
  Image image;
  try {
    image = io::readPng(file);
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
    return cv::Mat();
  }
  cv::Mat m(image.height, image.width, CV_8UC4);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      m.at<cv::Vec4b>(y, x) = cv::Vec4b(p[2], p[1], p[0], p[3]);
    }
  return m;
}

bool samePixels(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

const char* kMip =
    R"({ "name": "mip", "mode": "mip", "view": "anterior", "azimuth": 20, "window": 2000,
         "level": 900, "width": 65, "height": 57 })";

TEST(OrbitCli, SpinFramesMovieAndRecord) {
  const fs::path dir = test::scratchDir();
  const fs::path study = writeStudy(dir, kMip);
  ASSERT_TRUE(
      ran("render " + study.string() + " -o " + (dir / "spin").string() + " --orbit 8", dir));
  for (int k = 0; k < 8; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%03d.png", k);
    const cv::Mat f = png(dir / "spin" / "mip" / name);
    EXPECT_EQ(f.cols, 65);
    EXPECT_EQ(f.rows, 57);
  }
  EXPECT_FALSE(fs::exists(dir / "spin" / "mip" / "frame-008.png"));
  // The first frame is the still at the view's azimuth; frame N/2 the still at azimuth + 180.
  ASSERT_TRUE(ran("render " + study.string() + " -o " + (dir / "still").string(), dir));
  EXPECT_TRUE(
      samePixels(png(dir / "spin" / "mip" / "frame-000.png"), png(dir / "still" / "mip.png")));
  EXPECT_TRUE(samePixels(png(dir / "spin" / "mip.png"), png(dir / "still" / "mip.png")));
  ASSERT_TRUE(
      ran("render " + study.string() + " -o " + (dir / "turned").string() + " --azimuth 200", dir));
  EXPECT_TRUE(
      samePixels(png(dir / "spin" / "mip" / "frame-004.png"), png(dir / "turned" / "mip.png")));
  EXPECT_FALSE(
      samePixels(png(dir / "spin" / "mip" / "frame-001.png"), png(dir / "still" / "mip.png")));
  // The movie: every frame, at the even size.
  const io::MovieInfo movie = io::readMovieInfo(dir / "spin" / "mip.mp4");
  EXPECT_EQ(movie.frames, 8);
  EXPECT_EQ(movie.width, 66);
  EXPECT_EQ(movie.height, 58);
  const nlohmann::json record =
      nlohmann::json::parse(std::ifstream(dir / "spin" / "render.json"))["views"][0]["orbit"];
  EXPECT_EQ(record["frames"], 8);
  EXPECT_EQ(record["mode"], "spin");
  EXPECT_EQ(record["movie"], "mip.mp4");
  EXPECT_EQ(record["movie_size"], nlohmann::json({66, 58}));
  ASSERT_EQ(record["files"].size(), 8u);
  EXPECT_EQ(record["files"][7], "mip/frame-007.png");
  EXPECT_EQ(record["azimuths_deg"][4], 200.0);
  // Nothing staged is left beside the output.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".mvw-render-"), std::string::npos) << e.path();
}

TEST(OrbitCli, RockSwingsOverItsRangeWithDepthCue) {
  const fs::path dir = test::scratchDir();
  const fs::path study = writeStudy(
      dir, R"({ "name": "cued", "mode": "mip", "view": "left", "window": 2000, "level": 900,
               "width": 48, "height": 48, "depth_cue": { "amount": 0.8, "contrast": 0.35 },
               "colormap": "hot-iron", "orbit": 8, "orbit_mode": "rock", "orbit_range": 20 })");
  // Into folders that do not exist yet: created, with nothing staged left on the way.
  const fs::path rock = dir / "deep" / "er" / "rock";
  ASSERT_TRUE(ran("render " + study.string() + " -o " + rock.string(), dir));
  for (const fs::path& d : {dir, dir / "deep", dir / "deep" / "er"})
    for (const auto& e : fs::directory_iterator(d))
      EXPECT_EQ(e.path().filename().string().find(".mvw-render-"), std::string::npos) << e.path();
  // Frame 2 of 8 is the top of the swing: azimuth + 20 exactly (sin(pi/2) = 1).
  ASSERT_TRUE(
      ran("render " + study.string() + " -o " + (dir / "top").string() + " --azimuth 20", dir));
  // --azimuth keeps the orbit, so the top run's own first frame is the still at azimuth 20.
  EXPECT_TRUE(samePixels(png(rock / "cued" / "frame-002.png"),
                         png(dir / "top" / "cued" / "frame-000.png")));
  EXPECT_EQ(io::readMovieInfo(rock / "cued.mp4").frames, 8);
  const nlohmann::json record =
      nlohmann::json::parse(std::ifstream(rock / "render.json"))["views"][0];
  EXPECT_EQ(record["orbit"]["mode"], "rock");
  EXPECT_EQ(record["orbit"]["range_deg"], 20.0);
  EXPECT_EQ(record["colormap"], "hot-iron");
  EXPECT_TRUE(record.contains("depth_cue"));
}

TEST(OrbitCli, FusionOrbitsWithItsOverlayColourMap) {
  const fs::path dir = test::scratchDir();
  const fs::path study = dir / "fusion.json";
  std::ofstream(study) << R"({ "anatomical": { "path": ")"
                       << test::sampleData("cranium/cranium.nii.gz").string()
                       << R"(" }, "functional": { "path": ")"
                       << test::sampleData("derived/pet_like.nii.gz").string() << R"(" },
      "render": { "views": [ { "name": "fused", "mode": "composite", "preset": "ct-skin",
        "fusion": true, "overlay_colormap": "pet", "width": 48, "height": 48 },
      { "name": "fused-mip", "mode": "mip", "fusion": true, "overlay_colormap": "pet",
        "overlay_threshold": 0.3, "depth_cue": { "amount": 0.66, "contrast": 0.33 },
        "annotate": false,
        "width": 48, "height": 48 } ] } })";
  ASSERT_TRUE(
      ran("render " + study.string() + " -o " + (dir / "spin").string() + " --orbit 4", dir));
  ASSERT_TRUE(
      ran("render " + study.string() + " -o " + (dir / "back").string() + " --azimuth 180", dir));
  EXPECT_TRUE(
      samePixels(png(dir / "spin" / "fused" / "frame-002.png"), png(dir / "back" / "fused.png")));
  // The fused, depth-cued MIP turns too (issue 41), its frames in colour where the PET is hot
  // (two lesions of a few pixels each at 48 x 48).
  const cv::Mat fusedMip = png(dir / "spin" / "fused-mip" / "frame-002.png");
  EXPECT_TRUE(samePixels(fusedMip, png(dir / "back" / "fused-mip.png")));
  int coloured = 0;
  for (int y = 0; y < fusedMip.rows; ++y)
    for (int x = 0; x < fusedMip.cols; ++x) {
      const cv::Vec4b p = fusedMip.at<cv::Vec4b>(y, x);
      coloured += p[0] != p[1] || p[1] != p[2];
    }
  EXPECT_GT(coloured, 5) << "the fused MIP's frame shows no functional colour";
  ASSERT_TRUE(ran("render " + study.string() + " -o " + (dir / "hot").string() +
                      " --overlay-colormap hot-metal",
                  dir));
  EXPECT_FALSE(samePixels(png(dir / "spin" / "fused.png"), png(dir / "hot" / "fused.png")))
      << "the overlay colour map changed nothing";
  const nlohmann::json record =
      nlohmann::json::parse(std::ifstream(dir / "spin" / "render.json"))["views"][0];
  EXPECT_EQ(record["overlay_colormap"], "pet");
  EXPECT_EQ(record["orbit"]["frames"], 4);
  EXPECT_EQ(io::readMovieInfo(dir / "spin" / "fused.mp4").frames, 4);
}

TEST(OrbitCli, ColourMapsReachThePixels) {
  const fs::path dir = test::scratchDir();
  const fs::path study = writeStudy(dir, kMip);
  const std::string base = "render " + study.string() + " --no-annotate --zoom 0.6 -o ";
  ASSERT_TRUE(ran(base + (dir / "grey").string(), dir));
  const cv::Mat grey = png(dir / "grey" / "mip.png");
  for (const char* name : {"grey-inverted", "hot-iron", "pet", "hot-metal-blue", "pet-20-step"}) {
    ASSERT_TRUE(ran(base + (dir / name).string() + " --colormap " + name, dir)) << name;
    const cv::Mat img = png(dir / name / "mip.png");
    const ColorTable table = io::standardColorTable(*parseColorMap(name));
    ASSERT_EQ(img.size(), grey.size());
    int wrong = 0;
    for (int y = 0; y < img.rows; ++y)
      for (int x = 0; x < img.cols; ++x) {
        const auto g = grey.at<cv::Vec4b>(y, x)[0];
        const auto& want = table.rgb[g];
        const cv::Vec4b got = img.at<cv::Vec4b>(y, x);  // BGRA
        wrong += got[2] != want[0] || got[1] != want[1] || got[0] != want[2];
      }
    EXPECT_EQ(wrong, 0) << name;
  }
  // Inverted grey: the empty background (zoomed out past the box) is white.
  const cv::Vec4b corner = png(dir / "grey-inverted" / "mip.png").at<cv::Vec4b>(0, 0);
  EXPECT_EQ(corner, cv::Vec4b(255, 255, 255, 255));
  EXPECT_EQ(grey.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 0, 255));
}

TEST(OrbitCli, BadInputIsRefusedWithNothingWritten) {
  const fs::path dir = test::scratchDir();
  const fs::path study = writeStudy(dir, kMip);
  const fs::path out = dir / "out";
  // A movie plugin that is not there (MVW_MOVIE_PLUGIN set wrong): one message, exit 2, no output.
  {
    const CliRun r = mvw("render " + study.string() + " -o " + out.string() + " --orbit 4", dir,
                         "MVW_MOVIE_PLUGIN=" + (dir / "no-such-plugin.so").string());
    EXPECT_EQ(r.rc, 2) << r.err;
    EXPECT_NE(r.err.find("MVW_MOVIE_PLUGIN names"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  for (const char* n : {"0", "1", "-3", "100000", "abc", "2.5", "99999999999999999999"}) {
    const CliRun r = mvw("render " + study.string() + " -o " + out.string() + " --orbit " + n, dir);
    EXPECT_EQ(r.rc, 2) << n << ": " << r.err;
    EXPECT_NE(r.err.find("orbit"), std::string::npos) << n << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << n;
  }
  CliRun r = mvw("render " + study.string() + " -o " + out.string() + " --colormap jet", dir);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--colormap 'jet' is not a colour map"), std::string::npos) << r.err;
  r = mvw("render " + study.string() + " -o " + out.string() + " --orbit 8 --orbit-mode tumble",
          dir);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--orbit-mode must be spin or rock"), std::string::npos) << r.err;
  r = mvw("render " + study.string() + " -o " + out.string() + " --orbit 8 --view superior", dir);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("every view of the study looks along it"), std::string::npos) << r.err;
  const fs::path badMap = writeStudy(dir, R"({ "mode": "mip", "colormap": "rainbow" })");
  r = mvw("render " + badMap.string() + " -o " + out.string(), dir);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("'render.views[0].colormap' must be grey, grey-inverted"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("study.json"), std::string::npos) << r.err;
  const fs::path badOrbit = writeStudy(dir, R"({ "mode": "mip", "orbit": "many" })");
  r = mvw("render " + badOrbit.string() + " -o " + out.string(), dir);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("'render.views[0].orbit' must be a whole number of frames"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".mvw-render-"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace mvw
