#pragma once
// A helper executable of mvw run as a child process with limits, talking over a socket: what a
// fault in it does (a decoder writing past its buffer, a loop, a memory blow-up) ends that
// process, not the caller, which may hold the user's work (the viewer, a Python session). The
// child is started with posix_spawn (no fork of the caller: its threads and locks are not
// half-copied, and a large caller is not duplicated), its fd 3 one end of a socket, stdin,
// stdout and stderr /dev/null (stderr the caller's when asked), every other descriptor closed.
// The caller limits it from outside, once it has said it started (its libraries loaded, a
// sanitizer's shadow memory mapped): RLIMIT_AS its present size plus a budget, RLIMIT_CPU, no
// core file; and kills it at a wall-clock deadline. Nothing it sends is trusted: the caller
// sizes and checks what it receives.
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace mvw::process {

struct HelperLimits {
  std::uint64_t memoryBytes = 0;  // address space it may map beyond its size at start
  double seconds = 60.0;          // wall clock from its start; CPU seconds as well
};

class HelperProcess {
 public:
  // Starts `exe` with `args` (argv[1]...). Throws mvw::Error when it cannot be started.
  HelperProcess(const std::filesystem::path& exe, const std::vector<std::string>& args,
                const HelperLimits& limits, bool inheritStderr);
  // Kills (SIGKILL) and reaps it if it still runs.
  ~HelperProcess();
  HelperProcess(const HelperProcess&) = delete;
  HelperProcess& operator=(const HelperProcess&) = delete;

  // Waits (to the deadline) for its first byte, which says it has started, then applies the
  // limits. False when it ended first; throws WireTimeout (Wire.h) past the deadline; throws
  // mvw::Error when the limits cannot be set.
  bool started();

  int socket() const { return socket_; }
  std::chrono::steady_clock::time_point deadline() const { return deadline_; }

  // Waits for it to end, to the deadline, then kills it. Its exit status; 128 + N when killed
  // by signal N; kTimedOut (124, ProcessPool.h) when killed at the deadline.
  int wait();
  // Kills it now (SIGKILL) and reaps it.
  void kill();

 private:
  pid_t pid_ = -1;
  int socket_ = -1;
  HelperLimits limits_;
  std::chrono::steady_clock::time_point deadline_;
  int status_ = -1;
};

// In the helper: the caller's end of the socket (fd 3), after saying it has started. The helper
// dies with its caller (PR_SET_PDEATHSIG). -1 when fd 3 is not a socket (not started by
// HelperProcess).
int helperSocket();

}  // namespace mvw::process
