// The heap policy of the formsim executable: a large buffer freed and allocated again each frame
// (a 3840x2160 RGBA frame is 33 MB) is not faulted in anew each time.
#include "app/cli/heap_policy.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace formsim::app {
namespace {

#if defined(__SANITIZE_ADDRESS__)
#define FORMSIM_OWN_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FORMSIM_OWN_ALLOCATOR 1
#endif
#endif

long MinorFaults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// In a child process (the policy is for the whole process): the page faults of frames 2-8 when
// each frame allocates, fills and frees a 40 MiB buffer; 0 after setting the policy.
[[maybe_unused]] long FaultsOfRepeatedFrames(bool with_policy) {
  int fds[2];
  if (pipe(fds) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    if (with_policy) ApplyHeapPolicy();
    constexpr std::size_t kBytes = 40u << 20;
    long before = 0;
    for (int frame = 0; frame < 8; ++frame) {
      if (frame == 1) before = MinorFaults();
      auto* p = static_cast<unsigned char*>(std::malloc(kBytes));
      if (p == nullptr) _exit(1);
      std::memset(p, frame + 1, kBytes);
      asm volatile("" : : "r"(p) : "memory");  // the pages are written, not optimised away
      std::free(p);
    }
    const long faults = MinorFaults() - before;
    if (write(fds[1], &faults, sizeof faults) != sizeof faults) _exit(1);
    _exit(0);
  }
  close(fds[1]);
  long faults = -1;
  if (read(fds[0], &faults, sizeof faults) != sizeof faults) faults = -1;
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return faults;
}

TEST(HeapPolicy, AFrameSizedBufferIsNotFaultedInAgainEachFrame) {
#if defined(FORMSIM_OWN_ALLOCATOR) || !defined(__GLIBC__)
  GTEST_SKIP() << "the policy is glibc's malloc's; this build has another allocator";
#else
  const long with_policy = FaultsOfRepeatedFrames(true);
  const long without = FaultsOfRepeatedFrames(false);
  // 40 MiB is 10240 pages: glibc's defaults map and unmap the buffer at every frame.
  EXPECT_GT(without, 7 * 10000) << "glibc kept the buffer without the policy: the test no longer "
                                   "tells the two apart";
  EXPECT_LT(with_policy, 1000) << "without the policy: " << without;
#endif
}

}  // namespace
}  // namespace formsim::app
