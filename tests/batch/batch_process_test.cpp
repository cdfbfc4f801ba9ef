// The run of one batch study (batch BatchProcess, BatchFolders): its mvw command line, the pool
// job that execs it with stdout where the task wants it, the message a failed run leaves, and
// the work, publish and leftover folders in OUT.
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/batch/BatchFolders.h"
#include "mvw/batch/BatchProcess.h"
#include "mvw/core/Error.h"

namespace mvw::batch {
namespace {

namespace fs = std::filesystem;

using Args = std::vector<std::string>;

std::string text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::set<std::string> names(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

TEST(BatchProcess, CommandLinesOfTheTasks) {
  BatchStudy s;
  s.id = "a";
  s.study = "/cohort/a.json";
  s.task = "render";
  s.options = {{"size", "256 128"}, {"mip", ""}, {"crop", "0 0 0 40"}};
  EXPECT_EQ(batchCommand(s, "/out/.work-a-1"),
            (Args{"render", "/cohort/a.json", "-o", "/out/.work-a-1", "--size", "256", "128",
                  "--mip", "--crop", "0", "0", "0", "40"}));
  s.task = "stats";
  s.options = {{"labels", "/cohort/labels.txt"}};
  EXPECT_EQ(batchCommand(s, "/out/.work-a-1"),
            (Args{"stats", "/cohort/a.json", "--json", "--labels", "/cohort/labels.txt"}));
}

TEST(BatchProcess, RegisterCommandFromTheStudyConfig) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "fixed.nii") << "x";
  std::ofstream(dir / "moving.nii") << "x";
  std::ofstream(dir / "pair.json") << R"({"anatomical": {"path": "fixed.nii"},
                                         "functional": {"path": "moving.nii"}})";
  std::ofstream(dir / "single.json") << R"({"anatomical": {"path": "fixed.nii"}})";
  BatchStudy s;
  s.id = "p";
  s.study = dir / "pair.json";
  s.task = "register";
  s.options = {{"metric-samples", "5000"}};
  EXPECT_EQ(batchCommand(s, "/w"),
            (Args{"register", "--fixed", (dir / "fixed.nii").string(), "--moving",
                  (dir / "moving.nii").string(), "-o", "/w", "--metric-samples", "5000"}));
  s.study = dir / "single.json";
  try {
    batchCommand(s, "/w");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "single.json").string() +
                                         ": has no functional volume to register (batch study "
                                         "'p')");
  }
}

// A config naming PACS series has no paths to give register: it registers the config itself.
// mvw's own options of the batch run (--cache, time-outs) end every study's command.
TEST(BatchProcess, PacsStudiesAndTheRunsOwnOptions) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "pacs.json")
      << R"({"anatomical": {"pacs": "dicom://ORTHANC@pacs:4242", "study": "1.2", "series": "CT"},
             "functional": {"pacs": "http://pacs:8042/dicom-web", "study": "1.2",
                            "series": "PT", "kind": "pet"}})";
  BatchStudy s;
  s.id = "p";
  s.study = dir / "pacs.json";
  s.task = "register";
  const Args cache{"--cache", "/cache", "--read-timeout", "5"};
  EXPECT_EQ(batchCommand(s, "/w", cache), (Args{"register", (dir / "pacs.json").string(), "-o",
                                                "/w", "--cache", "/cache", "--read-timeout", "5"}));
  s.task = "render";
  s.options = {{"size", "64 64"}};
  EXPECT_EQ(batchCommand(s, "/w", cache),
            (Args{"render", (dir / "pacs.json").string(), "-o", "/w", "--size", "64", "64",
                  "--cache", "/cache", "--read-timeout", "5"}));
  // A config that cannot be read still has a command for failed.json.
  std::ofstream(dir / "bad.json") << "{";
  s.study = dir / "bad.json";
  s.task = "register";
  s.options = {};
  EXPECT_EQ(batchCommandOrPlain(s, "/w", cache),
            (Args{"register", (dir / "bad.json").string(), "-o", "/w", "--cache", "/cache",
                  "--read-timeout", "5"}));
}

TEST(BatchProcess, JobsExecTheExecutableWithStdoutWhereTheTaskWantsIt) {
  const fs::path dir = test::scratchDir();
  BatchStudy stats, render;
  stats.task = "stats";
  render.task = "render";
  const process::ProcessJob statsJob = batchJob(stats, dir / "ws", {"hello", "stats"});
  EXPECT_EQ(statsJob.args, (Args{(dir / "ws" / "stats.json").string(), "hello", "stats"}));
  EXPECT_EQ(statsJob.log, dir / "ws" / "log.txt");
  const process::ProcessJob renderJob = batchJob(render, dir / "wr", {"hello", "render"});
  EXPECT_EQ(renderJob.args, (Args{"", "hello", "render"}));
  fs::create_directories(dir / "ws");
  fs::create_directories(dir / "wr");
  // /bin/echo stands in for mvw: what it prints lands in stats.json, or in the log.
  process::ProcessPool echo(mvwJobFunction("/bin/echo"));
  process::ProcessPool missing(mvwJobFunction(dir / "no-such-mvw"));
  std::vector<int> status(2, -1);
  echo.run({statsJob, renderJob}, 2, 60,
           [&](std::size_t k, const process::ProcessResult& r) { status[k] = r.status; });
  EXPECT_EQ(status, (std::vector<int>{0, 0}));
  EXPECT_EQ(text(dir / "ws" / "stats.json"), "hello stats\n");
  EXPECT_EQ(text(dir / "wr" / "log.txt"), "hello render\n");
  int code = -1;
  missing.run({renderJob}, 1, 60,
              [&](std::size_t, const process::ProcessResult& r) { code = r.status; });
  EXPECT_EQ(code, 127);
  EXPECT_EQ(text(dir / "wr" / "log.txt"), "mvw: error: " + (dir / "no-such-mvw").string() +
                                              " cannot be started: No such file or directory\n");
}

TEST(BatchProcess, FailureMessageIsTheLastErrorAndWhyItWasKilled) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "log.txt") << "loading\nmvw: error: a.nii: is bad\n  \nwriting\n";
  process::ProcessResult r;
  r.status = 2;
  EXPECT_EQ(batchFailureMessage(r, dir / "log.txt", 60), "mvw: error: a.nii: is bad");
  r.status = process::kTimedOut;
  EXPECT_EQ(batchFailureMessage(r, dir / "log.txt", 60),
            "killed after 60 s (the time limit); mvw: error: a.nii: is bad");
  r.status = 128 + 9;
  EXPECT_EQ(batchFailureMessage(r, dir / "log.txt", 60),
            "killed by signal 9; mvw: error: a.nii: is bad");
  std::ofstream(dir / "quiet.txt") << "step 1\nstep 2\n\n";
  r.status = 1;
  EXPECT_EQ(batchFailureMessage(r, dir / "quiet.txt", 60), "step 2");
  EXPECT_EQ(batchFailureMessage(r, dir / "none.txt", 60), "");
  std::ofstream(dir / "long.txt") << "mvw: " << std::string(3000, 'x') << "\n";
  EXPECT_EQ(batchFailureMessage(r, dir / "long.txt", 60), "mvw: " + std::string(1995, 'x') + "...");
}

TEST(BatchFolders, LeftoversOfThisStudyOnlyAreRemoved) {
  const fs::path out = test::scratchDir();
  for (const char* name :
       {".work-a-123", ".old-a-9", ".work-a-b-123", ".work-ab-1", "a", "a-b", ".work-b-5"})
    fs::create_directories(out / name);
  removeLeftovers(out, "a");
  EXPECT_EQ(names(out),
            (std::set<std::string>{".work-a-b-123", ".work-ab-1", "a", "a-b", ".work-b-5"}));
  removeLeftovers(out, "a-b");
  EXPECT_EQ(names(out), (std::set<std::string>{".work-ab-1", "a", "a-b", ".work-b-5"}));
}

TEST(BatchFolders, OneListingFindsEveryStudysLeftovers) {
  const fs::path out = test::scratchDir();
  for (const char* name : {".work-a-123", ".old-a-9", ".work-a-b-123", ".work-ab-1", "a", "a-b",
                           ".work-b-5", ".workers"})
    fs::create_directories(out / name);
  const Leftovers found = findLeftovers(out);
  EXPECT_EQ(found.size(), 4u);
  EXPECT_EQ(found.at("a").size(), 2u);
  EXPECT_EQ(found.at("a-b"), std::vector<fs::path>{out / ".work-a-b-123"});
  removeLeftovers(found, "a");
  removeLeftovers(found, "c");
  EXPECT_EQ(names(out), (std::set<std::string>{".work-a-b-123", ".work-ab-1", "a", "a-b",
                                               ".work-b-5", ".workers"}));
}

TEST(BatchProcess, AFailedStatsRunLeavesNoStatsJson) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "stats.json");
  std::ofstream(dir / "log.txt") << "mvw: error: bad\n";
  BatchStudy render;
  render.task = "render";
  discardFailedOutput(render, dir);
  EXPECT_TRUE(fs::exists(dir / "stats.json"));
  BatchStudy stats;
  stats.task = "stats";
  discardFailedOutput(stats, dir);
  EXPECT_EQ(names(dir), std::set<std::string>{"log.txt"});
}

TEST(BatchFolders, PublishReplacesTheLastResultWhole) {
  const fs::path out = test::scratchDir();
  const fs::path work = workFolder(out, "a");
  EXPECT_EQ(work, out / (".work-a-" + std::to_string(::getpid())));
  fs::create_directories(work);
  std::ofstream(work / "failed.json") << "{}";
  publish(work, out, "a");
  EXPECT_EQ(names(out), std::set<std::string>{"a"});
  EXPECT_EQ(names(out / "a"), std::set<std::string>{"failed.json"});
  fs::create_directories(work);
  std::ofstream(work / "done.json") << "{}";
  publish(work, out, "a");
  // The failed run's marker went with its folder: a folder is one run's.
  EXPECT_EQ(names(out), std::set<std::string>{"a"});
  EXPECT_EQ(names(out / "a"), std::set<std::string>{"done.json"});
}

TEST(BatchProcess, SelfExecutableIsThisTestProgram) {
  EXPECT_EQ(selfExecutable().filename(), "mvw_batch_tests");
}

}  // namespace
}  // namespace mvw::batch
