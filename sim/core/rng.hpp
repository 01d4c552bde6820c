#pragma once
/// \file Seeded random numbers with a portable Gaussian (the standard library's distributions
/// are implementation-defined; ours give the same numbers on every platform).

#include <cstdint>
#include <random>

namespace formsim::sim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 1) : engine_(seed) {}
  /// Uniform in [0, 1).
  double Uniform() { return (engine_() >> 11) * (1.0 / 9007199254740992.0); }
  double Uniform(double a, double b) { return a + (b - a) * Uniform(); }
  /// Standard normal by Box-Muller (one value per call, the pair's second value is cached).
  double Normal();
  double Normal(double mean, double sigma) { return mean + sigma * Normal(); }
  bool Bernoulli(double p) { return Uniform() < p; }
  /// A child generator with its own stream (e.g. one per sensor), stable under reordering.
  Rng Fork(std::uint64_t stream_id) const;

 private:
  std::mt19937_64 engine_;
  double cached_ = 0.0;
  bool has_cached_ = false;
};

}  // namespace formsim::sim
