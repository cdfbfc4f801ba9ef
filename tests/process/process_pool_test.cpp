// The process pool (process ProcessPool) that runs `mvw validate`'s renderings and `mvw batch`'s
// studies in parallel, each a call of its function in a forked child: exit codes and signals
// reported, exceptions ended as mvw's main ends them, a job past the time limit killed, the
// launcher a copy of the caller as it was when the pool was made, and running jobs killed when
// the caller's callback throws.
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/process/ProcessPool.h"

namespace mvw::process {
namespace {

namespace fs = std::filesystem;

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
  if (what == "server") throw ServiceError("dicom://PACS@127.0.0.1:9: connection refused");
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
  const std::vector<std::string> kinds = {"exit3", "sleep",    "kill",  "input",
                                          "fault", "buffered", "server"};
  std::vector<ProcessJob> jobs;
  for (const std::string& k : kinds) jobs.push_back({{k}, dir / (k + ".log")});
  std::vector<ProcessResult> results(jobs.size());
  int calls = 0;
  pool.run(jobs, 2, 1.0, [&](std::size_t j, const ProcessResult& r) {
    results[j] = r;
    ++calls;
  });
  EXPECT_EQ(calls, 7);
  EXPECT_EQ(results[0].status, 3);
  EXPECT_EQ(firstLine(dir / "exit3.log"), "out");
  EXPECT_EQ(results[1].status, kTimedOut);
  EXPECT_LT(results[1].seconds, 10.0);
  EXPECT_EQ(results[2].status, 128 + 9);
  // Exceptions end the child as mvw's main ends mvw (exitCodeOf): 3 for a server that failed, 2
  // for bad input, 1 for a fault.
  EXPECT_EQ(results[3].status, 2);
  EXPECT_EQ(firstLine(dir / "input.log"), "mvw: error: bad.json: is bad");
  EXPECT_EQ(results[4].status, 1);
  EXPECT_EQ(firstLine(dir / "fault.log"), "mvw: internal error: it broke");
  EXPECT_EQ(results[5].status, 0);
  EXPECT_EQ(firstLine(dir / "buffered.log"), "left in the buffer");
  EXPECT_EQ(results[6].status, 3);
  EXPECT_EQ(firstLine(dir / "server.log"),
            "mvw: error: dicom://PACS@127.0.0.1:9: connection refused");
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

}  // namespace
}  // namespace mvw::process
