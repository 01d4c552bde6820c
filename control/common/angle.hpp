#pragma once
/// \file Angle helpers shared by every controller and estimator.

#include <cmath>

namespace formsim::control {

constexpr double kPi = 3.14159265358979323846;

/// Wraps an angle to (-pi, pi].
inline double WrapToPi(double a) {
  a = std::remainder(a, 2.0 * kPi);  // in [-pi, pi]
  return a <= -kPi ? a + 2.0 * kPi : a;
}

/// Wraps an angle to [0, 2pi).
inline double WrapTo2Pi(double a) {
  a = std::fmod(a, 2.0 * kPi);
  return a < 0.0 ? a + 2.0 * kPi : a;
}

/// Smallest signed difference a - b, in (-pi, pi].
inline double AngleDiff(double a, double b) { return WrapToPi(a - b); }

/// Wraps `a` to the branch nearest to `reference` (a + 2k*pi closest to reference).
inline double UnwrapNear(double a, double reference) { return reference + AngleDiff(a, reference); }

}  // namespace formsim::control
