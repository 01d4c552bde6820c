// A step allocates nothing: filters, sensors, control, the thread pool, recorded and streamed
// rows (once the history has room) and events (once the log has seen their kind, robots and
// subject and stores no more of that kind). Counted with a replacement of the global operator
// new in this test program; skipped under AddressSanitizer, which provides its own.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "sim/core/event_log.hpp"
#include "sim/core/run_output.hpp"
#include "sim/scenario/scenario.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define FORMSIM_COUNT_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FORMSIM_COUNT_ALLOCATIONS 0
#endif
#endif
#ifndef FORMSIM_COUNT_ALLOCATIONS
#define FORMSIM_COUNT_ALLOCATIONS 1
#endif

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

#if FORMSIM_COUNT_ALLOCATIONS
void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  ++g_allocations;
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace formsim::sim {
namespace {

TEST(Allocations, NoneInASwarmStepWithRowsAndStreaming) {
  if (!FORMSIM_COUNT_ALLOCATIONS) GTEST_SKIP() << "AddressSanitizer replaces operator new";
  auto exp = LoadExperiment(std::string(FORMSIM_SOURCE_DIR) +
                            "/assets/scenarios/formation_swarm_100.yaml", {"record_every=10"});
  exp->SetThreads(2);
  const std::string dir = std::string(FORMSIM_BINARY_DIR) + "/alloc_test";
  PrepareOutputDir(dir);
  exp->mutable_recorder().StreamTo(CsvPath(dir));
  // The history is reserved for the whole run at its start (Recorder::ExpectRows).
  for (int k = 0; k < 100; ++k) exp->Step();  // the start: filters initialised, buffers grown
  const long before = g_allocations.load();
  for (int k = 0; k < 300; ++k) exp->Step();
  EXPECT_EQ(g_allocations.load() - before, 0) << "allocations in 300 steps (30 recorded rows)";
  EXPECT_EQ(exp->events().total(), 0);
  exp->mutable_recorder().FinishStream();
}

TEST(Allocations, NoneForARaisedEventOnceItsKindIsFull) {
  if (!FORMSIM_COUNT_ALLOCATIONS) GTEST_SKIP() << "AddressSanitizer replaces operator new";
  EventLog log;
  const auto id = log.DeclareCondition("saturation", "R123456789012345678", "link R1-R123456789012");
  auto raise = [&](int k) {
    log.Update(id, k, true, [&](std::string& m) {
      m += "R123456789012345678 command clamped to the drive limits, a long message";
    });
    log.Update(id, k + 0.5, false, [](std::string&) {});
  };
  for (long k = 0; k < EventLog::kMaxStoredPerKind + static_cast<long>(EventLog::kRecent); ++k)
    raise(static_cast<int>(k));
  const long before = g_allocations.load();
  for (int k = 0; k < 500; ++k) raise(k);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(log.Count("saturation"), EventLog::kMaxStoredPerKind + static_cast<long>(EventLog::kRecent) + 500);
  EXPECT_EQ(log.CountForRobot("saturation", "R123456789012345678"), log.Count("saturation"));
  EXPECT_EQ(static_cast<long>(log.list().size()), EventLog::kMaxStoredPerKind);
}

}  // namespace
}  // namespace formsim::sim
