#include "app/render/plot.hpp"

#include <algorithm>
#include <cmath>

#include "app/render/plot_frame.hpp"
#include "app/render/plot_log_scale.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {

LineDash DashStyle(int k) {
  switch ((k - 1) % 4) {
    case 0:
      return LineDash::Dashes(8, 5);
    case 1:
      return LineDash::Dashes(2, 3);
    case 2:
      return LineDash::DashDot(9, 3, 2);
    default:
      return LineDash::Dashes(14, 5);
  }
}

sim::Color Viridis(double f) {
  // Nine samples of matplotlib's viridis, linearly interpolated.
  static const float kStops[9][3] = {
      {0.267f, 0.005f, 0.329f}, {0.279f, 0.175f, 0.483f}, {0.230f, 0.322f, 0.546f},
      {0.173f, 0.449f, 0.558f}, {0.128f, 0.567f, 0.551f}, {0.153f, 0.683f, 0.502f},
      {0.369f, 0.789f, 0.383f}, {0.678f, 0.864f, 0.190f}, {0.993f, 0.906f, 0.144f}};
  const double x = std::clamp(std::isfinite(f) ? f : 0.0, 0.0, 1.0) * 8.0;
  const int i = std::min(7, static_cast<int>(x));
  const float t = static_cast<float>(x - i);
  sim::Color c;
  c.r = kStops[i][0] + t * (kStops[i + 1][0] - kStops[i][0]);
  c.g = kStops[i][1] + t * (kStops[i + 1][1] - kStops[i][1]);
  c.b = kStops[i][2] + t * (kStops[i + 1][2] - kStops[i][2]);
  return c;
}

std::vector<double> NiceTicks(double lo, double hi, int max_ticks, double* step_out) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  max_ticks = std::max(2, max_ticks);
  // A short axis can be left with one tick (±0.009 with a step of 0.01, a figure of a few
  // centimetres): then finer steps, up to twice as many ticks, until two are in range.
  for (int n = max_ticks;; ++n) {
    const double raw = (hi - lo) / n;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    const double norm = raw / mag;
    const double step = (norm <= 1.0 ? 1.0 : norm <= 2.0 ? 2.0 : norm <= 5.0 ? 5.0 : 10.0) * mag;
    ticks.clear();
    for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0) {
      double v = k * step;
      if (std::abs(v) < 1e-12 * step) v = 0.0;  // no "-0"
      ticks.push_back(v);
    }
    if (ticks.size() >= 2 || n >= 2 * max_ticks) {
      if (step_out != nullptr) *step_out = step;
      return ticks;
    }
  }
}

std::string FormatTick(double value, double step, int exponent) {
  const double scale = std::pow(10.0, -exponent);
  const double v = value * scale, st = step * scale;
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(st) + 1e-9)));
  std::string s = sim::FormatFixed(std::abs(v), std::min(decimals, 8));
  const bool zero = std::abs(v) < 0.5 * std::pow(10.0, -decimals);
  if (v < 0 && !zero) s = "−" + s;  // typographic minus
  return s;
}

double SampleSeries(const PlotSeries& s, double x) {
  const std::size_t n = std::min(s.x.size(), s.y.size());
  if (n == 0 || !(x >= s.x.front()) || !(x <= s.x[n - 1])) return plot_detail::kNaN;
  const auto it = std::lower_bound(s.x.begin(), s.x.begin() + static_cast<long>(n), x);
  const std::size_t i = static_cast<std::size_t>(it - s.x.begin());
  if (i == 0) return s.y[0];
  const double t = (x - s.x[i - 1]) / (s.x[i] - s.x[i - 1]);
  return s.y[i - 1] + t * (s.y[i] - s.y[i - 1]);
}

PlotStyle FigureStyle(const Theme& theme) {
  PlotStyle s;
  s.title_font = FontRole::kTitle;
  s.label_font = FontRole::kLabel;
  s.tick_font = FontRole::kSmall;
  s.line_width = 2.0f;
  s.padding = 14.0f;
  s.theme = &theme;
  return s;
}

PlotLayout DrawPlot(Canvas& cv, ImVec2 min, ImVec2 max, const PlotData& data, const PlotStyle& st,
                    double cursor_x) {
  // A log y axis draws the data in decades; the stages then work as for a linear one.
  long dropped = 0;
  bool log_y = false;
  PlotData decades;
  if (data.log_y) decades = LogYData(data, &dropped, &log_y);
  plot_detail::PlotFrame f(cv, min, max, log_y ? decades : data, st);
  f.log_y = log_y;
  f.log_dropped = dropped;
  cv.FillBackground(min, max, f.th.background);
  f.Ranges();
  f.Layout();
  f.PlaceLegend();
  f.DrawAxes();
  f.DrawSeries(cursor_x);
  f.DrawColourBar();
  f.DrawLegend();
  return f.L;
}

}  // namespace formsim::app
