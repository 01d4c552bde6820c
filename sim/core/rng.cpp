#include "sim/core/rng.hpp"

#include <cmath>

namespace formsim::sim {

double Rng::Normal() {
  if (has_cached_) {
    has_cached_ = false;
    return cached_;
  }
  // Box-Muller on (0, 1] so log() never sees zero.
  const double u1 = 1.0 - Uniform();
  const double u2 = Uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double a = 6.283185307179586476925 * u2;
  // libm's sine and cosine, not control::SinCosOf: a different last bit in a draw changes the
  // velocity kind's sliding-window decisions and so its reproduced tables; every seed keeps the
  // noise it had.
  cached_ = r * std::sin(a);
  has_cached_ = true;
  return r * std::cos(a);
}

Rng Rng::Fork(std::uint64_t stream_id) const {
  // SplitMix64 of (a draw-independent base, stream id): forks do not consume this stream.
  std::mt19937_64 copy = engine_;
  std::uint64_t z = copy() + 0x9E3779B97F4A7C15ull * (stream_id + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return Rng(z ^ (z >> 31));
}

}  // namespace formsim::sim
