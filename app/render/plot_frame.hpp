#pragma once
/// \file The stages of DrawPlot, over one PlotFrame that carries what each stage found: ranges
/// (the data's extent to axis ranges), layout (the data area, from the tick labels' widths),
/// legend placement (the corner covering the fewest points), then drawing: axes, data, colour
/// bar and legend. Internal to the plot widget: plot.cpp runs the stages in this order.

#include <imgui.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "app/render/canvas.hpp"
#include "app/render/plot.hpp"
#include "app/render/theme.hpp"
#include "control/common/float_limits.hpp"

namespace formsim::app::plot_detail {

using control::kNaN;

/// A legend entry is cut to this many bytes (a name of any length keeps the legend in its
/// corner).
constexpr std::size_t kLegendBytes = 80;

/// A legend entry's label (markup) as drawn: its runs when the drawn text fits kLegendBytes,
/// else the drawn text cut to that many bytes.
ImVec2 LegendTextSize(const Canvas& cv, FontRole font, const std::string& label);
void DrawLegendText(Canvas& cv, ImVec2 pos, FontRole font, sim::Color color,
                    const std::string& label);

/// The finite extent of some values (NaN, NaN while empty).
struct Range {
  double lo = kNaN, hi = kNaN;
  void Add(double v) {
    if (!std::isfinite(v)) return;
    if (!(v >= lo)) lo = v;  // NaN-safe first value
    if (!(v <= hi)) hi = v;
  }
  bool valid() const { return std::isfinite(lo) && std::isfinite(hi); }
};

/// Where the bars of bar series `j` of `n` stand in their category: the offset of their centre
/// from the category's x and their width (the group fills 80% of a category).
struct BarSlot {
  double offset, width;
};
BarSlot BarSlotOf(int j, int n);

/// v[i], or NaN past its end.
double At(const std::vector<double>& v, std::size_t i);

/// "×10⁻⁴" with Unicode superscripts.
std::string PowerLabel(int e);

/// A shared power of ten for tick labels when the values are tiny or huge (0 otherwise).
int AxisExponent(double lo, double hi);

/// One plot being drawn: its inputs, then what the stages computed, in stage order.
struct PlotFrame {
  PlotFrame(Canvas& canvas, ImVec2 min, ImVec2 max, const PlotData& data, const PlotStyle& style);

  // ---- inputs ----
  Canvas& cv;
  const PlotData& data;
  const PlotStyle& st;
  const Theme& th;
  ImVec2 min, max;  ///< the whole plot's rectangle
  float line_w;     ///< data line width after the theme's scale

  // ---- ranges ----
  Range rx, ry;                           ///< the data's extent (before padding)
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;  ///< the axes' ranges
  double ypad = 0;
  int bar_series = 0;  ///< bar series share each category
  bool heat = false, cat_x = false, cat_y = false;
  /// A log y axis: `data` is already in decades (LogYData); `log_dropped` values <= 0 were
  /// left out of it.
  bool log_y = false;
  long log_dropped = 0;

  // ---- layout ----
  float pad, title_h, tick_h, xlabel_h, ylabel_w;
  ImVec2 a, b;         ///< the data area: top-left, bottom-right
  int ex = 0, ey = 0;  ///< shared powers of ten of the tick labels
  double xstep = 1, ystep = 1;
  float right_reserve = 0;   ///< room for a colour bar outside the axes, on the right
  float bottom_reserve = 0;  ///< room for a legend below the axes (and their x label)
  double heat_lo = kNaN, heat_hi = kNaN, cstep = 1;  ///< the heatmap's colour bar
  int ce = 0;
  std::vector<double> cticks;

  // ---- legend ----
  std::vector<int> legend_items;  ///< indices of the labelled series
  ImVec2 leg_size{0, 0};
  float row_h = 0, sample_w = 26, col_w = 0;
  int leg_cols = 1;
  /// Each legend column's left offset from the legend's left (empty: col_w apart).
  std::vector<float> col_x;
  int corner = 1;  ///< 0..3: top-left, top-right, bottom-left, bottom-right; -1: below the axes

  PlotLayout L;  ///< what DrawPlot returns

  /// Stage 1: the axes' ranges from the data, bands, heatmap, categories and references.
  void Ranges();
  /// Stage 2: the data area and the ticks (and an equal-aspect plot's widened range).
  void Layout();
  /// Stage 3: the legend's size and corner (raising the y range if no corner is free, or else
  /// moving it below the axes in as many columns as fit their width); then fixes L's area and
  /// ranges.
  void PlaceLegend();
  /// Stage 4: title, grid, ticks and axis labels.
  void DrawAxes();
  /// Stage 5: heatmap, bands, reference lines, bars, lines and markers, marker and cursor
  /// (clipped to the data area), then the frame.
  void DrawSeries(double cursor_x);
  /// Stage 6: the heatmap's colour bar and the legend.
  void DrawColourBar();
  void DrawLegend();

  /// Screen x of data x, screen y of data y.
  float X(double v) const;
  float Y(double v) const;

 private:
  void LayOutOnce();  // the area and ticks for the current ranges
  void Equalize();    // same units per pixel on both axes
  std::string XText(double t) const;
  std::string YText(double t) const;
  void CornerBox(int c, ImVec2& lo, ImVec2& hi) const;
  long CountInside(ImVec2 lo, ImVec2 hi) const;
};

}  // namespace formsim::app::plot_detail
