// The browser page writes doubles with WriteShortestDoubleByFmt ({fmt}'s shortest digits laid
// out by ToCharsText; its libc++ has no floating-point to_chars): it must give std::to_chars'
// text for every double, or the page's CSVs differ from the desktop's.
#include "control/common/shortest_double_format.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace formsim::control {
namespace {

std::string ByToChars(double v) {
  char buf[40];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}
std::string ByFormsim(double v) {
  char buf[40];
  return std::string(buf, WriteShortestDoubleByFmt(buf, buf + sizeof buf, v));
}

TEST(ShortestDouble, SameTextAsToCharsOnChosenValues) {
  const std::vector<double> values = {0.0,
                                      -0.0,
                                      1.0,
                                      -1.0,
                                      0.1,
                                      0.2,
                                      0.3,
                                      1.0 / 3.0,
                                      2.0 / 3.0,
                                      100.0,
                                      1e5,
                                      1e6,
                                      123456.0,
                                      1e15,
                                      1e16,
                                      1e17,
                                      1e21,
                                      1e22,
                                      1e23,
                                      1.5e300,
                                      1e-5,
                                      1e-4,
                                      0.001,
                                      12345.678,
                                      -9.87654321e-7,
                                      3.141592653589793,
                                      2.718281828459045,
                                      0.01,
                                      0.05,
                                      299792458.0,
                                      6.02214076e23,
                                      std::numeric_limits<double>::max(),
                                      std::numeric_limits<double>::min(),
                                      std::numeric_limits<double>::epsilon(),
                                      9007199254740993.0,
                                      5e-324,
                                      2.2250738585072014e-308,
                                      4.35,
                                      0.30000000000000004,
                                      1234567890123456789.0,
                                      100000000000000000000.0,
                                      1e-7,
                                      123e-20,
                                      -0.0,
                                      1e-320,
                                      -1e300,
                                      0.001,
                                      9.5367431640625e-07};
  for (double v : values) EXPECT_EQ(ByFormsim(v), ByToChars(v)) << "value bits of " << ByToChars(v);
}

TEST(ShortestDouble, SameTextAsToCharsOnRandomBitsAndSimulationLikeValues) {
  std::mt19937_64 rng(29);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    double v = 0;
    if (i % 2 == 0) {
      const std::uint64_t bits = rng();
      std::memcpy(&v, &bits, sizeof v);
      if (!std::isfinite(v)) continue;
    } else {
      // Values like a run's: results of arithmetic on a few decimals, any magnitude.
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      v = u(rng) * std::pow(10.0, static_cast<int>(rng() % 24) - 12);
      if (i % 4 == 1) v = std::round(v * 1000.0) / 1000.0;
    }
    ASSERT_EQ(ByFormsim(v), ByToChars(v));
    ++checked;
  }
  EXPECT_GT(checked, 190000);
}

TEST(ShortestDouble, WriteShortestDoubleIsToChars) {
  char a[40], b[40];
  for (double v : {0.1, -2.5e-300, 7.0, 1e21, 123456789012345680000.0, 1e-5}) {
    const std::string w(a, WriteShortestDouble(a, a + sizeof a, v));
    EXPECT_EQ(w, std::string(b, std::to_chars(b, b + sizeof b, v).ptr));
  }
}

TEST(ShortestDouble, NotFiniteIsToCharsText) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double v : {inf, -inf, nan, -nan}) EXPECT_EQ(ByFormsim(v), ByToChars(v));
}

TEST(ShortestDouble, ReadsAsFromCharsDoes) {
  auto read = [](const std::string& s) {
    double v = -12345;
    return ReadWholeDouble(s.data(), s.data() + s.size(), &v) ? ByToChars(v)
                                                              : std::string("refused");
  };
  EXPECT_EQ(read("0.1"), "0.1");
  EXPECT_EQ(read("-2.5e-3"), "-0.0025");
  EXPECT_EQ(read("1."), "1");
  EXPECT_EQ(read(".5"), "0.5");
  EXPECT_EQ(read("1E5"), "1e+05");
  for (const char* bad :
       {"", "+1", " 1", "1 ", "0x10", "1e", "e5", "-", ".", "1e400", "abc", "1,5"})
    EXPECT_EQ(read(bad), "refused") << bad;
}

}  // namespace
}  // namespace formsim::control
