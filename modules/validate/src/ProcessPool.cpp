#include "mvw/validate/ProcessPool.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "mvw/core/Error.h"

extern char** environ;

namespace mvw::validate {

namespace {

pid_t spawn(const ProcessJob& job) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, job.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<std::string> args = job.argv;
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args.at(0).c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw Error("cannot start " + args.at(0) + ": " + std::strerror(rc));
  return pid;
}

struct Running {
  pid_t pid;
  std::size_t job;
  std::chrono::steady_clock::time_point start;
};

// Kills and reaps what still runs when the pool is left by an exception.
struct Reaper {
  std::vector<Running>& running;
  ~Reaper() {
    for (const Running& r : running) {
      ::kill(r.pid, SIGKILL);
      int status = 0;
      ::waitpid(r.pid, &status, 0);
    }
  }
};

}  // namespace

void runProcesses(const std::vector<ProcessJob>& jobs, int parallel, double timeoutS,
                  const std::function<void(std::size_t, const ProcessResult&)>& onDone) {
  std::vector<Running> running;
  Reaper reaper{running};
  std::size_t next = 0;
  while (next < jobs.size() || !running.empty()) {
    while (static_cast<int>(running.size()) < parallel && next < jobs.size()) {
      running.push_back({spawn(jobs[next]), next, std::chrono::steady_clock::now()});
      ++next;
    }
    bool reaped = false;
    for (auto it = running.begin(); it != running.end();) {
      int status = 0;
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - it->start).count();
      pid_t got = ::waitpid(it->pid, &status, WNOHANG);
      ProcessResult result;
      if (got == 0 && seconds > timeoutS) {
        ::kill(it->pid, SIGKILL);
        ::waitpid(it->pid, &status, 0);
        result.status = kTimedOut;
        got = it->pid;
      } else if (got == it->pid) {
        result.status = WIFEXITED(status) ? WEXITSTATUS(status)
                                          : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
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
      onDone(job, result);
    }
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace mvw::validate
