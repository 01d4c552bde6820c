#include "app/render/plot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/render/polyline_simplify.hpp"
#include "app/render/vector_canvas.hpp"
#include "app/render/world_view.hpp"

namespace formsim::app {
namespace {

TEST(NiceTicks, OneTwoFiveSteps) {
  double step = 0;
  const auto t = NiceTicks(0.0, 11.0, 6, &step);
  EXPECT_DOUBLE_EQ(step, 2.0);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_DOUBLE_EQ(t.back(), 10.0);
}

TEST(NiceTicks, TinyAndNegativeRanges) {
  double step = 0;
  const auto t = NiceTicks(-3.2e-4, 1.1e-4, 5, &step);
  EXPECT_NEAR(step, 1e-4, 1e-18);
  ASSERT_FALSE(t.empty());
  EXPECT_NEAR(t.front(), -3e-4, 1e-12);
  for (double v : t) EXPECT_TRUE(v >= -3.2e-4 && v <= 1.1e-4);
  for (double v : t) EXPECT_FALSE(std::signbit(v) && v == 0.0) << "no negative zero";
}

TEST(NiceTicks, AShortAxisKeepsAtLeastTwoTicks) {
  // ±0.009 in room for two ticks: a step of 0.01 would leave 0 alone; 0.005 gives three.
  double step = 0;
  const auto t = NiceTicks(-0.009, 0.009, 2, &step);
  EXPECT_DOUBLE_EQ(step, 0.005);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[0], -0.005);
  EXPECT_EQ(t[1], 0.0);
  EXPECT_DOUBLE_EQ(t[2], 0.005);
  EXPECT_EQ(NiceTicks(0.0, 11.0, 6).size(), 6u) << "unchanged where two fit already";
}

TEST(NiceTicks, DegenerateRangeGivesNothing) {
  EXPECT_TRUE(NiceTicks(1.0, 1.0, 5).empty());
  EXPECT_TRUE(NiceTicks(0.0, NAN, 5).empty());
}

TEST(FormatTick, DecimalsFollowTheStep) {
  EXPECT_EQ(FormatTick(0.5, 0.5, 0), "0.5");
  EXPECT_EQ(FormatTick(2.0, 2.0, 0), "2");
  EXPECT_EQ(FormatTick(0.02, 0.01, 0), "0.02");
  EXPECT_EQ(FormatTick(-1.0, 0.5, 0), "−1.0");
  EXPECT_EQ(FormatTick(-0.0, 0.5, 0), "0.0");
  // With a shared exponent the label is the mantissa.
  EXPECT_EQ(FormatTick(1.5e-4, 5e-5, -4), "1.5");
}

TEST(SampleSeries, InterpolatesInsideAndNaNOutside) {
  PlotSeries s;
  s.x = {0, 1, 2};
  s.y = {0, 10, 30};
  EXPECT_DOUBLE_EQ(SampleSeries(s, 0.5), 5.0);
  EXPECT_DOUBLE_EQ(SampleSeries(s, 1.5), 20.0);
  EXPECT_TRUE(std::isnan(SampleSeries(s, 2.5)));
}

TEST(GridStep, AtLeastTheMinimumSpacing) {
  EXPECT_DOUBLE_EQ(GridStep(100.0, 70.0), 1.0);
  EXPECT_DOUBLE_EQ(GridStep(30.0, 70.0), 5.0);
  EXPECT_DOUBLE_EQ(GridStep(1000.0, 70.0), 0.1);
}

TEST(View, FitShowsTheWholeBoxAndMapsBack) {
  View v;
  v.min = ImVec2(0, 0);
  v.max = ImVec2(800, 400);
  v.Fit({-1, -2}, {3, 2}, 20.0f);
  for (Vec2 corner : {Vec2{-1, -2}, Vec2{3, 2}}) {
    const ImVec2 s = v.ToScreen(corner);
    EXPECT_GE(s.x, 19.0f);
    EXPECT_LE(s.x, 781.0f);
    EXPECT_GE(s.y, 19.0f);
    EXPECT_LE(s.y, 381.0f);
    const Vec2 back = v.ToWorld(s);
    EXPECT_NEAR(back.x, corner.x, 1e-4);
    EXPECT_NEAR(back.y, corner.y, 1e-4);
  }
  // Zooming about a point keeps that point fixed.
  const ImVec2 p(600, 100);
  const Vec2 before = v.ToWorld(p);
  v.ZoomAt(p, 2.5);
  const Vec2 after = v.ToWorld(p);
  EXPECT_NEAR(before.x, after.x, 1e-9);
  EXPECT_NEAR(before.y, after.y, 1e-9);
}

}  // namespace
}  // namespace formsim::app

namespace formsim::app {
namespace {

TEST(SimplifyPolyline, StraightLineBecomesOneSegmentCurveStaysClose) {
  std::vector<ImVec2> line;
  for (int i = 0; i <= 1000; ++i) line.emplace_back(0.5f * i, 100.0f);
  const auto s = SimplifyPolyline(line);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.back().x, 500.0f);

  std::vector<ImVec2> arc;
  for (int i = 0; i <= 2000; ++i) {
    const double t = i * 0.001 * 3.14159;
    arc.emplace_back(static_cast<float>(200 + 150 * std::cos(t)),
                     static_cast<float>(200 + 150 * std::sin(t)));
  }
  const auto a = SimplifyPolyline(arc, 0.35f);
  EXPECT_LT(a.size(), arc.size() / 10);
  EXPECT_GT(a.size(), 10u);
  // Every original point lies within the tolerance (plus rounding) of the simplified polyline.
  for (const ImVec2& p : arc) {
    double best = 1e9;
    for (std::size_t k = 1; k < a.size(); ++k) {
      const double dx = a[k].x - a[k - 1].x, dy = a[k].y - a[k - 1].y;
      const double len2 = dx * dx + dy * dy;
      double t = len2 > 0 ? ((p.x - a[k - 1].x) * dx + (p.y - a[k - 1].y) * dy) / len2 : 0;
      t = std::clamp(t, 0.0, 1.0);
      best = std::min(best, std::hypot(p.x - (a[k - 1].x + t * dx), p.y - (a[k - 1].y + t * dy)));
    }
    ASSERT_LT(best, 0.5);
  }
}

// With data in every corner and no headroom to make (an equal-aspect plot keeps its scale), the
// legend goes below the axes, and the axes keep well over 60% of the figure's width.
TEST(PlotLegend, NoFreeCornerPutsItBelowTheAxes) {
  PlotData d;
  d.equal_aspect = true;
  for (int i = 0; i < 6; ++i) {
    PlotSeries s;
    s.label = "a long legend entry number " + std::to_string(i);
    for (int k = 0; k <= 200; ++k) {  // a dense zigzag over the whole square
      s.x.push_back(k / 200.0);
      s.y.push_back(((k * 7 + i * 13) % 50) / 49.0);
    }
    d.series.push_back(s);
  }
  const float w = 321, h = 227;  // 8.5 cm x 6 cm
  VectorCanvas cv(w, h);
  const PlotLayout L =
      DrawPlot(cv, ImVec2(0, 0), ImVec2(w, h), d, FigureStyle(GetTheme(ThemeId::kLight)));
  EXPECT_GE(L.legend_min.y, L.area_max.y) << "the legend overlaps the axes";
  EXPECT_LE(L.legend_max.y, h + 0.5f) << "the legend leaves the figure";
  EXPECT_GE(L.area_max.x - L.area_min.x, 0.6f * w) << "the legend took the axes' width";
}

}  // namespace
}  // namespace formsim::app
