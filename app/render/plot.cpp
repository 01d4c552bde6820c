#include "app/render/plot.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>

#include "app/render/long_text.hpp"
#include "app/render/polyline_simplify.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

// A legend entry is cut to this many bytes (a name of any length keeps the legend in its corner).
constexpr std::size_t kLegendBytes = 80;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// "×10⁻⁴" with Unicode superscripts.
std::string PowerLabel(int e) {
  static const char* sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string digits = std::to_string(std::abs(e)), out = "×10";
  if (e < 0) out += "⁻";
  for (char c : digits) out += sup[c - '0'];
  return out;
}

// A shared power of ten for tick labels when the values are tiny or huge (distance errors of
// order 1e-4 read better as "1.5" with "×10⁻⁴" than as "0.00015").
int AxisExponent(double lo, double hi) {
  const double m = std::max(std::abs(lo), std::abs(hi));
  if (m == 0 || !std::isfinite(m)) return 0;
  if (m < 1e-2 || m >= 1e5) return static_cast<int>(std::floor(std::log10(m)));
  return 0;
}

struct Range {
  double lo = kNaN, hi = kNaN;
  void Add(double v) {
    if (!std::isfinite(v)) return;
    if (!(v >= lo)) lo = v;  // NaN-safe first value
    if (!(v <= hi)) hi = v;
  }
  bool valid() const { return std::isfinite(lo) && std::isfinite(hi); }
};

// Screen points of a series. For x-sorted data with more points than pixels, each pixel column
// keeps its first, min, max and last point (the shape is exact at screen resolution); otherwise
// points closer than ~0.7 px are merged. Non-finite values split the line into runs.
std::vector<std::vector<ImVec2>> ScreenRuns(const PlotSeries& s, double x0, double x1, double y0,
                                            double y1, ImVec2 a, ImVec2 b) {
  std::vector<std::vector<ImVec2>> runs;
  const std::size_t n = std::min(s.x.size(), s.y.size());
  const double sx = (b.x - a.x) / (x1 - x0), sy = (b.y - a.y) / (y1 - y0);
  auto to_screen = [&](std::size_t i) {
    return ImVec2(static_cast<float>(a.x + (s.x[i] - x0) * sx),
                  static_cast<float>(b.y - (s.y[i] - y0) * sy));
  };
  bool sorted = true;
  for (std::size_t i = 1; i < n && sorted; ++i) sorted = !(s.x[i] < s.x[i - 1]);
  // A plot squeezed to nothing (a tiny window) has a negative width: no bucketing then.
  const double width_px = std::max(0.0, static_cast<double>(b.x - a.x));
  const bool bucket = sorted && static_cast<double>(n) > 2.0 * width_px;
  std::vector<ImVec2> run;
  int col = INT32_MIN;
  ImVec2 first, mn, mx, last;
  std::size_t i_mn = 0, i_mx = 0;
  // Emits the column's first, min, max and last points in the order they occurred, so the line
  // never steps backwards (a 180° turn makes anti-aliased polyline joins blow up).
  auto flush_col = [&]() {
    if (col == INT32_MIN) return;
    auto push = [&](ImVec2 p) {
      if (run.empty() || run.back().x != p.x || run.back().y != p.y) run.push_back(p);
    };
    push(first);
    if (i_mn < i_mx)
      push(mn), push(mx);
    else
      push(mx), push(mn);
    push(last);
    col = INT32_MIN;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
      flush_col();
      if (run.size() > 0) runs.push_back(std::move(run));
      run.clear();
      continue;
    }
    const ImVec2 p = to_screen(i);
    if (bucket) {
      // Clamped before the conversion: a point far off screen must not overflow an int.
      const int c = static_cast<int>(std::floor(std::clamp(p.x, -1e9f, 1e9f)));
      if (c != col) {
        flush_col();
        col = c;
        first = mn = mx = last = p;
        i_mn = i_mx = i;
      } else {
        if (p.y < mn.y) mn = p, i_mn = i;
        if (p.y > mx.y) mx = p, i_mx = i;
        last = p;
      }
    } else if (run.empty() || std::abs(p.x - run.back().x) + std::abs(p.y - run.back().y) > 0.7f ||
               i + 1 == n) {
      run.push_back(p);
    }
  }
  flush_col();
  if (!run.empty()) runs.push_back(std::move(run));
  if (!s.markers_only)
    for (auto& r : runs) r = SimplifyPolyline(r);
  return runs;
}

// Ticks of a categorical axis: every k-th of 0..n-1 so that at most `fit` labels are written.
std::vector<double> CategoryTicks(std::size_t n, double fit) {
  const std::size_t step = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::ceil(static_cast<double>(n) / std::max(1.0, fit))));
  std::vector<double> t;
  for (std::size_t k = 0; k < n; k += step) t.push_back(static_cast<double>(k));
  return t;
}

// The finite range of a heatmap's values (NaN, NaN when it has none).
void HeatRange(const PlotHeatmap& h, double* lo, double* hi) {
  *lo = *hi = kNaN;
  for (double v : h.values) {
    if (!std::isfinite(v)) continue;
    if (!(v >= *lo)) *lo = v;
    if (!(v <= *hi)) *hi = v;
  }
}

sim::Color HeatColor(double v, double lo, double hi) {
  if (!std::isfinite(v)) return sim::Color{0.84f, 0.84f, 0.84f, 1};
  return Viridis(hi > lo ? (v - lo) / (hi - lo) : 0.5);
}

// Shades the band of a series (between band_lo and band_hi): each finite run of points as one
// polygon (upper edge forward, lower edge back), in chunks so no polygon gets large.
void DrawBand(Canvas& cv, const PlotSeries& s, sim::Color col,
              const std::function<ImVec2(double, double)>& to_screen) {
  const std::size_t n = std::min({s.x.size(), s.band_lo.size(), s.band_hi.size()});
  auto finite = [&](std::size_t i) {
    return std::isfinite(s.x[i]) && std::isfinite(s.band_lo[i]) && std::isfinite(s.band_hi[i]);
  };
  constexpr std::size_t kChunk = 64;
  std::size_t i = 0;
  while (i < n) {
    while (i < n && !finite(i)) ++i;
    std::size_t j = i;
    while (j < n && finite(j) && j - i < kChunk) ++j;
    if (j - i >= 2) {
      std::vector<ImVec2> poly;
      for (std::size_t k = i; k < j; ++k) poly.push_back(to_screen(s.x[k], s.band_hi[k]));
      for (std::size_t k = j; k-- > i;) poly.push_back(to_screen(s.x[k], s.band_lo[k]));
      cv.FillPolygon(poly.data(), static_cast<int>(poly.size()), col);
    }
    // The next chunk starts at this chunk's last point, so they join.
    i = (j < n && finite(j) && j - i >= kChunk) ? j - 1 : j;
  }
}

// Where the bars of bar series `j` of `n` stand in their category: the offset of their centre
// from the category's x and their width (the group fills 80% of a category).
struct BarSlot {
  double offset, width;
};
BarSlot BarSlotOf(int j, int n) {
  const double w = 0.8 / std::max(1, n);
  return {-0.4 + w * (j + 0.5), w};
}

double At(const std::vector<double>& v, std::size_t i) {
  return i < v.size() ? v[i] : kNaN;
}

}  // namespace

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
  const double raw = (hi - lo) / max_ticks;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double step = (norm <= 1.0 ? 1.0 : norm <= 2.0 ? 2.0 : norm <= 5.0 ? 5.0 : 10.0) * mag;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0) {
    double v = k * step;
    if (std::abs(v) < 1e-12 * step) v = 0.0;  // no "-0"
    ticks.push_back(v);
  }
  if (step_out != nullptr) *step_out = step;
  return ticks;
}

std::string FormatTick(double value, double step, int exponent) {
  const double scale = std::pow(10.0, -exponent);
  const double v = value * scale, st = step * scale;
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(st) + 1e-9)));
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", std::min(decimals, 8), std::abs(v));
  std::string s = buf;
  const bool zero = std::abs(v) < 0.5 * std::pow(10.0, -decimals);
  if (v < 0 && !zero) s = "−" + s;  // typographic minus
  return s;
}

double SampleSeries(const PlotSeries& s, double x) {
  const std::size_t n = std::min(s.x.size(), s.y.size());
  if (n == 0 || !(x >= s.x.front()) || !(x <= s.x[n - 1])) return kNaN;
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
  PlotLayout L;
  const Theme& th = *st.theme;
  const FontRole title_font = st.title_font, label_font = st.label_font, tick_font = st.tick_font;
  auto TextSize = [&](FontRole f, const std::string& s) { return cv.TextSize(f, s); };
  auto Text = [&](FontRole f, ImVec2 pos, sim::Color col, const std::string& s) {
    cv.Text(pos, f, col, s);
  };
  const float line_w = st.line_width * th.line_scale;
  cv.FillRect(min, max, th.background);

  // ---- data ranges ----
  Range rx, ry;
  for (const auto& s : data.series) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      rx.Add(s.x[i]);
      ry.Add(s.y[i]);
      if (s.bars) ry.Add(0.0), ry.Add(At(s.err_lo, i)), ry.Add(At(s.err_hi, i));
    }
    const std::size_t nb = std::min({s.x.size(), s.band_lo.size(), s.band_hi.size()});
    for (std::size_t i = 0; i < nb; ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.band_lo[i]) || !std::isfinite(s.band_hi[i]))
        continue;
      rx.Add(s.x[i]);
      ry.Add(s.band_lo[i]);
      ry.Add(s.band_hi[i]);
    }
  }
  // Bar series: their number (they share each category) and whether all stand on zero.
  int bar_series = 0;
  for (const auto& s : data.series) bar_series += s.bars;
  // Heatmaps and categorical axes: half a cell of room around the first and last category.
  const bool heat = !data.heatmap.empty();
  const bool cat_x = !data.x_tick_labels.empty(), cat_y = !data.y_tick_labels.empty();
  if (heat) rx.Add(0), rx.Add(data.heatmap.columns - 1), ry.Add(0), ry.Add(data.heatmap.rows - 1);
  if (cat_x) rx.Add(-0.5), rx.Add(static_cast<double>(data.x_tick_labels.size()) - 0.5);
  if (heat || cat_y) {
    ry.Add(-0.5);
    ry.Add(static_cast<double>(heat ? data.heatmap.rows
                                    : static_cast<int>(data.y_tick_labels.size())) -
           0.5);
  }
  if (heat) rx.Add(-0.5), rx.Add(data.heatmap.columns - 0.5);
  for (double r : data.reference_lines) ry.Add(r);
  if (std::isfinite(data.marker_x)) rx.Add(data.marker_x);
  if (!rx.valid()) rx.lo = 0, rx.hi = 1;
  if (!ry.valid()) ry.lo = 0, ry.hi = 1;
  if (rx.hi - rx.lo < 1e-12) {
    const double h = std::max(1e-9, std::abs(rx.lo) * 0.1) + (rx.lo == 0 ? 1 : 0);
    rx.lo -= h, rx.hi += h;
  }
  if (ry.hi - ry.lo < 1e-300 || ry.hi - ry.lo < 1e-9 * std::max(std::abs(ry.lo), std::abs(ry.hi))) {
    const double h = ry.lo == 0 ? 1.0 : std::abs(ry.lo) * 0.1;
    ry.lo -= h, ry.hi += h;
  }
  double x0 = rx.lo - data.x_margin * (rx.hi - rx.lo), x1 = rx.hi + data.x_margin * (rx.hi - rx.lo);
  const double ypad = heat || cat_y ? 0.0 : 0.06 * (ry.hi - ry.lo);
  double y0 = ry.lo - ypad, y1 = ry.hi + ypad;
  if (bar_series > 0 && ry.lo >= 0.0) y0 = 0.0;  // bars stand on the axis
  if (data.equal_aspect) {
    const double xpad = 0.06 * (x1 - x0);
    x0 -= xpad, x1 += xpad;
  }

  // ---- frame layout (margins depend on tick label widths, so ticks first) ----
  const float pad = st.padding;
  const float title_h = (st.show_title && !data.title.empty()) ? cv.FontSize(title_font) + 8 : 0;
  const float tick_h = cv.FontSize(tick_font);
  const float xlabel_h = data.x_label.empty() ? 0 : cv.FontSize(label_font) + 4;
  const float ylabel_w = data.y_label.empty() ? 0 : cv.FontSize(label_font) + 6;
  ImVec2 a, b;  // data area
  int ex = 0, ey = 0;
  double xstep = 1, ystep = 1;
  float right_reserve = 0;  // room for a legend or colour bar outside the axes, on the right
  double heat_lo = kNaN, heat_hi = kNaN, cstep = 1;
  int ce = 0;
  std::vector<double> cticks;
  if (heat) {
    HeatRange(data.heatmap, &heat_lo, &heat_hi);
    if (std::isfinite(heat_lo)) {
      cticks = NiceTicks(heat_lo, heat_hi, 6, &cstep);
      ce = AxisExponent(heat_lo, heat_hi);
    }
    float wmax = 0;
    for (double t : cticks) wmax = std::max(wmax, TextSize(tick_font, FormatTick(t, cstep, ce)).x);
    right_reserve = 12 + 16 + 6 + wmax + 8 +
                    (data.heatmap.value_label.empty() ? 0 : cv.FontSize(label_font) + 6);
  }
  auto x_text = [&](double t) {
    return cat_x ? data.x_tick_labels[static_cast<std::size_t>(std::llround(t))]
                 : FormatTick(t, xstep, ex);
  };
  auto y_text = [&](double t) {
    return cat_y ? data.y_tick_labels[static_cast<std::size_t>(std::llround(t))]
                 : FormatTick(t, ystep, ey);
  };
  auto layout = [&]() {
    const float top = min.y + pad + title_h + tick_h * 0.6f;
    b.y = max.y - pad - xlabel_h - tick_h - 8;
    a.y = top + (AxisExponent(y0, y1) != 0 ? tick_h + 2 : 0);
    const int ny = std::max(2, static_cast<int>((b.y - a.y) / 45));
    if (cat_y) {
      L.y_ticks = CategoryTicks(data.y_tick_labels.size(), (b.y - a.y) / (tick_h + 6));
      ey = 0;
    } else {
      L.y_ticks = NiceTicks(y0, y1, ny, &ystep);
      ey = AxisExponent(y0, y1);
    }
    float wmax = 0;
    for (double t : L.y_ticks) wmax = std::max(wmax, TextSize(tick_font, y_text(t)).x);
    a.x = min.x + pad + ylabel_w + wmax + 8;
    b.x = max.x - pad - 14 - right_reserve;
    // Whole pixels, so the frame, grid and ticks are crisp 1-px lines.
    a = ImVec2(std::round(a.x), std::round(a.y));
    b = ImVec2(std::round(b.x), std::round(b.y));
    const int nx = std::max(2, static_cast<int>((b.x - a.x) / 90));
    if (cat_x) {
      float lw = 0;
      for (const std::string& l : data.x_tick_labels) lw = std::max(lw, TextSize(tick_font, l).x);
      L.x_ticks = CategoryTicks(data.x_tick_labels.size(), (b.x - a.x) / (lw + 12));
      ex = 0;
    } else {
      L.x_ticks = NiceTicks(x0, x1, nx, &xstep);
      ex = AxisExponent(x0, x1);
    }
  };
  // Same metres per pixel on both axes: widen whichever range is too narrow.
  auto equalize = [&]() {
    const double w = b.x - a.x, h = b.y - a.y;
    const double sx = (x1 - x0) / w, sy = (y1 - y0) / h;
    if (sx > sy) {
      const double c = 0.5 * (y0 + y1), half = 0.5 * sx * h;
      y0 = c - half, y1 = c + half;
    } else {
      const double c = 0.5 * (x0 + x1), half = 0.5 * sy * w;
      x0 = c - half, x1 = c + half;
    }
    layout();
  };
  layout();
  if (data.equal_aspect) equalize();

  // ---- legend: pick the corner that covers the fewest data points; if all cover some, make
  // headroom above the data (not for equal-aspect plots, which keep their scale) ----
  std::vector<int> legend_items;
  for (std::size_t i = 0; i < data.series.size(); ++i)
    if (!data.series[i].label.empty()) legend_items.push_back(static_cast<int>(i));
  ImVec2 leg_size(0, 0);
  const float row_h = cv.FontSize(label_font) + 4, sample_w = 26;
  int leg_cols = 1;
  float col_w = 0;
  if (!legend_items.empty()) {
    float wmax = 0;
    for (int i : legend_items)
      wmax = std::max(wmax, TextSize(label_font, Shorten(data.series[i].label, kLegendBytes)).x);
    col_w = sample_w + 14 + wmax + 8;
    // A tall legend goes to several columns, so it fits in a corner of a short plot.
    const int n = static_cast<int>(legend_items.size());
    while (leg_cols < 4 && leg_cols < n &&
           row_h * ((n + leg_cols - 1) / leg_cols) + 8 > 0.4f * (b.y - a.y) &&
           col_w * (leg_cols + 1) < 0.7f * (b.x - a.x))
      ++leg_cols;
    const int rows = (n + leg_cols - 1) / leg_cols;
    leg_size = ImVec2(col_w * leg_cols, row_h * rows + 8);
  }
  auto corner_box = [&](int c, ImVec2& lo, ImVec2& hi) {
    const float m = 6;
    if (c < 0) {  // outside, right of the axes
      lo = ImVec2(b.x + 10, a.y);
      hi = ImVec2(lo.x + leg_size.x, lo.y + leg_size.y);
      return;
    }
    lo.x = (c & 1) ? b.x - m - leg_size.x : a.x + m;
    lo.y = (c & 2) ? b.y - m - leg_size.y : a.y + m;
    hi = ImVec2(lo.x + leg_size.x, lo.y + leg_size.y);
  };
  auto count_inside = [&](ImVec2 lo, ImVec2 hi) {
    long count = 0;
    const double sx = (b.x - a.x) / (x1 - x0), sy = (b.y - a.y) / (y1 - y0);
    int bar_j = 0;
    for (const auto& s : data.series) {
      const std::size_t n = std::min(s.x.size(), s.y.size());
      const std::size_t stride = std::max<std::size_t>(1, n / 3000);
      const double dx = s.bars ? BarSlotOf(bar_j++, bar_series).offset : 0.0;
      for (std::size_t i = 0; i < n; i += stride) {
        const double px = a.x + (s.x[i] + dx - x0) * sx;
        // A bar covers its whole height up to the top of its error bar.
        const double top = s.bars ? std::max(s.y[i], At(s.err_hi, i)) : s.y[i];
        const double bottom = s.bars ? std::min(0.0, s.y[i]) : s.y[i];
        const double py_top = b.y - (top - y0) * sy, py_bottom = b.y - (bottom - y0) * sy;
        if (px >= lo.x - 4 && px <= hi.x + 4 && py_top <= hi.y + 4 && py_bottom >= lo.y - 4)
          ++count;
      }
    }
    for (double r : data.reference_lines) {
      const double py = b.y - (r - y0) * sy;
      if (py >= lo.y - 3 && py <= hi.y + 3) count += 50;
    }
    return count;
  };
  int corner = 1;  // top-right
  if (!legend_items.empty()) {
    long best = -1;
    for (int c : {1, 0, 3, 2}) {
      ImVec2 lo, hi;
      corner_box(c, lo, hi);
      const long n = count_inside(lo, hi);
      if (best < 0 || n < best) best = n, corner = c;
    }
    const float f = (leg_size.y + 12) / std::max(1.0f, b.y - a.y);
    if (best > 0 && !data.equal_aspect && f < 0.45f) {
      // Raise the top of the y range until the top band of height f is empty of data.
      y1 = (ry.hi + ypad * 0.3 - y0 * f) / (1 - f);
      layout();
      long best2 = -1;
      for (int c : {1, 0}) {
        ImVec2 lo, hi;
        corner_box(c, lo, hi);
        const long n = count_inside(lo, hi);
        if (best2 < 0 || n < best2) best2 = n, corner = c;
      }
    } else if (best > 0) {
      // No free corner and no room above the data: the legend goes outside, right of the axes,
      // in as many columns as its height needs.
      const int n = static_cast<int>(legend_items.size());
      const float avail_h = std::max(row_h, b.y - a.y - 8);
      const int rows = std::max(1, static_cast<int>(avail_h / row_h));
      const int cols = (n + rows - 1) / rows;
      const float w = cols * col_w;
      if (w < 0.4f * (max.x - min.x)) {
        leg_cols = cols;
        leg_size = ImVec2(w, row_h * ((n + cols - 1) / cols) + 8);
        right_reserve = w + 4;
        layout();
        if (data.equal_aspect) equalize();
        corner = -1;
      }
    }
  }
  L.area_min = a, L.area_max = b;
  L.x0 = x0, L.x1 = x1, L.y0 = y0, L.y1 = y1;
  auto X = [&](double v) { return static_cast<float>(a.x + (v - x0) * (b.x - a.x) / (x1 - x0)); };
  auto Y = [&](double v) { return static_cast<float>(b.y - (v - y0) * (b.y - a.y) / (y1 - y0)); };

  // ---- title, grid, ticks, labels ----
  if (title_h > 0) {
    // Centred over the data, kept inside the figure; a title wider than the figure is cut at a
    // character boundary and ends in "...".
    const float avail = std::max(0.0f, max.x - min.x - 2 * pad);
    std::string title = data.title;
    ImVec2 ts = TextSize(title_font, title);
    if (ts.x > avail) {
      while (!title.empty() && TextSize(title_font, title + "...").x > avail) {
        while (!title.empty() && (static_cast<unsigned char>(title.back()) & 0xC0) == 0x80)
          title.pop_back();  // UTF-8 continuation bytes, then their lead byte
        if (!title.empty()) title.pop_back();
      }
      title += "...";
      ts = TextSize(title_font, title);
    }
    const float x = std::max(min.x + pad, std::min(0.5f * (a.x + b.x) - ts.x / 2, max.x - pad - ts.x));
    Text(title_font, ImVec2(x, min.y + pad), th.text, title);
  }
  // Grid and ticks as 1-px rectangles on whole pixels (sharp on screen and in PNGs).
  auto px_col = [&](double v) { return std::floor(X(v)); };
  auto px_row = [&](double v) { return std::floor(Y(v)); };
  if (!heat) {  // a heatmap's cells are its grid
    for (double t : L.x_ticks)
      cv.FillRect(ImVec2(px_col(t), a.y), ImVec2(px_col(t) + 1, b.y), th.grid);
    for (double t : L.y_ticks)
      cv.FillRect(ImVec2(a.x, px_row(t)), ImVec2(b.x, px_row(t) + 1), th.grid);
  }
  for (double t : L.x_ticks) {
    const float x = X(t);
    cv.FillRect(ImVec2(px_col(t), b.y - 5), ImVec2(px_col(t) + 1, b.y), th.axis);
    const std::string s = x_text(t);
    const ImVec2 ts = TextSize(tick_font, s);
    Text(tick_font, ImVec2(x - ts.x / 2, b.y + 5), th.text, s);
  }
  for (double t : L.y_ticks) {
    const float y = Y(t);
    cv.FillRect(ImVec2(a.x, px_row(t)), ImVec2(a.x + 5, px_row(t) + 1), th.axis);
    const std::string s = y_text(t);
    const ImVec2 ts = TextSize(tick_font, s);
    Text(tick_font, ImVec2(a.x - 6 - ts.x, y - ts.y / 2), th.text, s);
  }
  if (ey != 0) Text(tick_font, ImVec2(a.x, a.y - tick_h - 3), th.text, PowerLabel(ey));
  if (ex != 0) {
    const std::string s = PowerLabel(ex);
    Text(tick_font, ImVec2(b.x - TextSize(tick_font, s).x, b.y + 5 + tick_h + 2), th.text, s);
  }
  if (!data.x_label.empty()) {
    const ImVec2 ts = TextSize(label_font, data.x_label);
    Text(label_font, ImVec2(0.5f * (a.x + b.x) - ts.x / 2, max.y - pad - ts.y), th.text,
         data.x_label);
  }
  if (!data.y_label.empty())
    cv.TextVertical(ImVec2(min.x + pad + cv.FontSize(label_font) / 2, 0.5f * (a.y + b.y)),
                    label_font, th.text, data.y_label);

  // ---- data ----
  cv.PushClip(a, b);
  if (heat) {
    const PlotHeatmap& h = data.heatmap;
    for (int r = 0; r < h.rows; ++r)
      for (int c = 0; c < h.columns; ++c) {
        const std::size_t k = static_cast<std::size_t>(r) * h.columns + c;
        const double v = k < h.values.size() ? h.values[k] : kNaN;
        const ImVec2 lo(std::round(X(c - 0.5)), std::round(Y(r + 0.5)));
        const ImVec2 hi(std::round(X(c + 0.5)), std::round(Y(r - 0.5)));
        const sim::Color col = HeatColor(v, heat_lo, heat_hi);
        cv.FillRect(lo, hi, col);
        // The value in the cell when it fits, dark on light colours and light on dark ones.
        // The cell's own label ("mean ± CI") when given and it fits, else the value alone.
        const std::string value = std::isfinite(v) ? sim::Sprintf("%.3g", v) : "no data";
        std::string txt = k < h.cell_labels.size() && !h.cell_labels[k].empty() ? h.cell_labels[k]
                                                                                : value;
        if (TextSize(tick_font, txt).x + 6 > hi.x - lo.x) txt = value;
        const ImVec2 ts = TextSize(tick_font, txt);
        if (ts.x + 6 <= hi.x - lo.x && ts.y + 4 <= hi.y - lo.y) {
          const bool light = 0.299f * col.r + 0.587f * col.g + 0.114f * col.b > 0.55f;
          Text(tick_font, ImVec2(0.5f * (lo.x + hi.x) - ts.x / 2, 0.5f * (lo.y + hi.y) - ts.y / 2),
               light ? sim::Color{0.08f, 0.08f, 0.08f, 1} : sim::Color{1, 1, 1, 1}, txt);
        }
      }
  }
  for (const auto& s : data.series)
    if (!s.band_lo.empty())
      DrawBand(cv, s, th.Series(s.color, s.style_index, false).color.WithAlpha(s.band_alpha),
               [&](double x, double y) { return ImVec2(X(x), Y(y)); });
  for (double r : data.reference_lines)
    cv.Line(ImVec2(a.x, Y(r)), ImVec2(b.x, Y(r)), {th.reference, 1.2f, LineDash::Dashes(6, 4)});
  if (!data.error.empty()) Text(label_font, ImVec2(a.x + 8, a.y + 8), th.error, data.error);
  // Bars from zero in their slot of each category, outlined, with their error bars.
  int bar_j = 0;
  for (const auto& s : data.series) {
    if (!s.bars) continue;
    const SeriesLook look = th.Series(s.color, s.style_index, false);
    const BarSlot slot = BarSlotOf(bar_j++, bar_series);
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      const double c = s.x[i] + slot.offset, hw = 0.5 * slot.width;
      const ImVec2 lo(std::round(X(c - hw)), std::round(Y(std::max(0.0, s.y[i]))));
      const ImVec2 hi(std::round(X(c + hw)), std::round(Y(std::min(0.0, s.y[i]))));
      cv.FillRect(lo, hi, look.color.WithAlpha(0.75f));
      cv.StrokeRect(lo, hi, look.color, 1.0f);
      const double e0 = At(s.err_lo, i), e1 = At(s.err_hi, i);
      if (std::isfinite(e0) && std::isfinite(e1)) {
        const float xc = X(c),
                    cap = static_cast<float>(0.25 * slot.width * (b.x - a.x) / (x1 - x0));
        const Stroke err{th.text, 1.5f};
        cv.Line(ImVec2(xc, Y(e0)), ImVec2(xc, Y(e1)), err);
        for (double e : {e0, e1}) cv.Line(ImVec2(xc - cap, Y(e)), ImVec2(xc + cap, Y(e)), err);
      }
    }
  }
  for (const auto& s : data.series) {
    if (s.bars) continue;
    SeriesLook look = th.Series(s.color, s.style_index, s.dashed);
    if (s.dash_style > 0) look.dash = DashStyle(s.dash_style);
    const Stroke stroke{look.color, line_w, look.dash};
    for (const auto& run : ScreenRuns(s, x0, x1, y0, y1, a, b)) {
      if (s.markers_only) {
        for (const ImVec2& p : run) {
          if (look.hollow_markers)
            cv.StrokeCircle(p, 2.6f, look.color, 1.2f);
          else
            cv.FillCircle(p, 2.6f, look.color);
        }
      } else if (run.size() > 1) {
        cv.Polyline(run.data(), static_cast<int>(run.size()), stroke);
      } else {
        cv.FillCircle(run[0], line_w, look.color);
      }
    }
  }
  if (std::isfinite(data.marker_x))
    cv.Line(ImVec2(X(data.marker_x), a.y), ImVec2(X(data.marker_x), b.y),
            {th.marker, 1.5f, LineDash::Dashes(5, 3)});
  if (std::isfinite(cursor_x) && cursor_x >= x0 && cursor_x <= x1)
    cv.Line(ImVec2(X(cursor_x), a.y), ImVec2(X(cursor_x), b.y), {th.cursor, 1.0f});
  cv.PopClip();
  // The frame: 1-px lines on the pixel column/row just outside the data area on the left and
  // top, and on the last column/row of it on the right and bottom.
  cv.StrokeRect(ImVec2(a.x - 1, a.y - 1), ImVec2(b.x + 1, b.y + 1), th.axis, 1.0f);

  // ---- colour bar of a heatmap: the map from bottom (min) to top (max), ticks on its right ----
  if (heat && !cticks.empty()) {
    const float x0b = b.x + 12, x1b = x0b + 16;
    const int steps = 64;
    for (int k = 0; k < steps; ++k) {
      const float ya = b.y - (b.y - a.y) * k / steps, yb = b.y - (b.y - a.y) * (k + 1) / steps;
      cv.FillRect(ImVec2(x0b, std::floor(yb)), ImVec2(x1b, std::ceil(ya)), Viridis((k + 0.5) / steps));
    }
    cv.StrokeRect(ImVec2(x0b - 1, a.y - 1), ImVec2(x1b + 1, b.y + 1), th.axis, 1.0f);
    auto cy = [&](double v) {
      const double f = heat_hi > heat_lo ? (v - heat_lo) / (heat_hi - heat_lo) : 0.5;
      return static_cast<float>(b.y - f * (b.y - a.y));
    };
    float wmax = 0;
    for (double t : cticks) {
      const float y = std::floor(cy(t));
      cv.FillRect(ImVec2(x1b, y), ImVec2(x1b + 4, y + 1), th.axis);
      const std::string s = FormatTick(t, cstep, ce);
      const ImVec2 ts = TextSize(tick_font, s);
      wmax = std::max(wmax, ts.x);
      Text(tick_font, ImVec2(x1b + 6, y - ts.y / 2), th.text, s);
    }
    if (ce != 0) Text(tick_font, ImVec2(x0b, a.y - tick_h - 3), th.text, PowerLabel(ce));
    if (!data.heatmap.value_label.empty())
      cv.TextVertical(ImVec2(x1b + 6 + wmax + 8 + cv.FontSize(label_font) / 2, 0.5f * (a.y + b.y)),
                      label_font, th.text, data.heatmap.value_label);
  }

  // ---- legend ----
  if (!legend_items.empty()) {
    ImVec2 lo, hi;
    corner_box(corner, lo, hi);
    L.legend_min = lo, L.legend_max = hi;
    cv.FillRect(lo, hi, th.legend_fill, 3.0f);
    cv.StrokeRect(lo, hi, th.legend_border, 1.0f, 3.0f);
    for (std::size_t k = 0; k < legend_items.size(); ++k) {
      const auto& s = data.series[legend_items[k]];
      SeriesLook look = th.Series(s.color, s.style_index, s.dashed);
      if (s.dash_style > 0) look.dash = DashStyle(s.dash_style);
      const float x = lo.x + col_w * static_cast<float>(k % leg_cols);
      const float y = lo.y + 4 + row_h * static_cast<float>(k / leg_cols);
      const float cy = y + row_h / 2;
      const ImVec2 p0(x + 7, cy), p1(x + 7 + sample_w, cy);
      if (s.bars) {
        const ImVec2 lo(p0.x + 4, cy - 6), hi(p1.x - 4, cy + 6);
        cv.FillRect(lo, hi, look.color.WithAlpha(0.75f));
        cv.StrokeRect(lo, hi, look.color, 1.0f);
      } else if (s.markers_only) {
        const ImVec2 c(0.5f * (p0.x + p1.x), cy);
        if (look.hollow_markers)
          cv.StrokeCircle(c, 3.0f, look.color, 1.2f);
        else
          cv.FillCircle(c, 3.0f, look.color);
      } else {
        cv.Line(p0, p1, {look.color, line_w, look.dash});
      }
      Text(label_font, ImVec2(p1.x + 7, y + 2), th.text, Shorten(s.label, kLegendBytes));
    }
  }
  return L;
}

}  // namespace formsim::app
