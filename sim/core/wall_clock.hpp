#pragma once
/// Wall-clock time for timing and pacing (never for simulated time, which is step * dt).
#include <chrono>

namespace formsim::sim {

/// Seconds on the monotonic clock, from an arbitrary origin: only differences mean anything.
inline double WallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace formsim::sim
