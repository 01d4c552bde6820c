// The plot's band: the area between two curves, for points in any order, with zero and
// non-zero widths, filled alike on the raster (ImGui: window, PNG) and vector (SVG, PDF)
// canvases. A band's outline is not convex; ImGui's convex fill once drew a wedge across it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "app/export/figure_export.hpp"
#include "app/export/video_writer.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "app/render/plot.hpp"
#include "app/render/theme.hpp"
#include "app/render/vector_canvas.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

// A band alone (no line) given out of x order: the sweep of issue 25 (σ 0, 0.001 and 0 at
// k_l = 0.1, 0.3, 1), and a second one of zero and non-zero widths whose curves touch.
PlotData BandFigure() {
  PlotData d;
  PlotSeries thin;
  thin.x = {1.0, 0.1, 0.3};
  const double mean[] = {1.5, 1.0, 2.0}, sd[] = {0.0, 0.0, 0.001};
  for (int i = 0; i < 3; ++i) {
    thin.band_lo.push_back(mean[i] - sd[i]);
    thin.band_hi.push_back(mean[i] + sd[i]);
  }
  thin.color = sim::PaletteColor(0);
  PlotSeries wide;
  wide.x = {2.0, 1.4, 1.7, 2.3};
  wide.band_lo = {1.0, 1.0, 0.5, 1.0};
  wide.band_hi = {1.0, 2.0, 1.5, 1.8};
  wide.color = sim::PaletteColor(0);
  d.series = {thin, wide};
  return d;
}

// The band's lower and upper curve at x (NaN outside), by linear interpolation in x order.
std::pair<double, double> BandAt(const PlotSeries& s, double x) {
  std::vector<std::size_t> o(s.x.size());
  for (std::size_t i = 0; i < o.size(); ++i) o[i] = i;
  std::sort(o.begin(), o.end(), [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
  for (std::size_t k = 0; k + 1 < o.size(); ++k) {
    const std::size_t i = o[k], j = o[k + 1];
    if (x < s.x[i] || x > s.x[j]) continue;
    const double t = (x - s.x[i]) / (s.x[j] - s.x[i]);
    return {s.band_lo[i] + t * (s.band_lo[j] - s.band_lo[i]),
            s.band_hi[i] + t * (s.band_hi[j] - s.band_hi[i])};
  }
  return {NAN, NAN};
}

// Winding number of `p` around a closed polygon.
int Winding(const std::vector<ImVec2>& poly, ImVec2 p) {
  int w = 0;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const ImVec2 a = poly[j], b = poly[i];
    const float side = (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y);
    if (a.y <= p.y && b.y > p.y && side > 0) ++w;
    if (a.y > p.y && b.y <= p.y && side < 0) --w;
  }
  return w;
}

// Samples of the data area more than 2 px from every band edge, with whether each lies inside
// a band: the test points of both canvases.
struct Sample {
  ImVec2 screen;
  bool inside;
};
std::vector<Sample> Samples(const PlotData& d, const PlotLayout& L) {
  std::vector<Sample> out;
  const float sx = (L.area_max.x - L.area_min.x) / static_cast<float>(L.x1 - L.x0);
  const float sy = (L.area_max.y - L.area_min.y) / static_cast<float>(L.y1 - L.y0);
  for (float px = L.area_min.x + 3; px < L.area_max.x - 3; px += 3)
    for (float py = L.area_min.y + 3; py < L.area_max.y - 3; py += 3) {
      const double x = L.x0 + (px - L.area_min.x) / sx, y = L.y0 + (L.area_max.y - py) / sy;
      bool inside = false, near = false;
      for (const PlotSeries& s : d.series) {
        for (double dx : {-2.0 / sx, 0.0, 2.0 / sx}) {
          const auto [lo, hi] = BandAt(s, x + dx);
          if (std::isnan(lo)) continue;
          if (std::abs(y - lo) * sy < 2.5 || std::abs(y - hi) * sy < 2.5) near = true;
        }
        const auto [lo, hi] = BandAt(s, x);
        if (!std::isnan(lo) && y > std::min(lo, hi) && y < std::max(lo, hi)) inside = true;
      }
      // Near an edge or a band's first or last x: anti-aliasing decides, skip.
      for (const PlotSeries& s : d.series)
        for (double bx : s.x) near = near || std::abs(x - bx) * sx < 2.5;
      if (!near) out.push_back({ImVec2(px, py), inside});
    }
  return out;
}

TEST(PlotBand, VectorFillCoversExactlyTheAreaBetweenTheCurves) {
  const PlotData d = BandFigure();
  VectorCanvas cv(480, 320);
  const PlotLayout L =
      DrawPlot(cv, ImVec2(0, 0), ImVec2(480, 320), d, FigureStyle(GetTheme(ThemeId::kLight)));
  std::vector<std::vector<ImVec2>> fills;
  for (const VectorOp& op : cv.figure().ops)
    if (op.kind == VectorOp::Kind::kFillPath) fills.push_back(op.pts);
  ASSERT_FALSE(fills.empty());
  int in = 0, out = 0;
  for (const Sample& s : Samples(d, L)) {
    int w = 0;
    for (const auto& f : fills) w += Winding(f, s.screen) != 0;
    EXPECT_EQ(w > 0, s.inside) << "at " << s.screen.x << ", " << s.screen.y;
    (s.inside ? in : out) += 1;
  }
  EXPECT_GT(in, 50) << "the test must see the wide band's inside";
  EXPECT_GT(out, 1000);
}

TEST(PlotBand, RasterFillCoversExactlyTheAreaBetweenTheCurves) {
  const PlotData d = BandFigure();
  const int w = 480, h = 320;
  OffscreenRenderer r(w, h);
  const auto& px = r.RenderFigure(d, w, h);
  const PlotLayout& L = r.last_plot_layout();
  // Light theme: background and grid have red above 215; the band (blue at 22% opacity) has
  // about 195.
  int in = 0, wrong = 0;
  for (const Sample& s : Samples(d, L)) {
    const int x = static_cast<int>(s.screen.x), y = static_cast<int>(s.screen.y);
    const int red = px[(static_cast<std::size_t>(y) * w + x) * 4];
    const bool shaded = red < 210;
    if (shaded != s.inside) ++wrong;
    in += s.inside;
  }
  EXPECT_GT(in, 50);
  EXPECT_EQ(wrong, 0) << "pixels shaded outside the band or left blank inside it";
}

// The band figure and a print figure with a marker on every series, as SVG that xmllint reads
// as well-formed XML, and as PDF (a picture to look at: test_tmp/plot_band/).
TEST(PlotBand, SvgIsWellFormedXmlForXmllint) {
  if (FindOnPath("xmllint").empty()) GTEST_SKIP() << "xmllint not installed (libxml2-utils)";
  const std::string dir = testing::TempDir("plot_band");
  PlotData print;
  print.title = "print: a dash and a marker per series";
  for (int i = 0; i < 8; ++i) {
    PlotSeries s;
    for (int k = 0; k <= 40; ++k) {
      s.x.push_back(0.1 * k);
      s.y.push_back(std::sin(0.1 * k + 0.4 * i) + 0.3 * i);
    }
    s.label = "series " + std::to_string(i);
    s.style_index = i;
    s.color = sim::PaletteColor(i);
    print.series.push_back(s);
  }
  const FigureSize size = ParseFigureSize("480x320", "--plot-size");
  struct Case {
    const char* name;
    PlotData data;
    ThemeId theme;
  };
  for (const Case& c : {Case{"band", BandFigure(), ThemeId::kLight},
                        Case{"print_markers", print, ThemeId::kPrint}}) {
    const VectorFigure fig = RecordPlot(c.data, 480, 320, GetTheme(c.theme));
    const std::string svg = dir + "/" + c.name + ".svg";
    WriteVectorFigure(fig, FigureFormat::kSvg, size, c.name, svg);
    WriteVectorFigure(fig, FigureFormat::kPdf, size, c.name, dir + "/" + c.name + ".pdf");
    EXPECT_EQ(testing::RunShell("xmllint --noout '" + svg + "'", dir + "/xmllint.txt"), 0)
        << testing::ReadText(dir + "/xmllint.txt");
  }
}

}  // namespace
}  // namespace formsim::app
