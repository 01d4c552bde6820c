// The one number formatter (control/common/number_format.hpp): each form's text, the edges
// that used to be handled by local copies (minus zero, rounding carries, non-finite values).
#include "control/common/number_format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "control/common/float_limits.hpp"

namespace formsim::control {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

TEST(NumberFormat, ShortestTextReadsBackToTheSameBits) {
  EXPECT_EQ(FormatDouble(0.03), "0.03");
  EXPECT_EQ(FormatDouble(1e-9), "1e-09");
  EXPECT_EQ(FormatDouble(-kInf), "-inf");
  EXPECT_EQ(FormatDouble(-kNan), "nan");
  for (double v : {0.1, 1.0 / 3.0, 6.02214076e23, -2.5e-300}) {
    double back = 0;
    ASSERT_TRUE(ParseFiniteDouble(FormatDouble(v), &back));
    EXPECT_EQ(back, v);
  }
}

TEST(NumberFormat, SignificantDigits) {
  EXPECT_EQ(FormatSignificant(0.123456789, 4), "0.1235");
  EXPECT_EQ(FormatSignificant(1.5e-5), "1.5e-05");
  EXPECT_EQ(FormatSignificant(120.0), "120");
  EXPECT_EQ(FormatSignificant(-kNan), "nan");  // never glibc's "-nan"
  EXPECT_EQ(FormatSignificant(kInf, 3), "inf");
  EXPECT_EQ(FormatSignificant(2.0, 0), "2");  // digits clamped to at least one
}

TEST(NumberFormat, FixedDecimalsNeverPrintMinusZero) {
  EXPECT_EQ(FormatFixed(0.25, 3), "0.250");
  EXPECT_EQ(FormatFixed(-0.0004, 3), "0.000");
  EXPECT_EQ(FormatFixed(-0.0006, 3), "-0.001");
  EXPECT_EQ(FormatFixed(12.5, 2, true), "12.5");
  EXPECT_EQ(FormatFixed(3.0, 2, true), "3");
  EXPECT_EQ(FormatFixed(-0.004, 2, true), "0");
  EXPECT_EQ(FormatFixed(1500.0, 0, true), "1500");  // trimming never eats a whole number's zeros
  EXPECT_EQ(FormatFixed(kNan, 2), "nan");
}

TEST(NumberFormat, ScientificAsPapersWriteIt) {
  EXPECT_EQ(FormatScientific(0.0721, 2), "7.2e-2");
  EXPECT_EQ(FormatScientific(-1302.0, 3), "-1.30e3");
  EXPECT_EQ(FormatScientific(9.96, 2), "1.0e1");  // the rounding carry renormalises
  EXPECT_EQ(FormatScientific(0.0, 3), "0");
  EXPECT_EQ(FormatScientific(kInf, 3), "inf");
}

TEST(NumberFormat, WholeNumbersAsIntegers) {
  EXPECT_EQ(FormatWholeOrShortest(15.0), "15");
  EXPECT_EQ(FormatWholeOrShortest(-3.0), "-3");
  EXPECT_EQ(FormatWholeOrShortest(1e14), "100000000000000");
  EXPECT_EQ(FormatWholeOrShortest(0.1), "0.1");
  EXPECT_EQ(FormatWholeOrShortest(1e16), "1e+16");
}

TEST(NumberFormat, DurationsReadAsAClock) {
  EXPECT_EQ(FormatClock(5.4), "0:05");
  EXPECT_EQ(FormatClock(72), "1:12");
  EXPECT_EQ(FormatClock(3723), "1:02:03");
  EXPECT_EQ(FormatClock(kNan), "0:00");
  EXPECT_EQ(FormatClock(-4), "0:00");
  EXPECT_EQ(FormatClock(1e300), "888888:53:20");  // capped, never an overflowing conversion
}

TEST(NumberFormat, TableCellsKeepTheirDigitsAndMeanSigmaMatches) {
  // One column, one look: the same significant digits, trailing zeros kept.
  EXPECT_EQ(FormatCell(0.00712, 4), "0.007120");
  EXPECT_EQ(FormatCell(7.086e-03, 4), "0.007086");
  EXPECT_EQ(FormatCell(12.5, 4), "12.50");
  EXPECT_EQ(FormatCell(9.99996, 4), "10.00");  // the rounding carry
  EXPECT_EQ(FormatCell(3.0, 4), "3");          // a count
  EXPECT_EQ(FormatCell(0.0, 4), "0");
  EXPECT_EQ(FormatCell(7.12e-6, 4), "7.120e-6");
  EXPECT_EQ(FormatCell(2.5e7 + 0.5, 3), "2.50e7");
  EXPECT_EQ(FormatCell(kNan, 4), "nan");
  // σ to the decimal place of the mean's last digit.
  EXPECT_EQ(FormatMeanSigma(0.007559, 0.00068, 4), "0.007559 ± 0.000680");
  EXPECT_EQ(FormatMeanSigma(12.5, 0.26, 3), "12.5 ± 0.3");
  EXPECT_EQ(FormatMeanSigma(7.559e-6, 6.8e-7, 4), "(7.559 ± 0.680)e-6");
  EXPECT_EQ(FormatMeanSigma(0.5, kNan, 4), "0.5000");
  EXPECT_EQ(FormatMeanSigma(0.0, 0.0, 4), "0 ± 0");
}

}  // namespace
}  // namespace formsim::control
