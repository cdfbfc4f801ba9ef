// modules/validate without GL: image metrics against hand-computed values, suite parsing and
// its refusals, the report's text, the process pool's exit codes and time limit.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/validate/Checksums.h"
#include "mvw/validate/ImageMetrics.h"
#include "mvw/validate/ProcessPool.h"
#include "mvw/validate/Report.h"
#include "mvw/validate/Suite.h"

namespace mvw::validate {
namespace {

namespace fs = std::filesystem;

TEST(ImageMetrics, PsnrOfKnownErrors) {
  EXPECT_EQ(psnrFromMse(0.0), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(psnrFromMse(255.0 * 255.0), 0.0);
  EXPECT_NEAR(psnrFromMse(1.0), 48.1308, 1e-4);
  Image a(4, 4), b(4, 4);
  EXPECT_EQ(psnr(a, b), std::numeric_limits<double>::infinity());
  b.pixel(1, 1)[0] = 48;   // one channel of one pixel off by 48: mse = 48^2 / 48 values
  b.pixel(1, 1)[3] = 200;  // alpha does not count
  EXPECT_NEAR(psnr(a, b), 10 * std::log10(255.0 * 255.0 / 48.0), 1e-9);
}

TEST(ImageMetrics, CompareImagesCountsTheDifferingPixels) {
  cv::Mat a(10, 10, CV_8UC3, cv::Scalar(100, 100, 100));
  cv::Mat b = a.clone();
  b.at<cv::Vec3b>(2, 3)[1] = 130;  // +30 on one channel
  b.at<cv::Vec3b>(5, 5)[2] = 110;  // +10, under the threshold
  const Metrics m = compareImages(b, a, 24.0);
  EXPECT_EQ(m.maxDelta, 30.0);
  EXPECT_DOUBLE_EQ(m.overFraction, 1.0 / 100.0);
  EXPECT_DOUBLE_EQ(m.meanDelta, 40.0 / 300.0);
  EXPECT_NEAR(m.psnr, 10 * std::log10(255.0 * 255.0 / ((900.0 + 100.0) / 300.0)), 1e-9);
  EXPECT_LT(m.ssim, 1.0);
  EXPECT_EQ(m.heat.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));  // identical pixels stay black
  EXPECT_NE(m.heat.at<cv::Vec3b>(2, 3), cv::Vec3b(0, 0, 0));
  EXPECT_DOUBLE_EQ(ssimGrey(a, a), 1.0);
}

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

// Expected digests from Python: hashlib.sha256(bytes(pixels) + b"WxHx3").hexdigest().
TEST(Checksums, PixelSha256HashesPixelsAndShape) {
  cv::Mat one(1, 1, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_EQ(pixelSha256(one), "636a2d5f89b59e1e3cf490fd262046164f805a9dc60389ee1eb20b150d2aa7c3");
  const unsigned char six[] = {1, 2, 3, 4, 5, 6};
  const cv::Mat wide(1, 2, CV_8UC3, const_cast<unsigned char*>(six));
  const cv::Mat tall(2, 1, CV_8UC3, const_cast<unsigned char*>(six));
  EXPECT_EQ(pixelSha256(wide), "48f33293624fcae89f15911ec579d37f8811a01bd4fac865b62199e02ca45fe1");
  EXPECT_EQ(pixelSha256(tall), "f0876dc5363e9926e43d070e4fb7b4e1a97a3850545419754cbe963128422306");
  // A region of a larger image (rows not contiguous) hashes as its own pixels.
  cv::Mat big(3, 3, CV_8UC3, cv::Scalar(9, 9, 9));
  big(cv::Rect(1, 1, 1, 1)).setTo(cv::Scalar(1, 2, 3));
  EXPECT_EQ(pixelSha256(big(cv::Rect(1, 1, 1, 1))), pixelSha256(one));
}

TEST(Checksums, ManifestRoundTripAndRefusals) {
  const auto dir = test::scratchDir();
  std::filesystem::create_directories(dir / "golden");
  ChecksumManifest m;
  m.file = dir / "golden" / "checksums.json";
  m.glRenderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  m.glVersion = "4.5 (Core Profile) Mesa 22.3.6";
  m.images[m.keyOf(dir / "golden" / "a.png")] = std::string(64, 'a');
  writeChecksumManifest(m);
  const ChecksumManifest back = loadChecksumManifest(m.file);
  EXPECT_EQ(back.glRenderer, m.glRenderer);
  EXPECT_EQ(back.glVersion, m.glVersion);
  ASSERT_EQ(back.images.count("a.png"), 1u);
  EXPECT_TRUE(back.exactOn(m.glRenderer, m.glVersion));
  EXPECT_FALSE(back.exactOn("AMD Radeon", m.glVersion));
  EXPECT_FALSE(back.exactOn(m.glRenderer, "4.6 Mesa 23"));
  std::ofstream(m.file) << R"({"gl_renderer": "x", "gl_version": "y", "images": {"a.png": "12"}})";
  EXPECT_THROW(loadChecksumManifest(m.file), InputError);
  EXPECT_THROW(loadChecksumManifest(dir / "none.json"), InputError);
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

TEST(Report, HtmlAndCaseLinesSayWhatFailed) {
  Suite s;
  s.file = "suite.json";
  s.name = "golden <suite>";
  CaseSpec a, b;
  a.name = "a";
  b.name = "b";
  a.reference = "a.png";
  s.cases = {a, b};
  CaseResult ok, bad;
  bad.pass = false;
  bad.problems = {"mean delta 3.000 > 0.500"};
  const std::string page = reportHtml(s, {ok, bad}, {{"mvw_version", "9.9"}}, false);
  EXPECT_NE(page.find("<title>mvw validate: golden &lt;suite&gt;</title>"), std::string::npos);
  EXPECT_NE(page.find("1 of 2 cases pass"), std::string::npos);
  EXPECT_NE(page.find("mean delta 3.000 &gt; 0.500"), std::string::npos);
  EXPECT_NE(page.find("<td>9.9</td>"), std::string::npos);
  EXPECT_EQ(page.find("@BODY@"), std::string::npos);
  EXPECT_EQ(caseLine(b, bad).rfind("FAIL    b", 0), 0u);
  EXPECT_NE(caseLine(b, bad).find("mean delta 3.000"), std::string::npos);
}

TEST(ProcessPool, ReportsExitCodesAndKillsAtTheTimeLimit) {
  const fs::path dir = test::scratchDir();
  std::vector<ProcessJob> jobs = {{{"/bin/sh", "-c", "echo out; exit 3"}, dir / "a.log"},
                                  {{"/bin/sh", "-c", "sleep 30"}, dir / "b.log"},
                                  {{"/bin/sh", "-c", "kill -9 $$"}, dir / "c.log"}};
  std::vector<ProcessResult> results(jobs.size());
  int calls = 0;
  runProcesses(jobs, 2, 1.0, [&](std::size_t j, const ProcessResult& r) {
    results[j] = r;
    ++calls;
  });
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(results[0].status, 3);
  EXPECT_EQ(results[1].status, kTimedOut);
  EXPECT_LT(results[1].seconds, 10.0);
  EXPECT_EQ(results[2].status, 128 + 9);
  std::ifstream log(dir / "a.log");
  std::string line;
  std::getline(log, line);
  EXPECT_EQ(line, "out");
  EXPECT_THROW(runProcesses({{{"/nonexistent/mvw"}, dir / "d.log"}}, 1, 1.0,
                            [](std::size_t, const ProcessResult&) {}),
               Error);
}

}  // namespace
}  // namespace mvw::validate
