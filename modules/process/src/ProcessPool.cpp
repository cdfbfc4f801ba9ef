#include "mvw/process/ProcessPool.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "mvw/core/Error.h"
#include "mvw/core/ExitCode.h"
#include "mvw/process/Wire.h"

namespace mvw::process {

namespace {

// ---------------------------------------------------------------------------------------
// The child's end: the exit code and message mvw's main would give (mvw/core/ExitCode.h).

[[noreturn]] void endChild(const std::function<int()>& body) {
  const int code = runReportingErrors(body, std::cerr);
  // _exit: no atexit handlers or static destructors of the copied process run twice.
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  ::_exit(code);
}

int statusOf(int waitStatus) {
  return WIFEXITED(waitStatus) ? WEXITSTATUS(waitStatus)
                               : 128 + (WIFSIGNALED(waitStatus) ? WTERMSIG(waitStatus) : 0);
}

// What is buffered for stdout is written now, not once more by each copy of this process.
void flushBeforeFork() {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
}

// ---------------------------------------------------------------------------------------
// The socket between the pool and its launcher: the jobs of a run out, their results back.

struct Batch {
  int parallel = 1;
  double timeoutS = 0.0;
  std::vector<ProcessJob> jobs;
};

bool sendBatch(int fd, const std::vector<ProcessJob>& jobs, int parallel, double timeoutS) {
  Message m;
  m.put(static_cast<std::int32_t>(parallel));
  m.put(timeoutS);
  m.put(static_cast<std::uint64_t>(jobs.size()));
  for (const ProcessJob& j : jobs) {
    m.put(static_cast<std::uint64_t>(j.args.size()));
    for (const std::string& a : j.args) m.put(a);
    m.put(j.log.string());
  }
  return m.send(fd);
}

// False at the end of the stream: the pool is gone.
bool receiveBatch(int fd, Batch& b) {
  std::int32_t parallel = 1;
  std::uint64_t count = 0;
  if (!receive(fd, parallel) || !receive(fd, b.timeoutS) || !receive(fd, count)) return false;
  b.parallel = std::max(1, static_cast<int>(parallel));
  b.jobs.resize(count);
  for (ProcessJob& j : b.jobs) {
    std::uint64_t args = 0;
    std::string log;
    if (!receive(fd, args)) return false;
    j.args.resize(args);
    for (std::string& a : j.args)
      if (!receive(fd, a)) return false;
    if (!receive(fd, log)) return false;
    j.log = log;
  }
  return true;
}

// What the launcher says: a job ended, the run is over, or it could not go on (the message).
enum class Kind : std::uint8_t { JobEnded, RunOver, Failed };

bool sendRecord(int fd, Kind kind, std::uint64_t job, const ProcessResult& result,
                const std::string& message = {}) {
  Message m;
  m.put(kind);
  m.put(job);
  m.put(static_cast<std::int32_t>(result.status));
  m.put(result.seconds);
  m.put(message);
  return m.send(fd);
}

// ---------------------------------------------------------------------------------------
// The launcher: forked when the pool is made, it forks the jobs and times them.

// The pool closed its end while jobs ran (it was left by an exception, or its process ended).
struct Cancelled {};

pid_t startJob(const ProcessJob& job, const JobFunction& function, int socket) {
  const int log = ::open(job.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0)
    throw Error("cannot write the log " + job.log.string() + ": " + std::strerror(errno));
  const int null = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const pid_t pid = null < 0 ? -1 : ::fork();
  if (pid == 0) {
    ::close(socket);
    // dup2 leaves the new descriptors open across nothing but this process: no exec follows.
    ::dup2(null, STDIN_FILENO);
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::close(null);
    ::close(log);
    endChild([&] { return function(job.args); });
  }
  const int error = errno;
  ::close(log);
  if (null >= 0) ::close(null);
  if (pid < 0) throw Error(std::string("cannot start a process: ") + std::strerror(error));
  return pid;
}

struct Running {
  pid_t pid;
  std::size_t job;
  std::chrono::steady_clock::time_point start;
};

// Kills and reaps what still runs when a run is left by an exception.
struct Reaper {
  std::vector<Running>& running;
  ~Reaper() {
    for (const Running& r : running) {
      ::kill(r.pid, SIGKILL);
      int status = 0;
      while (::waitpid(r.pid, &status, 0) < 0 && errno == EINTR) {
      }
    }
  }
};

// Sleeps up to `ms`, unless the pool's end of the socket closes (or says anything: it says
// nothing while a run goes on), which cancels the run.
void waitOrCancel(int socket, int ms) {
  pollfd p{socket, POLLIN, 0};
  const int n = ::poll(&p, 1, ms);
  if (n > 0 && (p.revents & (POLLIN | POLLHUP | POLLERR)) != 0) throw Cancelled{};
}

void runBatch(const Batch& b, const JobFunction& function, int socket) {
  std::vector<Running> running;
  Reaper reaper{running};
  std::size_t next = 0;
  while (next < b.jobs.size() || !running.empty()) {
    while (static_cast<int>(running.size()) < b.parallel && next < b.jobs.size()) {
      running.push_back(
          {startJob(b.jobs[next], function, socket), next, std::chrono::steady_clock::now()});
      ++next;
    }
    bool reaped = false;
    for (auto it = running.begin(); it != running.end();) {
      int status = 0;
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - it->start).count();
      pid_t got = ::waitpid(it->pid, &status, WNOHANG);
      ProcessResult result;
      if (got == 0 && seconds > b.timeoutS) {
        ::kill(it->pid, SIGKILL);
        while (::waitpid(it->pid, &status, 0) < 0 && errno == EINTR) {
        }
        result.status = kTimedOut;
        got = it->pid;
      } else if (got == it->pid) {
        result.status = statusOf(status);
      } else if (got < 0 && errno == EINTR) {
        got = 0;  // asked again on the next round
      } else if (got < 0) {
        result.status = 1;
        got = it->pid;
      }
      if (got == 0) {
        ++it;
        continue;
      }
      result.seconds = seconds;
      reaped = true;
      const std::size_t job = it->job;
      it = running.erase(it);
      if (!sendRecord(socket, Kind::JobEnded, job, result)) throw Cancelled{};
    }
    if (!reaped) waitOrCancel(socket, 20);
  }
}

[[noreturn]] void launcherMain(int socket, const JobFunction& function) {
  // Its own signal handling: what the caller installed (a SIGCHLD handler) is not for it.
  ::signal(SIGCHLD, SIG_DFL);
  ::signal(SIGPIPE, SIG_DFL);
  int code = 0;
  try {
    Batch b;
    while (receiveBatch(socket, b)) {
      runBatch(b, function, socket);
      if (!sendRecord(socket, Kind::RunOver, 0, {})) break;
    }
  } catch (const Cancelled&) {
  } catch (const std::exception& e) {
    sendRecord(socket, Kind::Failed, 0, {}, e.what());
    code = 1;
  } catch (...) {
    code = 1;
  }
  ::_exit(code);
}

}  // namespace

ProcessPool::ProcessPool(JobFunction function) {
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0)
    throw Error(std::string("cannot make the process launcher's socket: ") + std::strerror(errno));
  flushBeforeFork();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ends[0]);
    launcherMain(ends[1], function);
  }
  const int error = errno;
  ::close(ends[1]);
  if (pid < 0) {
    ::close(ends[0]);
    throw Error(std::string("cannot start the process launcher: ") + std::strerror(error));
  }
  launcher_ = pid;
  socket_ = ends[0];
}

ProcessPool::~ProcessPool() {
  if (socket_ >= 0) ::close(socket_);  // the launcher sees the end, kills its jobs and exits
  int status = 0;
  if (launcher_ > 0)
    while (::waitpid(launcher_, &status, 0) < 0 && errno == EINTR) {
    }
}

void ProcessPool::run(const std::vector<ProcessJob>& jobs, int parallel, double timeoutS,
                      const std::function<void(std::size_t, const ProcessResult&)>& onDone) {
  if (socket_ < 0) throw Error("the process pool was closed by an earlier failure");
  try {
    if (!sendBatch(socket_, jobs, parallel, timeoutS))
      throw Error("the process launcher ended unexpectedly");
    for (;;) {
      Kind kind{};
      std::uint64_t job = 0;
      std::int32_t status = 0;
      ProcessResult result;
      std::string message;
      if (!receive(socket_, kind) || !receive(socket_, job) || !receive(socket_, status) ||
          !receive(socket_, result.seconds) || !receive(socket_, message))
        throw Error("the process launcher ended unexpectedly");
      result.status = status;
      if (kind == Kind::RunOver) return;
      if (kind == Kind::Failed) throw Error(message);
      onDone(static_cast<std::size_t>(job), result);
    }
  } catch (...) {
    // The launcher kills and reaps the jobs still running when its socket closes.
    ::close(socket_);
    socket_ = -1;
    int s = 0;
    while (::waitpid(launcher_, &s, 0) < 0 && errno == EINTR) {
    }
    launcher_ = -1;
    throw;
  }
}

int runInChild(const std::function<void()>& body) {
  flushBeforeFork();
  const pid_t pid = ::fork();
  if (pid < 0) throw Error(std::string("cannot start a process: ") + std::strerror(errno));
  if (pid == 0)
    endChild([&] {
      body();
      return 0;
    });
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw Error(std::string("cannot wait for a process: ") + std::strerror(errno));
  return statusOf(status);
}

}  // namespace mvw::process
