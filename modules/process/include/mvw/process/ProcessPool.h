#pragma once
// Jobs run in child processes, N at a time, each with its stdout and stderr in a log file,
// stdin from /dev/null and a wall-clock limit: a crash or hang in one job is that job's
// failure, not the caller's. The validator renders every case so, and `mvw batch` runs every
// study so (its function execs mvw).
//
// A job is a call of the pool's function in a forked child, not a program: the pool never
// starts an executable of its own. The children are forked by a launcher process that the
// pool forks when it is made, so each starts as a copy of the caller as it was then, with one
// thread: a thread pool or lock that the caller starts afterwards (OpenCV's and VTK's TBB
// workers, a GL driver's threads) is not half-copied into the jobs. Make the pool before
// starting threads whose state the function needs.
#include <sys/types.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace mvw::process {

// What a job runs, in its child: its arguments in, its exit code out. An exception that
// leaves it ends the child as mvw's main does (mvw::exitCodeOf, mvw/core/ExitCode.h): its
// message on stderr ("mvw: error: ..."), exit 3 for a server that failed, 2 for bad input, 1
// for anything else.
using JobFunction = std::function<int(const std::vector<std::string>& args)>;

struct ProcessJob {
  std::vector<std::string> args;  // handed to the pool's function
  std::filesystem::path log;      // stdout + stderr
};

struct ProcessResult {
  int status = -1;  // the exit code; 124: killed at the time limit; 128 + N: killed by signal N
  double seconds = 0.0;
};

constexpr int kTimedOut = 124;

class ProcessPool {
 public:
  // Forks the launcher. Throws mvw::Error if it cannot.
  explicit ProcessPool(JobFunction function);
  // Ends the launcher, which kills and reaps any job still running.
  ~ProcessPool();
  ProcessPool(const ProcessPool&) = delete;
  ProcessPool& operator=(const ProcessPool&) = delete;

  // Runs every job, at most `parallel` at once, killing any that runs past `timeoutS`. onDone
  // is called in the calling thread as each job ends (in the order they end) while the others
  // go on. Throws mvw::Error if a job cannot be started (its log cannot be written, no process
  // can be forked); the jobs running then are killed and reaped first, as they are when onDone
  // throws.
  void run(const std::vector<ProcessJob>& jobs, int parallel, double timeoutS,
           const std::function<void(std::size_t job, const ProcessResult&)>& onDone);

 private:
  pid_t launcher_ = -1;
  int socket_ = -1;  // to the launcher: jobs out, results back
};

// Runs `body` in a forked child of this process, its output where this process's goes, and
// returns the child's exit code as ProcessResult::status gives it; the child ends as a job does
// (an exception: its message on stderr, mvw::exitCodeOf's code). For what must not happen in
// this process (`mvw validate` makes its probe GL context so, as the renders are forked from it).
int runInChild(const std::function<void()>& body);

}  // namespace mvw::process
