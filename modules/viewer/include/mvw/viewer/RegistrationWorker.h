#pragma once
// The viewer's background registration: one job at a time on a std::jthread, so the window
// keeps drawing while mutual information is maximised. std::jthread requests a stop and
// joins when destroyed: an exception that unwinds the viewer while a job runs (a script whose
// output file cannot be written, say) waits for the job instead of calling std::terminate
// the way a joinable std::thread does.
#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>

#include "mvw/resampling/RigidRegistration.h"

namespace mvw::viewer {

class RegistrationWorker {
 public:
  // The job gets the thread's stop token; a job that cannot be interrupted (registerRigid)
  // ignores it and the destructor waits for it to end.
  using Job = std::function<resampling::RegistrationResult(std::stop_token)>;

  // The job's result, or its error's message when it threw.
  struct Outcome {
    std::optional<resampling::RegistrationResult> result;
    std::string error;
  };

  RegistrationWorker() = default;
  ~RegistrationWorker() = default;  // thread_ (declared last) stops and joins first
  RegistrationWorker(const RegistrationWorker&) = delete;
  RegistrationWorker& operator=(const RegistrationWorker&) = delete;

  // Starts `job` unless one is running; returns whether it started.
  bool start(Job job);
  bool running() const { return running_; }
  double seconds() const;  // since the running job started
  // Once the running job has ended: its outcome (the thread joined), else nothing.
  std::optional<Outcome> finish();

 private:
  bool running_ = false;
  std::atomic<bool> done_{false};
  std::chrono::steady_clock::time_point start_;
  Outcome outcome_;  // written by the worker before done_, read after it
  std::jthread thread_;
};

}  // namespace mvw::viewer
