#include "GlThread.h"

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

namespace mvw::python {

namespace {

class GlThread {
 public:
  GlThread() : thread_([this] { run(); }) { thread_.detach(); }

  void call(const std::function<void()>& work) {
    Job job{&work, {}, false};
    {
      std::lock_guard lock(mutex_);
      queue_.push_back(&job);
    }
    wake_.notify_all();
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&job] { return job.done; });
    if (job.error) std::rethrow_exception(job.error);
  }

 private:
  struct Job {
    const std::function<void()>* work;
    std::exception_ptr error;
    bool done = false;
  };

  void run() {
    for (;;) {
      Job* job = nullptr;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return !queue_.empty(); });
        job = queue_.front();
        queue_.pop_front();
      }
      try {
        (*job->work)();
      } catch (...) {
        job->error = std::current_exception();
      }
      {
        std::lock_guard lock(mutex_);
        job->done = true;
      }
      done_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::deque<Job*> queue_;
  std::thread thread_;
};

}  // namespace

void onGlThread(const std::function<void()>& work) {
  // Made at the first render and never destroyed: it waits for work until the process ends
  // (a static's destructor at exit would join a thread that never returns).
  static GlThread* const thread = new GlThread();
  thread->call(work);
}

}  // namespace mvw::python
