// The plot's band (the area between two curves, in any point order, on raster and vector
// canvases alike) and how series are told apart: a colour-blind-safe cycle of twelve distinct
// colours, dashes past it, and the print theme's dash patterns and markers.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <utility>

#include "app/render/offscreen_renderer.hpp"
#include "app/render/plot.hpp"
#include "app/render/theme.hpp"
#include "app/render/vector_canvas.hpp"

namespace formsim::app {
namespace {

// CIE L*a*b* of an sRGB colour (D65).
std::array<double, 3> Lab(sim::Color c) {
  auto lin = [](double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); };
  const double r = lin(c.r), g = lin(c.g), b = lin(c.b);
  const double X = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047,
               Y = 0.2126 * r + 0.7152 * g + 0.0722 * b,
               Z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
  auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116; };
  return {116 * f(Y) - 16, 500 * (f(X) - f(Y)), 200 * (f(Y) - f(Z))};
}

TEST(SeriesStyle, TwelveColoursPairwiseDistinctThenDashes) {
  ASSERT_GE(kPaletteSize, 12);
  for (int i = 0; i < kPaletteSize; ++i) {  // the palette repeats after exactly kPaletteSize
    const sim::Color a = sim::PaletteColor(i), b = sim::PaletteColor(i + kPaletteSize);
    EXPECT_TRUE(a.r == b.r && a.g == b.g && a.b == b.b) << i;
  }
  for (int i = 0; i < kPaletteSize; ++i)
    for (int j = i + 1; j < kPaletteSize; ++j) {
      const auto a = Lab(sim::PaletteColor(i)), b = Lab(sim::PaletteColor(j));
      const double de = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
      EXPECT_GT(de, 20.0) << "palette colours " << i << " and " << j << " are too alike";
    }
  // Past the cycle a series repeats a colour, never its look: the dash tells it apart.
  for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kHighContrast}) {
    const Theme& th = GetTheme(id);
    for (int i = 0; i < kPaletteSize; ++i) {
      const SeriesLook a = th.Series(sim::PaletteColor(i), i, false);
      const SeriesLook b = th.Series(sim::PaletteColor(i + kPaletteSize), i + kPaletteSize, false);
      EXPECT_TRUE(a.dash.solid()) << th.name << " series " << i;
      EXPECT_FALSE(b.dash.solid()) << th.name << " series " << i + kPaletteSize;
    }
  }
}

TEST(SeriesStyle, PrintSeriesDifferByDashAndMarker) {
  const Theme& print = GetTheme(ThemeId::kPrint);
  std::set<std::pair<std::array<float, 5>, int>> looks;
  for (int i = 0; i < 42; ++i) {
    const SeriesLook look = print.Series(sim::PaletteColor(i), i, false);
    EXPECT_NE(look.marker, MarkerShape::kNone) << "print series " << i << " has no marker";
    std::array<float, 5> dash{};
    for (int k = 0; k < 4; ++k) dash[k] = look.dash.lengths[k];
    dash[4] = static_cast<float>(look.dash.count);
    EXPECT_TRUE(looks.insert({dash, static_cast<int>(look.marker)}).second)
        << "print series " << i << " repeats the dash and marker of an earlier one";
  }
  // The first six dash patterns and the first seven markers are all different.
  std::set<std::array<float, 5>> dashes;
  std::set<int> markers;
  for (int i = 0; i < 7; ++i) {
    const SeriesLook look = print.Series(sim::PaletteColor(i), i, false);
    std::array<float, 5> dash{};
    for (int k = 0; k < 4; ++k) dash[k] = look.dash.lengths[k];
    dash[4] = static_cast<float>(look.dash.count);
    if (i < 6) {
      EXPECT_TRUE(dashes.insert(dash).second) << "dash of series " << i;
    }
    EXPECT_TRUE(markers.insert(static_cast<int>(look.marker)).second) << "marker of series " << i;
  }
}

}  // namespace
}  // namespace formsim::app
