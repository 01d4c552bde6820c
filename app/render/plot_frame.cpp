#include "app/render/plot_frame.hpp"

#include <algorithm>
#include <cmath>

#include "app/render/label_markup.hpp"
#include "app/render/plot_log_scale.hpp"

namespace formsim::app::plot_detail {
namespace {

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

}  // namespace

BarSlot BarSlotOf(int j, int n) {
  const double w = 0.8 / std::max(1, n);
  return {-0.4 + w * (j + 0.5), w};
}

double At(const std::vector<double>& v, std::size_t i) {
  return i < v.size() ? v[i] : kNaN;
}

std::string PowerLabel(int e) {
  return "×10" + SuperscriptInt(e);
}

// Distance errors of order 1e-4 read better as "1.5" with "×10⁻⁴" than as "0.00015".
int AxisExponent(double lo, double hi) {
  const double m = std::max(std::abs(lo), std::abs(hi));
  if (m == 0 || !std::isfinite(m)) return 0;
  if (m < 1e-2 || m >= 1e5) return static_cast<int>(std::floor(std::log10(m)));
  return 0;
}

PlotFrame::PlotFrame(Canvas& canvas, ImVec2 min_, ImVec2 max_, const PlotData& data_,
                     const PlotStyle& style)
    : cv(canvas),
      data(data_),
      st(style),
      th(*style.theme),
      min(min_),
      max(max_),
      line_w(style.line_width * style.theme->line_scale) {}

float PlotFrame::X(double v) const {
  return static_cast<float>(a.x + (v - x0) * (b.x - a.x) / (x1 - x0));
}

float PlotFrame::Y(double v) const {
  return static_cast<float>(b.y - (v - y0) * (b.y - a.y) / (y1 - y0));
}

std::string PlotFrame::XText(double t) const {
  return cat_x ? data.x_tick_labels[static_cast<std::size_t>(std::llround(t))]
               : FormatTick(t, xstep, ex);
}

std::string PlotFrame::YText(double t) const {
  if (log_y) return DecadeLabel(t, ystep);
  return cat_y ? data.y_tick_labels[static_cast<std::size_t>(std::llround(t))]
               : FormatTick(t, ystep, ey);
}

void PlotFrame::Ranges() {
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
  for (const auto& s : data.series) bar_series += s.bars;
  // Heatmaps and categorical axes: half a cell of room around the first and last category.
  heat = !data.heatmap.empty();
  cat_x = !data.x_tick_labels.empty(), cat_y = !data.y_tick_labels.empty();
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
  x0 = rx.lo - data.x_margin * (rx.hi - rx.lo), x1 = rx.hi + data.x_margin * (rx.hi - rx.lo);
  ypad = heat || cat_y ? 0.0 : 0.06 * (ry.hi - ry.lo);
  y0 = ry.lo - ypad, y1 = ry.hi + ypad;
  if (bar_series > 0 && ry.lo >= 0.0) y0 = 0.0;  // bars stand on the axis
  if (data.equal_aspect) {
    const double xpad = 0.06 * (x1 - x0);
    x0 -= xpad, x1 += xpad;
  }
}

// Margins depend on the tick labels' widths, so the ticks come first.
void PlotFrame::Layout() {
  pad = st.padding;
  title_h = (st.show_title && !data.title.empty()) ? cv.FontSize(st.title_font) + 8 : 0;
  tick_h = cv.FontSize(st.tick_font);
  xlabel_h = data.x_label.empty() ? 0 : cv.FontSize(st.label_font) + 4;
  ylabel_w = data.y_label.empty() ? 0 : cv.FontSize(st.label_font) + 6;
  if (heat) {
    HeatRange(data.heatmap, &heat_lo, &heat_hi);
    if (std::isfinite(heat_lo)) {
      cticks = NiceTicks(heat_lo, heat_hi, 6, &cstep);
      ce = AxisExponent(heat_lo, heat_hi);
    }
    float wmax = 0;
    for (double t : cticks)
      wmax = std::max(wmax, cv.TextSize(st.tick_font, FormatTick(t, cstep, ce)).x);
    right_reserve = 12 + 16 + 6 + wmax + 8 +
                    (data.heatmap.value_label.empty() ? 0 : cv.FontSize(st.label_font) + 6);
  }
  LayOutOnce();
  if (data.equal_aspect) Equalize();
}

void PlotFrame::LayOutOnce() {
  const FontRole tick_font = st.tick_font;
  const float top = min.y + pad + title_h + tick_h * 0.6f;
  b.y = max.y - pad - xlabel_h - tick_h - 8 - bottom_reserve;
  // Room above the axes for the shared power of ten, or a log axis's note of dropped values.
  const bool above = log_y ? log_dropped > 0 : AxisExponent(y0, y1) != 0;
  a.y = top + (above ? tick_h + 2 : 0);
  const int ny = std::max(2, static_cast<int>((b.y - a.y) / 45));
  if (cat_y) {
    L.y_ticks = CategoryTicks(data.y_tick_labels.size(), (b.y - a.y) / (tick_h + 6));
    ey = 0;
  } else if (log_y) {
    L.y_ticks = DecadeTicks(y0, y1, ny, &ystep);
    ey = 0;
  } else {
    L.y_ticks = NiceTicks(y0, y1, ny, &ystep);
    ey = AxisExponent(y0, y1);
  }
  float wmax = 0;
  for (double t : L.y_ticks) wmax = std::max(wmax, cv.TextSize(tick_font, YText(t)).x);
  a.x = min.x + pad + ylabel_w + wmax + 8;
  b.x = max.x - pad - 14 - right_reserve;
  // Whole pixels, so the frame, grid and ticks are crisp 1-px lines.
  a = ImVec2(std::round(a.x), std::round(a.y));
  b = ImVec2(std::round(b.x), std::round(b.y));
  const int nx = std::max(2, static_cast<int>((b.x - a.x) / 90));
  if (cat_x) {
    float lw = 0;
    for (const std::string& l : data.x_tick_labels) lw = std::max(lw, cv.TextSize(tick_font, l).x);
    L.x_ticks = CategoryTicks(data.x_tick_labels.size(), (b.x - a.x) / (lw + 12));
    ex = 0;
  } else {
    L.x_ticks = NiceTicks(x0, x1, nx, &xstep);
    ex = AxisExponent(x0, x1);
  }
}

// Same metres per pixel on both axes: widen whichever range is too narrow.
void PlotFrame::Equalize() {
  const double w = b.x - a.x, h = b.y - a.y;
  const double sx = (x1 - x0) / w, sy = (y1 - y0) / h;
  if (sx > sy) {
    const double c = 0.5 * (y0 + y1), half = 0.5 * sx * h;
    y0 = c - half, y1 = c + half;
  } else {
    const double c = 0.5 * (x0 + x1), half = 0.5 * sy * w;
    x0 = c - half, x1 = c + half;
  }
  LayOutOnce();
}

void PlotFrame::CornerBox(int c, ImVec2& lo, ImVec2& hi) const {
  const float m = 6;
  if (c < 0) {  // below the axes and their x label, centred under the axes, inside the figure
    lo.x = std::max(min.x + pad,
                    std::min(0.5f * (a.x + b.x) - 0.5f * leg_size.x, max.x - pad - leg_size.x));
    lo.y = max.y - pad - leg_size.y;
    hi = ImVec2(lo.x + leg_size.x, lo.y + leg_size.y);
    return;
  }
  lo.x = (c & 1) ? b.x - m - leg_size.x : a.x + m;
  lo.y = (c & 2) ? b.y - m - leg_size.y : a.y + m;
  hi = ImVec2(lo.x + leg_size.x, lo.y + leg_size.y);
}

// Data points (and reference lines, which count as many) within the box, sampled.
long PlotFrame::CountInside(ImVec2 lo, ImVec2 hi) const {
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
      if (px >= lo.x - 4 && px <= hi.x + 4 && py_top <= hi.y + 4 && py_bottom >= lo.y - 4) ++count;
    }
  }
  for (double r : data.reference_lines) {
    const double py = b.y - (r - y0) * sy;
    if (py >= lo.y - 3 && py <= hi.y + 3) count += 50;
  }
  return count;
}

// The corner that covers the fewest data points; if all cover some, headroom above the data
// (not for equal-aspect plots, which keep their scale), else outside right of the axes.
void PlotFrame::PlaceLegend() {
  for (std::size_t i = 0; i < data.series.size(); ++i)
    if (!data.series[i].label.empty()) legend_items.push_back(static_cast<int>(i));
  row_h = cv.FontSize(st.label_font) + 4;
  if (!legend_items.empty()) {
    float wmax = 0;
    for (int i : legend_items)
      wmax = std::max(wmax, LegendTextSize(cv, st.label_font, data.series[i].label).x);
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
  if (!legend_items.empty()) {
    long best = -1;
    for (int c : {1, 0, 3, 2}) {
      ImVec2 lo, hi;
      CornerBox(c, lo, hi);
      const long n = CountInside(lo, hi);
      if (best < 0 || n < best) best = n, corner = c;
    }
    const float f = (leg_size.y + 12) / std::max(1.0f, b.y - a.y);
    // Over a heatmap every corner hides cells and its cells are not a range to raise: below.
    if (best > 0 && !data.equal_aspect && !heat && f < 0.45f) {
      // Raise the top of the y range until the top band of height f is empty of data.
      y1 = (ry.hi + ypad * 0.3 - y0 * f) / (1 - f);
      LayOutOnce();
      long best2 = -1;
      for (int c : {1, 0}) {
        ImVec2 lo, hi;
        CornerBox(c, lo, hi);
        const long n = CountInside(lo, hi);
        if (best2 < 0 || n < best2) best2 = n, corner = c;
      }
    } else if (best > 0 || heat) {
      // No free corner and no room above the data: the legend goes below the axes, in as many
      // columns as fit the figure's width (the axes keep their width).
      // Each column as wide as its own widest entry: one long label (a pinned run's) does not
      // make every column that wide, and the legend keeps few rows, the axes their height.
      const int n = static_cast<int>(legend_items.size());
      std::vector<float> item_w;
      for (int i : legend_items)
        item_w.push_back(sample_w + 14 + LegendTextSize(cv, st.label_font, data.series[i].label).x + 8);
      const float room = max.x - min.x - 2 * pad;
      for (int cols = n; cols >= 1; --cols) {
        std::vector<float> w(static_cast<std::size_t>(cols), 0.0f);
        for (int k = 0; k < n; ++k) w[k % cols] = std::max(w[k % cols], item_w[k]);
        float total = 0;
        col_x.clear();
        for (float c : w) col_x.push_back(total), total += c;
        if (total <= room || cols == 1) {
          leg_cols = cols;
          leg_size.x = total;
          break;
        }
      }
      const int rows = (n + leg_cols - 1) / leg_cols;
      leg_size.y = row_h * rows + 8;
      bottom_reserve = leg_size.y + 6;
      LayOutOnce();
      if (data.equal_aspect) Equalize();
      corner = -1;
    }
  }
  L.area_min = a, L.area_max = b;
  L.x0 = x0, L.x1 = x1, L.y0 = y0, L.y1 = y1;
}

}  // namespace formsim::app::plot_detail
