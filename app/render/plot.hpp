#pragma once
/// \file Our plot widget (ImPlot is not packaged in Debian): axes with ticks and units, grid,
/// several series with a legend placed off the data, autoscale, a time cursor, horizontal
/// reference lines, dashed and marker series and an equal-aspect mode. Drawn onto a Canvas: live
/// in the GUI, into PNG figures, and recorded for SVG and PDF, all by the same code.

#include <imgui.h>

#include <limits>
#include <string>
#include <vector>

#include "app/render/canvas.hpp"
#include "app/render/theme.hpp"
#include "sim/core/draw.hpp"

namespace formsim::app {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  sim::Color color;
  int style_index = 0;  ///< palette index: the print theme's dash pattern and grey
  bool dashed = false;
  /// A dash pattern of its own, overriding the theme's: 1 dashes, 2 dots, 3 dash-dot, 4 long
  /// dashes (told-apart overlays such as pinned runs); 0: the theme decides.
  int dash_style = 0;
  bool markers_only = false;
  /// A shaded band under the line from band_lo to band_hi at each x (e.g. mean ± 1σ over the
  /// seeds of a sweep); empty: none. With `y` empty the band is drawn alone.
  std::vector<double> band_lo, band_hi;
  float band_alpha = 0.22f;  ///< opacity of the band's shade
  /// Bars (y[i] at category x[i], from zero) with error bars from err_lo to err_hi (empty or
  /// NaN: none). The bar series of a plot stand side by side within each category.
  bool bars = false;
  std::vector<double> err_lo, err_hi;
};

/// A heatmap (a metric over two swept keys): cell (column c, row r) is drawn centred on x = c,
/// y = r with a colour from the viridis map, and a colour bar is drawn right of the axes.
struct PlotHeatmap {
  int columns = 0, rows = 0;
  std::vector<double> values;  ///< row-major, row 0 at the bottom; NaN: no data (grey)
  std::string value_label;     ///< the colour bar's label
  /// Text drawn in each cell where it fits (row-major like `values`), e.g. "0.12 ± 0.03"; where
  /// it is empty, missing or too wide: the value itself.
  std::vector<std::string> cell_labels;
  bool cell_values = true;  ///< write the value (or label) in each cell where it fits
  bool empty() const { return columns <= 0 || rows <= 0; }
};

/// What to draw: a sim::FigureSpec resolved against recorded data (see figure_data.hpp).
struct PlotData {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  std::vector<double> reference_lines;
  bool equal_aspect = false;
  double marker_x = std::numeric_limits<double>::quiet_NaN();
  bool x_is_time = false;  ///< every series is plotted against "t" (a time cursor makes sense)
  /// Categorical axes: label k is written at x = k (y = k); no numeric ticks then.
  std::vector<std::string> x_tick_labels, y_tick_labels;
  PlotHeatmap heatmap;     ///< drawn beneath the series when not empty
  double x_margin = 0.0;   ///< room added left and right, as a fraction of the x range
  /// A logarithmic y axis (decade ticks 10^k); values <= 0 are left out with a note. Lines and
  /// bands only: bar charts and heatmaps keep a linear axis. PlotLayout's y range is then in
  /// decades (log10 of y).
  bool log_y = false;
  std::string error;       ///< shown instead of data when the figure could not be resolved
};

struct PlotStyle {
  FontRole title_font = FontRole::kTitle;
  FontRole label_font = FontRole::kLabel;
  FontRole tick_font = FontRole::kSmall;
  bool show_title = true;
  float line_width = 2.0f;  ///< data lines, before the theme's line scale
  float padding = 10.0f;
  const Theme* theme = &GetTheme(ThemeId::kLight);  ///< colours, series looks
};

/// The style of exported figures (PNG, SVG, PDF alike): 16 px labels, 14 px ticks, 17 px bold
/// title, 2 px lines.
PlotStyle FigureStyle(const Theme& theme);

/// Where things ended up, for hit-testing and tests.
struct PlotLayout {
  ImVec2 area_min, area_max;  ///< the data area (inside the axes)
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  ImVec2 legend_min, legend_max;  ///< zero size when there is no legend
  std::vector<double> x_ticks, y_ticks;
};

/// "Nice" tick values (1, 2, 5 × 10^k) covering [lo, hi] with at most about `max_ticks` ticks.
std::vector<double> NiceTicks(double lo, double hi, int max_ticks, double* step = nullptr);
/// Tick label for `value` given the tick step and a shared power of ten `exponent`.
std::string FormatTick(double value, double step, int exponent);

/// Draws the plot onto `canvas` inside [min, max]. `cursor_x` (NaN: none) draws a time cursor.
PlotLayout DrawPlot(Canvas& canvas, ImVec2 min, ImVec2 max, const PlotData& data,
                    const PlotStyle& style,
                    double cursor_x = std::numeric_limits<double>::quiet_NaN());

/// The dash pattern of PlotSeries::dash_style `k` (k > 0).
LineDash DashStyle(int k);

/// The viridis colour map at f in [0, 1] (clamped).
sim::Color Viridis(double f);

/// Value of a series at x by linear interpolation (x ascending); NaN outside or when empty.
double SampleSeries(const PlotSeries& s, double x);

}  // namespace formsim::app
