// The process pool (validate ProcessPool) that runs `mvw validate`'s renderings in parallel:
// exit codes and signals reported, a job past the time limit killed, a missing program an error.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/validate/ProcessPool.h"

namespace mvw::validate {
namespace {

namespace fs = std::filesystem;
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
