#include "mvw/viewer/RegistrationWorker.h"

#include <exception>
#include <utility>

namespace mvw::viewer {

bool RegistrationWorker::start(Job job) {
  if (running_) return false;
  running_ = true;
  done_ = false;
  outcome_ = {};
  start_ = std::chrono::steady_clock::now();
  thread_ = std::jthread([this, job = std::move(job)](std::stop_token stop) {
    try {
      outcome_.result = job(stop);
    } catch (const std::exception& e) {
      outcome_.error = e.what();
    } catch (...) {
      outcome_.error = "unknown error";
    }
    done_ = true;
  });
  return true;
}

double RegistrationWorker::seconds() const {
  if (!running_) return 0.0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::optional<RegistrationWorker::Outcome> RegistrationWorker::finish() {
  if (!running_ || !done_) return std::nullopt;
  thread_.join();
  running_ = false;
  return std::exchange(outcome_, {});
}

}  // namespace mvw::viewer
