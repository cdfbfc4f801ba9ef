#include "mvw/process/Helper.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <thread>

#include "mvw/core/Error.h"
#include "mvw/process/ProcessPool.h"
#include "mvw/process/Wire.h"

extern char** environ;

namespace mvw::process {

namespace {

constexpr int kHelperFd = 3;

std::string errorText(int error) { return std::strerror(error); }

// The address space `pid` has mapped (VmSize, bytes); 0 when it cannot be read.
std::uint64_t mappedBytes(pid_t pid) {
  std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

struct FileActions {
  posix_spawn_file_actions_t actions;
  FileActions() { posix_spawn_file_actions_init(&actions); }
  ~FileActions() { posix_spawn_file_actions_destroy(&actions); }
};

}  // namespace

HelperProcess::HelperProcess(const std::filesystem::path& exe, const std::vector<std::string>& args,
                             const HelperLimits& limits, bool inheritStderr)
    : limits_(limits) {
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0)
    throw Error("cannot make a socket for " + exe.string() + ": " + errorText(errno));
  // The child's end must not already be fd 3: dup2 onto itself would keep its close-on-exec.
  if (ends[1] == kHelperFd) {
    const int moved = ::fcntl(ends[1], F_DUPFD_CLOEXEC, kHelperFd + 1);
    ::close(ends[1]);
    ends[1] = moved;
  }
  FileActions fa;
  posix_spawn_file_actions_addopen(&fa.actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa.actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  if (!inheritStderr)
    posix_spawn_file_actions_addopen(&fa.actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&fa.actions, ends[1], kHelperFd);
  posix_spawn_file_actions_addclosefrom_np(&fa.actions, kHelperFd + 1);
  std::vector<std::string> argvText;
  argvText.push_back(exe.string());
  argvText.insert(argvText.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argvText) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int error = ::posix_spawn(&pid, exe.c_str(), &fa.actions, nullptr, argv.data(), environ);
  ::close(ends[1]);
  if (error != 0) {
    ::close(ends[0]);
    throw Error("cannot start " + exe.string() + ": " + errorText(error));
  }
  pid_ = pid;
  socket_ = ends[0];
  deadline_ = std::chrono::steady_clock::now() +
              std::chrono::milliseconds(static_cast<long long>(limits.seconds * 1000.0));
}

HelperProcess::~HelperProcess() {
  if (socket_ >= 0) ::close(socket_);
  kill();
}

bool HelperProcess::started() {
  char ready = 0;
  if (!receiveAllBy(socket_, &ready, 1, deadline_)) return false;
  const std::uint64_t size = mappedBytes(pid_);
  if (size == 0) return false;  // it ended (its /proc entry is gone)
  // Lowered, never raised: a limit the caller already runs under (ulimit -v) stays.
  auto lower = [&](__rlimit_resource resource, rlim_t value) {
    struct rlimit now {};
    if (::prlimit(pid_, resource, nullptr, &now) != 0) return false;
    struct rlimit limit {};
    limit.rlim_max = now.rlim_max == RLIM_INFINITY ? value : std::min(now.rlim_max, value);
    limit.rlim_cur = limit.rlim_max;
    if (resource == RLIMIT_CPU && limit.rlim_cur > 1) --limit.rlim_cur;  // SIGXCPU, then SIGKILL
    return ::prlimit(pid_, resource, &limit, nullptr) == 0;
  };
  if (!lower(RLIMIT_AS, static_cast<rlim_t>(size + limits_.memoryBytes)) ||
      !lower(RLIMIT_CPU, static_cast<rlim_t>(std::ceil(limits_.seconds)) + 1) ||
      !lower(RLIMIT_CORE, 0)) {
    const int error = errno;
    if (error == ESRCH) return false;
    throw Error("cannot limit the memory and time of a helper process: " + errorText(error));
  }
  return true;
}

int HelperProcess::wait() {
  if (pid_ < 0) return status_;
  for (;;) {
    int status = 0;
    const pid_t got = ::waitpid(pid_, &status, WNOHANG);
    if (got == pid_) {
      status_ = WIFEXITED(status) ? WEXITSTATUS(status)
                                  : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
      pid_ = -1;
      return status_;
    }
    if (got < 0 && errno != EINTR) {  // reaped by someone else (SIGCHLD ignored)
      pid_ = -1;
      status_ = 0;
      return status_;
    }
    if (std::chrono::steady_clock::now() >= deadline_) {
      kill();
      status_ = kTimedOut;
      return status_;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void HelperProcess::kill() {
  if (pid_ < 0) return;
  ::kill(pid_, SIGKILL);
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

int helperSocket() {
  struct stat st {};
  if (::fstat(kHelperFd, &st) != 0 || !S_ISSOCK(st.st_mode)) return -1;
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() == 1) ::_exit(1);  // the caller died before this line
  const char ready = 1;
  if (!sendAll(kHelperFd, &ready, 1)) ::_exit(1);
  return kHelperFd;
}

}  // namespace mvw::process
