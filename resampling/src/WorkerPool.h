#pragma once
// A small fork-join pool for the registration's short parallel loops (a metric evaluation is
// about a millisecond). Unlike an OpenMP team, the calling thread never waits for a worker
// that has not started: it takes chunks itself, and waits only for chunks a worker already
// holds. So a worker that another process keeps off its core (ctest runs two tests at once
// on these 2-core machines) costs a little speed-up, not a stall of a scheduler time slice
// per evaluation. Internal to mvw_resampling.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace mvw::resampling::detail {

class WorkerPool {
 public:
  // threads: how many run a loop in all, the caller included (0: every core).
  explicit WorkerPool(int threads = 0);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  // Calls task(c) once for every c in [0, chunks), spread over the pool; returns when all
  // are done. Not re-entrant: one loop at a time per pool.
  void parallelFor(std::size_t chunks, const std::function<void(std::size_t)>& task);

 private:
  void work();
  // Claims the next chunk of job `generation`; false when that job is over or exhausted.
  bool claim(std::uint32_t generation, std::size_t chunks, std::size_t& chunk);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::uint32_t generation_ = 0;                            // guarded by mutex_
  const std::function<void(std::size_t)>* task_ = nullptr;  // guarded by mutex_
  std::size_t chunks_ = 0;                                  // guarded by mutex_
  std::atomic<std::uint64_t> next_{0};                      // generation << 32 | next chunk
  std::atomic<std::size_t> done_{0};
};

}  // namespace mvw::resampling::detail
