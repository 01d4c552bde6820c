#pragma once
/// \file Work beside the caller's thread, where there are threads. The desktop runs pins, the
/// Monte Carlo and the timeline's replays on threads of their own; the browser page (a
/// WebAssembly build without threads, so that it opens from any web server or folder) runs the
/// same work at once on the caller's thread, which then waits for it. Results are the same:
/// they never depend on the number of threads.

#include <functional>
#include <future>
#include <thread>
#include <type_traits>
#include <utility>

namespace formsim::sim {

/// Whether this build can start threads (false in the browser page).
#ifdef __EMSCRIPTEN__
inline constexpr bool kHaveThreads = false;
#else
inline constexpr bool kHaveThreads = true;
#endif

/// `requested` workers (at least 1), or 1 where there are no threads.
inline int UsableThreads(int requested) {
  if (!kHaveThreads || requested < 1) return 1;
  return requested;
}

/// Runs `fn` on a thread of its own (std::async), or, without threads, now; either way the
/// future holds its result or exception.
template <class F>
std::future<std::invoke_result_t<std::decay_t<F>>> StartBackground(F&& fn) {
  using R = std::invoke_result_t<std::decay_t<F>>;
  if constexpr (kHaveThreads) {
    return std::async(std::launch::async, std::forward<F>(fn));
  } else {
    std::packaged_task<R()> task(std::forward<F>(fn));
    std::future<R> done = task.get_future();
    task();
    return done;
  }
}

/// A thread that is joined when the object goes (or Join is called); without threads, `fn` runs
/// in the constructor.
class BackgroundThread {
 public:
  BackgroundThread() = default;
  explicit BackgroundThread(std::function<void()> fn) {
    if constexpr (kHaveThreads)
      thread_ = std::thread(std::move(fn));
    else
      fn();
  }
  ~BackgroundThread() { Join(); }
  BackgroundThread(BackgroundThread&&) = default;
  BackgroundThread& operator=(BackgroundThread&& other) {
    Join();
    thread_ = std::move(other.thread_);
    return *this;
  }
  void Join() {
    if (thread_.joinable()) thread_.join();
  }

 private:
  std::thread thread_;
};

}  // namespace formsim::sim
