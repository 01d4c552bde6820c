#include "app/cli/heap_policy.hpp"

// A C library header first: it defines __GLIBC__, which the test below needs. (Without one the
// policy compiled to nothing whenever this file began a unity batch.)
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace formsim::app {

void ApplyHeapPolicy() {
#if defined(__GLIBC__)
  // Setting these also stops glibc's own adjustment of the thresholds, which rise only as far as
  // the largest mapped block freed so far (at most 32 MiB) and let the heap's top be trimmed and
  // faulted in again between frames.
  constexpr int kMiB = 1 << 20;
  mallopt(M_MMAP_THRESHOLD, 64 * kMiB);
  mallopt(M_TRIM_THRESHOLD, 128 * kMiB);
#endif
}

}  // namespace formsim::app
