#include "sim/core/task_pool.hpp"

#include <algorithm>

#include "sim/core/background.hpp"

namespace formsim::sim {

TaskPool::TaskPool(int threads) {
  for (int i = 1; i < UsableThreads(threads); ++i) workers_.emplace_back([this] { WorkerLoop(); });
}

TaskPool::~TaskPool() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    quit_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

int TaskPool::HardwareThreads() {
  return UsableThreads(static_cast<int>(std::thread::hardware_concurrency()));
}

void TaskPool::Drain() {
  std::unique_lock<std::mutex> lock(mu_);
  while (next_ < count_ && !error_) {
    if (*stop_ && (*stop_)()) {
      next_ = count_;
      break;
    }
    const std::size_t i = next_++;
    const std::function<void(std::size_t)>* task = task_;  // read under the lock
    lock.unlock();
    try {
      (*task)(i);
    } catch (...) {
      lock.lock();
      if (!error_) error_ = std::current_exception();
      continue;
    }
    lock.lock();
  }
}

void TaskPool::WorkerLoop() {
  unsigned long seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mu_);
      wake_.wait(lock, [&] { return quit_ || generation_ != seen; });
      if (quit_) return;
      seen = generation_;
      ++busy_;
    }
    Drain();
    {
      std::lock_guard<std::mutex> lock(mu_);
      --busy_;
    }
    idle_.notify_all();
  }
}

void TaskPool::ForEach(std::size_t n, const std::function<void(std::size_t)>& task,
                       const std::function<bool()>& stop) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    next_ = 0;
    count_ = n;
    task_ = &task;
    stop_ = &stop;
    error_ = nullptr;
    ++generation_;
  }
  wake_.notify_all();
  Drain();
  std::exception_ptr error;
  {
    // Every worker that joined this batch must be out of it before the references go away.
    std::unique_lock<std::mutex> lock(mu_);
    idle_.wait(lock, [&] { return busy_ == 0; });
    task_ = nullptr;
    stop_ = nullptr;
    error = error_;
    error_ = nullptr;
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace formsim::sim
