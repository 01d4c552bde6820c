#pragma once
/// \file Angle helpers shared by every controller and estimator.
///
/// Hot paths (a UKF per link, a thousand links) call these millions of times a second, so the
/// common cases are cheap: WrapToPi returns an angle already in (−π, π] unchanged without a
/// division, and SinCosSmall evaluates sine and cosine of a small angle (|a| ≤ 1/8, the spread
/// of sigma points, a step's rotation) by polynomials accurate to the last bit or two instead
/// of a full libm call. Both fall back to the general computation outside their fast range.

#include <cmath>
#include <cstdint>
#include <cstring>

namespace formsim::control {

constexpr double kPi = 3.14159265358979323846;

/// Wraps an angle to (-pi, pi].
inline double WrapToPi(double a) {
  // In range already: exactly what std::remainder would return (±π itself goes on: π stays,
  // −π becomes π).
  if (std::abs(a) < kPi) return a;
  // One turn out: a ∓ 2π is exact there (Sterbenz), and is what std::remainder returns.
  if (a > kPi && a <= 3.0 * kPi) return a - 2.0 * kPi;
  if (a <= -kPi && a > -3.0 * kPi) return a + 2.0 * kPi;
  a = std::remainder(a, 2.0 * kPi);  // in [-pi, pi]
  return a <= -kPi ? a + 2.0 * kPi : a;
}

/// Wraps an angle to [0, 2pi).
inline double WrapTo2Pi(double a) {
  a = std::fmod(a, 2.0 * kPi);
  return a < 0.0 ? a + 2.0 * kPi : a;
}

/// Smallest signed difference a - b, in (-pi, pi].
inline double AngleDiff(double a, double b) {
  return WrapToPi(a - b);
}

/// Wraps `a` to the branch nearest to `reference` (a + 2k*pi closest to reference).
inline double UnwrapNear(double a, double reference) {
  return reference + AngleDiff(a, reference);
}

/// Sine and cosine of one angle.
struct SinCos {
  double s = 0.0;  ///< sin
  double c = 1.0;  ///< cos
};

/// Largest |a| that SinCosOf reduces itself (beyond it: libm).
constexpr double kSinCosReduced = 1.0e5;

/// Sine and cosine of `a`, each within 1 ulp: a in [−π/4, π/4] + kπ/2 is reduced by
/// Cody–Waite with π/2 in three parts (exact products for |k| < 2²⁰) and evaluated by fdlibm's
/// kernel polynomials (__kernel_sin, __kernel_cos: error below 1 ulp on [−π/4, π/4]). About a
/// third of libm's sincos, and the same bits on every x86-64: no FMA, no CPU dispatch. libm
/// beyond |a| = kSinCosReduced and for NaN or infinity.
inline SinCos SinCosOf(double a) {
  if (!(std::abs(a) <= kSinCosReduced)) return {std::sin(a), std::cos(a)};
  if (a == 0.0) return {a, 1.0};  // keeps the sign of −0 (the polynomial would return +0)
  // k = a / (π/2) rounded to nearest (adding 1.5·2⁵² rounds in the default mode).
  constexpr double kTwoOverPi = 6.36619772367581382433e-01, kRound = 6755399441055744.0;
  const double k = (a * kTwoOverPi + kRound) - kRound;
  constexpr double kPio2_1 = 1.57079632673412561417e+00;  // first 33 bits of π/2
  constexpr double kPio2_2 = 6.07710050630396597660e-11;  // next 33 bits
  constexpr double kPio2_3 = 2.02226624871116645580e-21;  // the rest
  const double r = ((a - k * kPio2_1) - k * kPio2_2) - k * kPio2_3;
  const double z = r * r;
  const double sr =
      r + r * z *
              (-1.66666666666666324348e-01 +
               z * (8.33333333332248946124e-03 +
                    z * (-1.98412698298579493134e-04 +
                         z * (2.75573137070700676789e-06 + z * (-2.50507602534068634195e-08 +
                                                                z * 1.58969099521155010221e-10)))));
  const double cpoly =
      z * z *
      (4.16666666666666019037e-02 +
       z * (-1.38888888888741095749e-03 +
            z * (2.48015872894767294178e-05 +
                 z * (-2.75573143513906633035e-07 +
                      z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  double cr;
  if (std::abs(r) < 0.3) {
    cr = 1.0 - (0.5 * z - cpoly);
  } else {
    // fdlibm's split of 1 − z/2 for |r| ≥ 0.3: qx is |r|/4 cut to its high 32 bits (0.28125
    // above 0.78125), so that 1 − qx is exact.
    double qx = 0.28125;
    if (std::abs(r) <= 0.78125) {
      std::uint64_t bits;
      const double q = 0.25 * std::abs(r);
      std::memcpy(&bits, &q, sizeof bits);
      bits &= 0xffffffff00000000ULL;
      std::memcpy(&qx, &bits, sizeof qx);
    }
    cr = (1.0 - qx) - ((0.5 * z - qx) - cpoly);
  }
  switch (static_cast<long>(k) & 3) {
    case 0:
      return {sr, cr};
    case 1:
      return {cr, -sr};
    case 2:
      return {-sr, -cr};
    default:
      return {-cr, sr};
  }
}

/// Largest |a| that SinCosSmall evaluates by its polynomials.
constexpr double kSmallAngle = 0.125;

/// SinCosSmall's polynomials alone, for |a| ≤ kSmallAngle (no check, no branch: a loop of
/// them over an array is vectorised).
inline void SinCosSmallPoly(double a, double& s_out, double& c_out) {
  const double a2 = a * a;
  s_out =
      a + a * a2 *
              (-1.0 / 6 + a2 * (1.0 / 120 +
                                a2 * (-1.0 / 5040 + a2 * (1.0 / 362880 + a2 * (-1.0 / 39916800)))));
  c_out = 1.0 +
          a2 * (-0.5 + a2 * (1.0 / 24 + a2 * (-1.0 / 720 +
                                              a2 * (1.0 / 40320 + a2 * (-1.0 / 3628800 +
                                                                        a2 * (1.0 / 479001600))))));
}

/// Sine and cosine of a small angle: Taylor polynomials to degree 11 / 12, whose truncation
/// error at |a| = 1/8 is below 1e-21 relative (so the result is the correctly rounded value up
/// to the rounding of the evaluation); SinCosOf beyond kSmallAngle.
inline SinCos SinCosSmall(double a) {
  if (!(std::abs(a) <= kSmallAngle)) return SinCosOf(a);
  SinCos r;
  SinCosSmallPoly(a, r.s, r.c);
  return r;
}

/// SinCosSmall of a[0, K) into s and c: the polynomials as one vectorised loop when every
/// |a| ≤ kSmallAngle (the same bits as one at a time).
template <int K>
inline void SinCosSmallAll(const double (&a)[K], double (&s)[K], double (&c)[K]) {
  bool small = true;
  for (int i = 0; i < K; ++i) small &= std::abs(a[i]) <= kSmallAngle;
  if (small) {
    for (int i = 0; i < K; ++i) SinCosSmallPoly(a[i], s[i], c[i]);
    return;
  }
  for (int i = 0; i < K; ++i) {
    const SinCos v = SinCosSmall(a[i]);
    s[i] = v.s, c[i] = v.c;
  }
}

/// atan2(y, x) for a point near the positive x axis (x > 0, |y| ≤ 7/16 x: the mean of small
/// angular deviations), by fdlibm's atan polynomial on y/x (error below 1 ulp before the
/// rounding of the quotient); std::atan2 otherwise.
inline double Atan2NearAxis(double y, double x) {
  if (!(x > 0.0 && std::abs(y) <= 0.4375 * x)) return std::atan2(y, x);
  const double t = y / x, z = t * t, w = z * z;
  const double s1 =
      z * (3.33333333333329318027e-01 +
           w * (1.42857142725034663711e-01 +
                w * (9.09088713343650656196e-02 +
                     w * (6.66107313738753120669e-02 +
                          w * (4.97687799461593236017e-02 + w * 1.62858201153657823623e-02)))));
  const double s2 =
      w * (-1.99999999998764832476e-01 +
           w * (-1.11111104054623557880e-01 +
                w * (-7.69187620504482999495e-02 +
                     w * (-5.83357013379057348645e-02 + w * -3.65315727442169155270e-02))));
  return t - t * (s1 + s2);
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
