// The thread pool of a step's independent work: every index exactly once, whatever the number
// of threads; exceptions reach the caller; nested and concurrent calls run inline.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "sim/core/thread_pool.hpp"

namespace formsim::sim {
namespace {

TEST(ThreadPool, CoversEveryIndexOnceForAnyThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (std::size_t n : {0u, 1u, 7u, 100u, 1937u}) {
      for (std::size_t grain : {1u, 16u}) {
        std::vector<int> hits(n, 0);
        pool.ParallelFor(
            n,
            [&](std::size_t b, std::size_t e) {
              ASSERT_LE(b, e);
              ASSERT_LE(e, n);
              for (std::size_t i = b; i < e; ++i) ++hits[i];
            },
            grain);
        for (std::size_t i = 0; i < n; ++i)
          ASSERT_EQ(hits[i], 1) << threads << " " << n << " " << i;
      }
    }
  }
}

TEST(ThreadPool, ManySectionsInARow) {
  // Like a simulation: thousands of short sections, each depending on the previous one.
  ThreadPool pool(3);
  std::vector<double> v(500, 1.0);
  for (int round = 0; round < 2000; ++round)
    pool.ParallelFor(v.size(), [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) v[i] = v[i] * 0.5 + 1.0;
    });
  for (double x : v) EXPECT_DOUBLE_EQ(x, 2.0);
}

TEST(ThreadPool, RethrowsTheFirstExceptionAfterEveryRangeRan) {
  ThreadPool pool(2);
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.ParallelFor(64,
                                [&](std::size_t b, std::size_t e) {
                                  ran += static_cast<int>(e - b);
                                  if (b == 0) throw std::runtime_error("boom");
                                }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 64);
  // The pool is still usable.
  std::atomic<int> again{0};
  pool.ParallelFor(64, [&](std::size_t b, std::size_t e) { again += static_cast<int>(e - b); });
  EXPECT_EQ(again.load(), 64);
}

TEST(ThreadPool, NestedAndConcurrentCallsRunInline) {
  ThreadPool pool(2);
  std::atomic<int> inner{0};
  pool.ParallelFor(8, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      pool.ParallelFor(10,
                       [&](std::size_t ib, std::size_t ie) { inner += static_cast<int>(ie - ib); });
  });
  EXPECT_EQ(inner.load(), 80);
  // Two threads sharing one pool: both loops complete.
  std::atomic<int> total{0};
  auto loop = [&] {
    for (int k = 0; k < 200; ++k)
      pool.ParallelFor(100,
                       [&](std::size_t b, std::size_t e) { total += static_cast<int>(e - b); });
  };
  std::thread other(loop);
  loop();
  other.join();
  EXPECT_EQ(total.load(), 2 * 200 * 100);
}

// The side task runs once on the calling thread while the ranges are taken by the others; every
// index is still covered exactly once, and with one thread it is side() then fn(0, n).
TEST(ThreadPool, BesideRunsTheSideTaskOnTheCallerAndCoversEveryIndexOnce) {
  for (int threads : {1, 2, 4}) {
    ThreadPool pool(threads);
    for (std::size_t n : {0u, 1u, 5u, 333u, 20000u}) {
      std::vector<std::atomic<int>> seen(n);
      std::atomic<int> sides{0};
      std::thread::id side_thread;
      bool side_first_inline = false;
      pool.ParallelForBeside(
          [&] {
            side_thread = std::this_thread::get_id();
            side_first_inline = true;
            ++sides;
          },
          n,
          [&](std::size_t b, std::size_t e) {
            if (threads == 1) {
              EXPECT_TRUE(side_first_inline) << "inline order: side, then fn";
            }
            for (std::size_t i = b; i < e; ++i) ++seen[i];
          });
      EXPECT_EQ(sides.load(), 1);
      EXPECT_EQ(side_thread, std::this_thread::get_id());
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(seen[i].load(), 1) << threads << " " << n << " " << i;
    }
  }
}

TEST(ThreadPool, BesideRethrowsTheSideTasksExceptionAfterTheRangesRan) {
  ThreadPool pool(2);
  std::atomic<std::size_t> done{0};
  EXPECT_THROW(pool.ParallelForBeside([] { throw std::runtime_error("side"); }, 1000,
                                      [&](std::size_t b, std::size_t e) { done += e - b; }),
               std::runtime_error);
  EXPECT_EQ(done.load(), 1000u);
  EXPECT_THROW(pool.ParallelForBeside([] {}, 1000,
                                      [&](std::size_t b, std::size_t) {
                                        if (b == 0) throw std::logic_error("range");
                                      }),
               std::logic_error);
}

TEST(ThreadPool, DefaultThreadsFollowTheSetting) {
  const int before = ThreadPool::DefaultThreads();
  ThreadPool::SetDefaultThreads(3);
  EXPECT_EQ(ThreadPool::DefaultThreads(), 3);
  ThreadPool::SetDefaultThreads(0);  // back to all cores
  EXPECT_EQ(ThreadPool::DefaultThreads(), ThreadPool::HardwareThreads());
  ThreadPool::SetDefaultThreads(before == ThreadPool::HardwareThreads() ? 0 : before);
}

}  // namespace
}  // namespace formsim::sim
