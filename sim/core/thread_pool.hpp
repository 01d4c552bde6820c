#pragma once
/// \file A small pool of worker threads for the independent work inside one simulation step
/// (link filters and sensors, recorder channels, CSV text): `ParallelFor(n, fn)` calls
/// fn(begin, end) on disjoint ranges covering [0, n) and returns when all are done; the calling
/// thread works too. Results never depend on the number of threads as long as each index writes
/// only its own data (no shared sums): that is the contract for every caller.
///
/// Latency matters more than throughput here (a 1000-robot step is about a millisecond, with two
/// or three parallel sections): workers spin briefly for the next section before they sleep, and
/// ranges are handed out dynamically in small chunks, so a thread descheduled by the OS does not
/// hold the others up. With one thread, or too little work for two, the caller runs everything
/// inline (no synchronisation at all).
///
/// A pool runs one ParallelFor at a time; a second caller (another thread, or a nested call from
/// inside a task) runs its loop inline instead of waiting. Distinct from sim/core/task_pool.hpp
/// (whole runs of a sweep).

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace formsim::sim {

class ThreadPool {
 public:
  /// A pool of `threads` threads in all, the caller included (so threads - 1 workers); values
  /// below 1 mean 1. The workers start with the first ParallelFor that needs them.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// Threads that work on a ParallelFor, the caller included.
  int threads() const { return threads_; }

  /// Calls fn(begin, end) for disjoint ranges covering [0, n), each of at least `grain` indices
  /// (except the last), on the pool's threads; returns when every range is done. An exception
  /// thrown by fn is rethrown here (the first one; the other ranges still run).
  template <class F>
  void ParallelFor(std::size_t n, F&& fn, std::size_t grain = 1) {
    if (n == 0) return;
    if (grain < 1) grain = 1;
    if (threads_ < 2 || n < 2 * grain || busy_.exchange(true)) {
      fn(std::size_t{0}, n);
      return;
    }
    RunTaken(n, grain, fn, nullptr, nullptr);
  }

  /// Runs `side()` on the calling thread while the other threads start on fn's ranges of
  /// [0, n); once side() returns the caller takes ranges too; returns when all are done. For
  /// work that is independent of side's (the estimators' time updates beside the Box2D step,
  /// which only the caller may run). With one thread, or while the pool is busy, side() then
  /// fn(0, n) inline. An exception from side() or fn is rethrown after everything finished.
  template <class S, class F>
  void ParallelForBeside(S&& side, std::size_t n, F&& fn, std::size_t grain = 1) {
    if (grain < 1) grain = 1;
    if (threads_ < 2 || n == 0 || busy_.exchange(true)) {
      side();
      if (n > 0) fn(std::size_t{0}, n);
      return;
    }
    using Side = std::remove_reference_t<S>;
    RunTaken(
        n, grain, fn, [](void* ctx) { (*static_cast<Side*>(ctx))(); },
        const_cast<void*>(static_cast<const void*>(std::addressof(side))));
  }

  /// Threads of this machine (std::thread::hardware_concurrency, at least 1).
  static int HardwareThreads();
  /// The number of threads a new experiment uses (the CLI's --threads; default: all cores).
  static int DefaultThreads();
  static void SetDefaultThreads(int threads);

 private:
  using Body = void (*)(void*, std::size_t, std::size_t);
  using SideFn = void (*)(void*);
  // Runs fn's job on the pool once the caller has taken busy_, and gives busy_ back however
  // it ends.
  template <class F>
  void RunTaken(std::size_t n, std::size_t grain, F& fn, SideFn side, void* side_ctx) {
    struct Release {
      std::atomic<bool>& busy;
      ~Release() { busy = false; }
    } release{busy_};
    using Fn = std::remove_reference_t<F>;
    Run(
        n, grain, [](void* ctx, std::size_t b, std::size_t e) { (*static_cast<Fn*>(ctx))(b, e); },
        const_cast<void*>(static_cast<const void*>(std::addressof(fn))), side, side_ctx);
  }
  // Publishes the job, runs `side` (if any) on this thread, then works on the job with the
  // workers until it is done.
  void Run(std::size_t n, std::size_t grain, Body body, void* ctx, SideFn side, void* side_ctx);
  void WorkerLoop();
  // Takes chunks of the current job until none is left.
  void Work();

  int threads_ = 1;
  std::vector<std::thread> workers_;
  std::atomic<bool> busy_{false};  ///< a ParallelFor is running

  // The current job. Workers join it only while it is open (under job_mutex_), so once the
  // caller has closed it and seen active_ fall to 0 nobody reads these fields any more.
  std::mutex job_mutex_;
  bool job_open_ = false;
  Body body_ = nullptr;
  void* ctx_ = nullptr;
  std::size_t n_ = 0, chunk_ = 1;
  std::atomic<std::size_t> next_{0};  ///< first index not yet handed out
  std::atomic<int> active_{0};        ///< workers inside Work()
  std::exception_ptr error_;
  std::mutex error_mutex_;

  // Waking the workers: a generation count they watch (spinning first, then sleeping).
  std::atomic<unsigned> generation_{0};
  std::atomic<bool> stop_{false};
  std::mutex wake_mutex_;
  std::condition_variable wake_;
  std::atomic<int> sleeping_{0};
};

}  // namespace formsim::sim
