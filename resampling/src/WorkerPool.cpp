#include "WorkerPool.h"

#include <algorithm>

namespace mvw::resampling::detail {

WorkerPool::WorkerPool(int threads) {
  const int n =
      threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 1; i < n; ++i) workers_.emplace_back([this] { work(); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

bool WorkerPool::claim(std::uint32_t generation, std::size_t chunks, std::size_t& chunk) {
  std::uint64_t state = next_.load(std::memory_order_acquire);
  for (;;) {
    if (static_cast<std::uint32_t>(state >> 32) != generation) return false;
    chunk = static_cast<std::size_t>(state & 0xffffffffu);
    if (chunk >= chunks) return false;
    if (next_.compare_exchange_weak(state, state + 1, std::memory_order_acq_rel)) return true;
  }
}

void WorkerPool::work() {
  std::uint32_t seen = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    // Copied under the lock: a chunk claimed below belongs to this job, and the caller's
    // task outlives every claimed chunk (parallelFor returns only when all are done).
    const auto* task = task_;
    const std::size_t chunks = chunks_;
    lock.unlock();
    std::size_t chunk;
    while (claim(seen, chunks, chunk)) {
      (*task)(chunk);
      done_.fetch_add(1, std::memory_order_acq_rel);
    }
    lock.lock();
  }
}

void WorkerPool::parallelFor(std::size_t chunks, const std::function<void(std::size_t)>& task) {
  if (chunks == 0) return;
  std::uint32_t generation;
  {
    std::lock_guard lock(mutex_);
    generation = ++generation_;
    task_ = &task;
    chunks_ = chunks;
    done_.store(0, std::memory_order_relaxed);
    next_.store(static_cast<std::uint64_t>(generation) << 32, std::memory_order_release);
  }
  if (!workers_.empty()) wake_.notify_all();
  std::size_t chunk;
  while (claim(generation, chunks, chunk)) {
    task(chunk);
    done_.fetch_add(1, std::memory_order_acq_rel);
  }
  // Only chunks a worker is running remain: a few tens of microseconds.
  while (done_.load(std::memory_order_acquire) < chunks) std::this_thread::yield();
}

}  // namespace mvw::resampling::detail
