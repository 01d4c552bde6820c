#pragma once
// Portable test noise: mt19937_64 is fully specified by the standard, Box-Muller is ours, so
// the numbers are the same on every platform (std::normal_distribution is not).
#include <cmath>
#include <cstdint>
#include <random>

namespace formsim::testutil {

class TestNoise {
 public:
  explicit TestNoise(std::uint64_t seed) : gen_(seed) {}
  double Uniform() { return (gen_() >> 11) * (1.0 / 9007199254740992.0); }
  double Normal() {
    const double u1 = 1.0 - Uniform(), u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
  }

 private:
  std::mt19937_64 gen_;
};

}  // namespace formsim::testutil
