// The fast angle functions of control/common/angle.hpp against libm and against their own
// definitions: SinCosOf within 2 ulp of glibc, Atan2NearAxis within 1 ulp, WrapToPi bit for bit
// what std::remainder gives, SinCosSmallAll bit for bit SinCosSmall.
#include "control/common/angle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

namespace formsim::control {
namespace {

// Distance in units in the last place (same sign; 0 for equal values, ±0 included).
std::int64_t Ulps(double a, double b) {
  if (a == b) return 0;
  std::int64_t x, y;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  if ((x < 0) != (y < 0)) return std::numeric_limits<std::int64_t>::max();
  return x > y ? x - y : y - x;
}

bool SameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// WrapToPi as it was defined before its fast paths: std::remainder, then −π to π.
double WrapByRemainder(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

TEST(Angle, SinCosOfIsWithinTwoUlpOfLibm) {
  std::mt19937_64 gen(7);
  for (double range : {1e-3, 0.8, 3.2, 7.0, 100.0, kSinCosReduced}) {
    std::uniform_real_distribution<double> u(-range, range);
    std::int64_t worst = 0;
    int same = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double a = u(gen);
      const SinCos f = SinCosOf(a);
      const std::int64_t e = std::max(Ulps(f.s, std::sin(a)), Ulps(f.c, std::cos(a)));
      worst = std::max(worst, e);
      same += e == 0;
    }
    EXPECT_LE(worst, 2) << "|a| <= " << range;
    EXPECT_GT(same, n / 2) << "|a| <= " << range;  // most results are libm's bits
  }
}

TEST(Angle, SinCosOfNearMultiplesOfHalfPiIsAccurateInAbsoluteTerms) {
  // The reduction keeps about 119 bits of π/2: relative accuracy is lost only where the result
  // is itself below ~1e-15, and the absolute error stays below 1e-30 there.
  for (int k = -8; k <= 8; ++k) {
    const double a = k * (kPi / 2);
    const SinCos f = SinCosOf(a);
    EXPECT_NEAR(f.s, std::sin(a), 1e-30) << k;
    EXPECT_NEAR(f.c, std::cos(a), 1e-30) << k;
  }
  EXPECT_EQ(SinCosOf(0.0).s, 0.0);
  EXPECT_EQ(SinCosOf(0.0).c, 1.0);
}

TEST(Angle, SinCosOfBeyondItsRangeIsLibm) {
  for (double a : {1.5e5, -1e7, 1e300, std::numeric_limits<double>::infinity()}) {
    const SinCos f = SinCosOf(a);
    EXPECT_TRUE(SameBits(f.s, std::sin(a)) || (std::isnan(f.s) && std::isnan(std::sin(a)))) << a;
    EXPECT_TRUE(SameBits(f.c, std::cos(a)) || (std::isnan(f.c) && std::isnan(std::cos(a)))) << a;
  }
  EXPECT_TRUE(std::isnan(SinCosOf(std::nan("")).s));
}

TEST(Angle, Atan2NearAxisIsWithinOneUlpOfLibmAndLibmElsewhere) {
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> t(-0.4375, 0.4375), x(1e-3, 10.0);
  std::int64_t worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double xi = x(gen), yi = t(gen) * xi;
    worst = std::max(worst, Ulps(Atan2NearAxis(yi, xi), std::atan2(yi, xi)));
  }
  EXPECT_LE(worst, 1);
  // Off the axis's neighbourhood, or behind it: exactly std::atan2.
  for (auto [y, xx] : {std::pair{1.0, 1.0}, {0.1, -1.0}, {-0.5, 1.0}, {0.0, 0.0}, {0.2, 0.0}})
    EXPECT_TRUE(SameBits(Atan2NearAxis(y, xx), std::atan2(y, xx))) << y << " " << xx;
}

TEST(Angle, WrapToPiIsExactlyTheRemainder) {
  std::mt19937_64 gen(3);
  std::uniform_real_distribution<double> u(-12 * kPi, 12 * kPi);
  for (int i = 0; i < 200000; ++i) {
    const double a = u(gen);
    ASSERT_TRUE(SameBits(WrapToPi(a), WrapByRemainder(a))) << a;
  }
  // The edges of each fast path and their neighbours.
  for (double edge : {kPi, 3 * kPi, -kPi, -3 * kPi, 0.0})
    for (double a : {edge, std::nextafter(edge, 1e9), std::nextafter(edge, -1e9)})
      EXPECT_TRUE(SameBits(WrapToPi(a), WrapByRemainder(a))) << a;
  EXPECT_EQ(WrapToPi(-kPi), kPi);
}

TEST(Angle, SinCosSmallAllIsSinCosSmallOneByOne) {
  std::mt19937_64 gen(5);
  for (double range : {0.01, kSmallAngle, 1.0}) {  // the last mixes polynomial and libm
    std::uniform_real_distribution<double> u(-range, range);
    double a[7], s[7], c[7];
    for (int rep = 0; rep < 1000; ++rep) {
      for (double& v : a) v = u(gen);
      SinCosSmallAll(a, s, c);
      for (int i = 0; i < 7; ++i) {
        const SinCos one = SinCosSmall(a[i]);
        ASSERT_TRUE(SameBits(s[i], one.s) && SameBits(c[i], one.c)) << a[i];
      }
    }
  }
}

}  // namespace
}  // namespace formsim::control
