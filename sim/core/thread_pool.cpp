#include "sim/core/thread_pool.hpp"

#include <algorithm>
#include <chrono>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define FORMSIM_CPU_RELAX() _mm_pause()
#else
#define FORMSIM_CPU_RELAX() std::this_thread::yield()
#endif

#include "sim/core/background.hpp"

namespace formsim::sim {
namespace {

// How long an idle worker watches for the next section before it sleeps: longer than the
// serial part of a large step (Box2D, control: a few hundred microseconds), so the next section
// finds it awake. After kSpinHard it yields between looks, so that the recorder's writer thread
// and other programs get the core.
constexpr auto kSpinHard = std::chrono::microseconds(20);
constexpr auto kSpin = std::chrono::microseconds(500);

std::atomic<int> g_default_threads{0};  // 0: all cores

}  // namespace

ThreadPool::ThreadPool(int threads) : threads_(UsableThreads(threads)) {}

ThreadPool::~ThreadPool() {
  stop_ = true;
  { std::lock_guard<std::mutex> lock(wake_mutex_); }
  wake_.notify_all();
  for (auto& w : workers_) w.join();
}

int ThreadPool::HardwareThreads() {
  return UsableThreads(static_cast<int>(std::thread::hardware_concurrency()));
}

int ThreadPool::DefaultThreads() {
  const int n = g_default_threads.load();
  return n > 0 ? n : HardwareThreads();
}

void ThreadPool::SetDefaultThreads(int threads) {
  g_default_threads = std::max(0, threads);
}

void ThreadPool::Run(std::size_t n, std::size_t grain, Body body, void* ctx, SideFn side,
                     void* side_ctx) {
  while (static_cast<int>(workers_.size()) < threads_ - 1)
    workers_.emplace_back([this] { WorkerLoop(); });
  {
    std::lock_guard<std::mutex> lock(job_mutex_);
    body_ = body;
    ctx_ = ctx;
    n_ = n;
    // Several chunks per thread: a thread the OS deschedules holds up at most a small one.
    chunk_ = std::max(grain, n / (8 * static_cast<std::size_t>(threads_)));
    next_.store(0);
    error_ = nullptr;
    job_open_ = true;
  }
  generation_.fetch_add(1);
  if (sleeping_.load() > 0) {
    { std::lock_guard<std::mutex> lock(wake_mutex_); }
    wake_.notify_all();
  }
  std::exception_ptr side_error;
  if (side != nullptr) {
    try {
      side(side_ctx);
    } catch (...) {
      side_error = std::current_exception();
    }
  }
  Work();
  {
    std::lock_guard<std::mutex> lock(job_mutex_);
    job_open_ = false;
  }
  // Every chunk is handed out; wait for the workers still finishing theirs (yielding after a
  // while, so that a worker waiting for this core gets it).
  for (int polls = 0; active_.load() != 0; ++polls) {
    if (polls < 4096)
      FORMSIM_CPU_RELAX();
    else
      std::this_thread::yield();
  }
  if (side_error) std::rethrow_exception(side_error);
  if (error_) std::rethrow_exception(error_);
}

void ThreadPool::Work() {
  for (;;) {
    const std::size_t begin = next_.fetch_add(chunk_);
    if (begin >= n_) return;
    const std::size_t end = std::min(n_, begin + chunk_);
    try {
      body_(ctx_, begin, end);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex_);
      if (!error_) error_ = std::current_exception();
    }
  }
}

void ThreadPool::WorkerLoop() {
  unsigned seen = 0;
  for (;;) {
    // Spin for a while, then sleep until the generation changes.
    const auto start = std::chrono::steady_clock::now();
    bool yielding = false;
    int polls = 0;
    while (generation_.load() == seen && !stop_.load()) {
      if (yielding)
        std::this_thread::yield();
      else
        FORMSIM_CPU_RELAX();
      if ((++polls & 63) != 0) continue;
      const auto waited = std::chrono::steady_clock::now() - start;
      yielding = waited > kSpinHard;
      if (waited > kSpin) {
        std::unique_lock<std::mutex> lock(wake_mutex_);
        sleeping_.fetch_add(1);
        wake_.wait(lock, [&] { return generation_.load() != seen || stop_.load(); });
        sleeping_.fetch_sub(1);
        break;
      }
    }
    if (stop_.load()) return;
    seen = generation_.load();
    {
      std::lock_guard<std::mutex> lock(job_mutex_);
      if (!job_open_) continue;
      active_.fetch_add(1);
    }
    Work();
    active_.fetch_sub(1);
  }
}

}  // namespace formsim::sim
