// modules/validate without GL: image metrics against hand-computed values, suite parsing and
// its refusals, the report's text, the process pool's exit codes, time limit and launcher, and
// runValidate through an injected render function.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <future>
#include <iostream>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Image.h"
#include "mvw/io/PngWriter.h"
#include "mvw/validate/Checksums.h"
#include "mvw/validate/ImageMetrics.h"
#include "mvw/validate/ProcessPool.h"
#include "mvw/validate/Report.h"
#include "mvw/validate/Suite.h"
#include "mvw/validate/Validator.h"

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
  const auto dir = std::filesystem::temp_directory_path() / "mvw-checksums-test";
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
  std::filesystem::remove_all(dir);
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

// What the pool's jobs do in these tests, by their first argument.
int testJob(const std::vector<std::string>& args) {
  const std::string& what = args.at(0);
  if (what == "exit3") {
    std::cout << "out" << std::endl;
    return 3;
  }
  if (what == "sleep") {
    std::cout << ::getpid() << std::endl;
    std::this_thread::sleep_for(std::chrono::seconds(30));
    return 0;
  }
  if (what == "late") std::this_thread::sleep_for(std::chrono::milliseconds(500));
  if (what == "kill") ::raise(SIGKILL);
  if (what == "input") throw InputError("bad.json", "is bad");
  if (what == "fault") throw std::runtime_error("it broke");
  if (what == "buffered") std::cout << "left in the buffer";  // no flush: the pool's
  return 0;
}

std::string firstLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

TEST(ProcessPool, ReportsExitCodesAndKillsAtTheTimeLimit) {
  const fs::path dir = test::scratchDir();
  ProcessPool pool(testJob);
  const std::vector<std::string> kinds = {"exit3", "sleep", "kill", "input", "fault", "buffered"};
  std::vector<ProcessJob> jobs;
  for (const std::string& k : kinds) jobs.push_back({{k}, dir / (k + ".log")});
  std::vector<ProcessResult> results(jobs.size());
  int calls = 0;
  pool.run(jobs, 2, 1.0, [&](std::size_t j, const ProcessResult& r) {
    results[j] = r;
    ++calls;
  });
  EXPECT_EQ(calls, 6);
  EXPECT_EQ(results[0].status, 3);
  EXPECT_EQ(firstLine(dir / "exit3.log"), "out");
  EXPECT_EQ(results[1].status, kTimedOut);
  EXPECT_LT(results[1].seconds, 10.0);
  EXPECT_EQ(results[2].status, 128 + 9);
  // Exceptions end the child as mvw's main ends mvw: 2 for bad input, 1 for a fault.
  EXPECT_EQ(results[3].status, 2);
  EXPECT_EQ(firstLine(dir / "input.log"), "mvw: error: bad.json: is bad");
  EXPECT_EQ(results[4].status, 1);
  EXPECT_EQ(firstLine(dir / "fault.log"), "mvw: internal error: it broke");
  EXPECT_EQ(results[5].status, 0);
  EXPECT_EQ(firstLine(dir / "buffered.log"), "left in the buffer");
  // The pool goes on with another run; a log that cannot be written is an Error.
  calls = 0;
  pool.run({{{"exit3"}, dir / "again.log"}}, 1, 10.0,
           [&](std::size_t, const ProcessResult& r) { calls += r.status == 3; });
  EXPECT_EQ(calls, 1);
  EXPECT_THROW(pool.run({{{"exit3"}, dir / "no" / "such" / "folder.log"}}, 1, 1.0,
                        [](std::size_t, const ProcessResult&) {}),
               Error);
}

// The jobs are forked by the launcher, a copy of the caller made with the pool: a lock that a
// thread of the caller took later (a thread pool's, say) is free in the jobs, not held by a
// thread that the fork left behind.
TEST(ProcessPool, JobsAreCopiesOfTheCallerAsItWasWhenThePoolWasMade) {
  static std::mutex lock;
  const fs::path dir = test::scratchDir();
  ProcessPool pool([](const std::vector<std::string>&) {
    if (!lock.try_lock()) return 1;
    lock.unlock();
    return 0;
  });
  std::promise<void> held, release;
  std::thread holder([&] {
    const std::lock_guard<std::mutex> guard(lock);
    held.set_value();
    release.get_future().wait();
  });
  held.get_future().wait();
  int status = -1;
  pool.run({{{}, dir / "a.log"}}, 1, 10.0,
           [&](std::size_t, const ProcessResult& r) { status = r.status; });
  release.set_value();
  holder.join();
  EXPECT_EQ(status, 0) << "the job saw the lock that a thread of the caller holds";
}

// When onDone throws, the jobs still running are killed and reaped before run() returns.
TEST(ProcessPool, AnExceptionFromOnDoneKillsTheJobsStillRunning) {
  const fs::path dir = test::scratchDir();
  ProcessPool pool(testJob);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(pool.run({{{"sleep"}, dir / "sleep.log"}, {{"late"}, dir / "late.log"}}, 2, 60.0,
                        [](std::size_t, const ProcessResult&) {
                          throw std::runtime_error("the judge failed");
                        }),
               std::runtime_error);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  const pid_t sleeper = static_cast<pid_t>(std::stol(firstLine(dir / "sleep.log")));
  EXPECT_NE(::kill(sleeper, 0), 0) << "the sleeping job " << sleeper << " still runs";
  EXPECT_THROW(pool.run({}, 1, 1.0, [](std::size_t, const ProcessResult&) {}), Error);
}

TEST(ProcessPool, RunInChildGivesTheExitCodeAndTheMessage) {
  EXPECT_EQ(runInChild([] {}), 0);
  testing::internal::CaptureStderr();
  const int status = runInChild([] { throw InputError("--gl egl", "no EGL here"); });
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_EQ(status, 2);
  EXPECT_EQ(said, "mvw: error: --gl egl: no EGL here\n");
  testing::internal::CaptureStderr();
  EXPECT_EQ(runInChild([] { throw Error("broke"); }), 1);
  testing::internal::GetCapturedStderr();
}

// runValidate renders through the function it is given, in child processes (not in the
// caller's), and a render that throws fails its cases with the exit code and the message.
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
