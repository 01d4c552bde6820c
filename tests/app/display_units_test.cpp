// One way to show numbers (issue 24 item 7): the angle unit applies to every unit built on the
// radian (sliders, table headers and cells, plot axes), view-only; a header that does not fit
// is shortened in its name, never cut mid-unit.
#include <gtest/gtest.h>

#include <cmath>

#include "app/gui/table_header.hpp"
#include "app/render/display_unit.hpp"
#include "app/render/plot_units.hpp"

namespace formsim::app {
namespace {

constexpr double kDeg = 180 / M_PI;

TEST(DisplayUnits, EveryUnitBuiltOnTheRadianFollowsTheAngleUnit) {
  EXPECT_EQ(ShownUnit("rad", true).unit, "°");
  EXPECT_NEAR(ShownUnit("rad", true).scale, kDeg, 1e-12);
  EXPECT_EQ(ShownUnit("rad/s", true).unit, "°/s");  // a rate limit reads 687.5°/s, not 687.55°
  EXPECT_EQ(ShownUnit("rad²", true).unit, "deg²");  // angle noise variances
  EXPECT_NEAR(ShownUnit("rad²", true).scale, kDeg * kDeg, 1e-9);
  EXPECT_EQ(ShownUnit("rad^2", true).unit, "deg²");
  EXPECT_EQ(ShownUnit("rad/√s", true).unit, "°/√s");
  EXPECT_EQ(ShownUnit("m", true).unit, "m");
  EXPECT_EQ(ShownUnit("m", true).scale, 1.0);
  EXPECT_FALSE(ShownUnit("m", true).angle);
  EXPECT_EQ(ShownUnit("radius", true).unit, "radius");
  const DisplayUnit off = ShownUnit("rad/s", false);
  EXPECT_EQ(off.unit, "rad/s");
  EXPECT_EQ(off.scale, 1.0);
  EXPECT_TRUE(off.angle);
}

TEST(DisplayUnits, LabelsCarryTheirUnitInBrackets) {
  EXPECT_EQ(LabelUnit("max|e_phi| [rad]"), "rad");
  EXPECT_EQ(LabelUnit("collisions"), "");
  EXPECT_EQ(ShownLabel("max|e_phi| [rad]", true), "max|e_phi| [°]");
  EXPECT_EQ(ShownLabel("max|e_phi| [rad]", false), "max|e_phi| [rad]");
  EXPECT_EQ(ShownLabel("P0 φ [rad²]", true), "P0 φ [deg²]");
  EXPECT_EQ(ShownLabel("e_l [m]", true), "e_l [m]");
}

TEST(DisplayUnits, PlotAxesInDegreesWhenDegreesAreChosen) {
  PlotData d;
  d.y_label = "e_φ [rad]";
  d.x_label = "t [s]";
  PlotSeries s;
  s.x = {0, 1};
  s.y = {0.5, -1};
  s.band_lo = {0.25};
  s.band_hi = {1};
  d.series.push_back(s);
  d.reference_lines = {M_PI};
  PlotData rad = d;
  ShowPlotInUnits(rad, false);
  EXPECT_EQ(rad.y_label, "e_φ [rad]");
  EXPECT_EQ(rad.series[0].y[0], 0.5);
  ShowPlotInUnits(d, true);
  EXPECT_EQ(d.y_label, "e_φ [°]");
  EXPECT_EQ(d.x_label, "t [s]");
  EXPECT_EQ(d.series[0].x[1], 1.0);
  EXPECT_NEAR(d.series[0].y[0], 0.5 * kDeg, 1e-12);
  EXPECT_NEAR(d.series[0].band_hi[0], kDeg, 1e-12);
  EXPECT_NEAR(d.reference_lines[0], 180.0, 1e-12);
}

TEST(DisplayUnits, AHeaderThatDoesNotFitKeepsItsUnitWhole) {
  const auto bytes = [](const std::string& s) { return static_cast<float>(s.size()); };
  const std::string h = "max|e_phi| [rad]";
  EXPECT_EQ(FitHeader(h, 100, bytes), h);
  // "…" is three bytes: 13 bytes leave "max|e…" before " [rad]" (6 bytes).
  const std::string cut = FitHeader(h, 14, bytes);
  EXPECT_EQ(cut, "max|e… [rad]");
  for (float w = 0; w < 17; ++w) {
    const std::string f = FitHeader(h, w, bytes);
    EXPECT_TRUE(f == "…" || f.find(" [rad]") != std::string::npos) << "cut mid-unit: " << f;
    EXPECT_TRUE(f == "…" || bytes(f) <= w) << f;
  }
  // Never inside a UTF-8 character.
  const std::string greek = FitHeader("φφφφ [°]", 10, bytes);
  EXPECT_EQ(greek, "φ… [°]");
}

}  // namespace
}  // namespace formsim::app
