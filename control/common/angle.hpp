#pragma once
/// \file Angle helpers shared by every controller and estimator.
///
/// Hot paths (a UKF per link, a thousand links) call these millions of times a second, so the
/// common cases are cheap: WrapToPi returns an angle already in (−π, π] unchanged without a
/// division, and SinCosSmall evaluates sine and cosine of a small angle (|a| ≤ 1/8, the spread
/// of sigma points, a step's rotation) by polynomials accurate to the last bit or two instead
/// of a full libm call. Both fall back to the general computation outside their fast range.

#include <cmath>

namespace formsim::control {

constexpr double kPi = 3.14159265358979323846;

/// Wraps an angle to (-pi, pi].
inline double WrapToPi(double a) {
  // In range already: exactly what std::remainder would return.
  if (a > -kPi && a <= kPi) return a;
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

/// Sine and cosine of one angle.
struct SinCos {
  double s = 0.0;  ///< sin
  double c = 1.0;  ///< cos
};

/// Sine and cosine of `a` from one evaluation (the compiler turns the pair into one sincos).
inline SinCos SinCosOf(double a) { return {std::sin(a), std::cos(a)}; }

/// Largest |a| that SinCosSmall evaluates by its polynomials.
constexpr double kSmallAngle = 0.125;

/// Sine and cosine of a small angle: Taylor polynomials to degree 11 / 12, whose truncation
/// error at |a| = 1/8 is below 1e-21 relative (so the result is the correctly rounded value up
/// to the rounding of the evaluation); SinCosOf beyond kSmallAngle.
inline SinCos SinCosSmall(double a) {
  if (!(std::abs(a) <= kSmallAngle)) return SinCosOf(a);
  const double a2 = a * a;
  const double s =
      a + a * a2 *
              (-1.0 / 6 +
               a2 * (1.0 / 120 +
                     a2 * (-1.0 / 5040 + a2 * (1.0 / 362880 + a2 * (-1.0 / 39916800)))));
  const double c =
      1.0 +
      a2 * (-0.5 +
            a2 * (1.0 / 24 +
                  a2 * (-1.0 / 720 +
                        a2 * (1.0 / 40320 + a2 * (-1.0 / 3628800 + a2 * (1.0 / 479001600))))));
  return {s, c};
}

/// sin and cos of (x + d) from those of x and d (angle addition).
inline SinCos AddAngles(const SinCos& x, const SinCos& d) {
  return {x.s * d.c + x.c * d.s, x.c * d.c - x.s * d.s};
}
/// sin and cos of (x − d).
inline SinCos SubAngles(const SinCos& x, const SinCos& d) {
  return {x.s * d.c - x.c * d.s, x.c * d.c + x.s * d.s};
}

}  // namespace formsim::control
