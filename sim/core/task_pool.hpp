#pragma once
/// \file A small pool of worker threads for independent tasks (the runs of a sweep, the seeds
/// of one tuning evaluation). The workers live as long as the pool; ForEach hands out indices
/// 0..n-1, each exactly once, and returns when every started task has finished. Results are
/// whatever the tasks write into their own slots, so they never depend on the number of
/// threads or on the order of completion.

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace formsim::sim {

class TaskPool {
 public:
  /// `threads` >= 1 workers in total; the calling thread of ForEach is one of them, so 1 means
  /// no extra thread at all.
  explicit TaskPool(int threads);
  ~TaskPool();
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  /// Runs `task(i)` for i = 0..n-1 on the workers and the calling thread. Indices are handed
  /// out in increasing order; once `stop()` returns true no further index is started. When a
  /// task throws, no further index is started and the first exception is rethrown here after
  /// the running tasks have finished. Not reentrant.
  void ForEach(std::size_t n, const std::function<void(std::size_t)>& task,
               const std::function<bool()>& stop = {});

  /// The number of hardware threads (at least 1).
  static int HardwareThreads();

 private:
  void WorkerLoop();
  void Drain();  ///< takes indices of the current batch until none are left

  std::vector<std::thread> workers_;
  std::mutex mu_;
  std::condition_variable wake_, idle_;
  bool quit_ = false;
  unsigned long generation_ = 0;  ///< bumped by each ForEach
  int busy_ = 0;                  ///< workers inside the current batch
  // The current batch (guarded by mu_).
  std::size_t next_ = 0, count_ = 0;
  const std::function<void(std::size_t)>* task_ = nullptr;
  const std::function<bool()>* stop_ = nullptr;
  std::exception_ptr error_;
};

}  // namespace formsim::sim
