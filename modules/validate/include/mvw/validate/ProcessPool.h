#pragma once
// Child processes run N at a time, each with its stdout and stderr in a log file, stdin from
// /dev/null and a wall-clock limit. The validator renders every case through `mvw render` so:
// a crash or hang in one case is that case's failure, not the suite's.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace mvw::validate {

struct ProcessJob {
  std::vector<std::string> argv;  // argv[0]: the executable's path
  std::filesystem::path log;      // stdout + stderr
};

struct ProcessResult {
  int status = -1;  // the exit code; 124: killed at the time limit; 128 + N: killed by signal N
  double seconds = 0.0;
};

constexpr int kTimedOut = 124;

// Runs every job, at most `parallel` at once, killing any that runs past `timeoutS`. onDone is
// called in the calling thread as each job ends (in the order they end). Throws mvw::Error if a
// process cannot be started; the ones running then are killed and reaped first.
void runProcesses(const std::vector<ProcessJob>& jobs, int parallel, double timeoutS,
                  const std::function<void(std::size_t job, const ProcessResult&)>& onDone);

}  // namespace mvw::validate
