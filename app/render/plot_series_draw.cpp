// The data stage: heatmap cells, bands, reference lines, bars, lines and markers, the marker
// line and time cursor, clipped to the data area; then the frame around it.
#include <algorithm>
#include <cmath>
#include <functional>

#include "app/render/plot_frame.hpp"
#include "app/render/plot_marker.hpp"
#include "app/render/polyline_simplify.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app::plot_detail {
namespace {

// Pixels between the markers along a line (print theme).
constexpr float kMarkerSpacing = 60.0f;

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

sim::Color HeatColor(double v, double lo, double hi) {
  if (!std::isfinite(v)) return sim::Color{0.84f, 0.84f, 0.84f, 1};
  return Viridis(hi > lo ? (v - lo) / (hi - lo) : 0.5);
}

// Shades the band of a series: the area between the curves band_lo and band_hi, for points in
// any x order (sorted here; a sweep's points may come in any order). A point whose band is not
// finite leaves a gap. Points closer than a pixel share one column (the envelope of their
// bands), so a dense time series gives at most one column per pixel.
void DrawBand(Canvas& cv, const PlotSeries& s, sim::Color col,
              const std::function<ImVec2(double, double)>& to_screen) {
  const std::size_t n = std::min({s.x.size(), s.band_lo.size(), s.band_hi.size()});
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(s.x[i])) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t i, std::size_t j) { return s.x[i] < s.x[j]; });
  std::vector<ImVec2> upper, lower;
  auto flush = [&]() {
    if (upper.size() >= 2)
      cv.FillBetween(upper.data(), lower.data(), static_cast<int>(upper.size()), col);
    upper.clear();
    lower.clear();
  };
  float column_x = 0;  // where the last column started
  for (std::size_t i : order) {
    if (!std::isfinite(s.band_lo[i]) || !std::isfinite(s.band_hi[i])) {
      flush();
      continue;
    }
    const ImVec2 hi = to_screen(s.x[i], s.band_hi[i]), lo = to_screen(s.x[i], s.band_lo[i]);
    if (!upper.empty() && hi.x - column_x < 1.0f) {
      // Same pixel column: the envelope of its points (upper keeps the top on screen).
      ImVec2 &u = upper.back(), &l = lower.back();
      const float top = std::min({u.y, l.y, hi.y, lo.y}), bottom = std::max({u.y, l.y, hi.y, lo.y});
      u.y = top, l.y = bottom;
      continue;
    }
    column_x = hi.x;
    upper.push_back(hi);
    lower.push_back(lo);
  }
  flush();
}

// Markers along a screen polyline (the print theme's way to tell lines apart): the first after
// `offset` pixels of the line (staggered per series so markers of overlapping lines do not sit
// on each other), then each `spacing` pixels (straight-line distance) from the one before, so a
// noisy signal that zigzags in place does not get a marker at every sample.
void MarkersAlong(Canvas& cv, const std::vector<ImVec2>& run, float offset, float spacing,
                  const SeriesLook& look, float radius) {
  if (run.empty()) return;
  if (run.size() == 1) {
    DrawMarker(cv, run[0], radius, look.marker, look.color, look.hollow_markers);
    return;
  }
  bool placed = false;
  ImVec2 last(0, 0);
  float walked = 0;
  for (std::size_t k = 1; k < run.size(); ++k) {
    ImVec2 p = run[k - 1];
    const ImVec2 q = run[k];
    if (!placed) {
      const float len = std::hypot(q.x - p.x, q.y - p.y);
      if (walked + len < offset) {
        walked += len;
        continue;
      }
      const float t = len > 0 ? (offset - walked) / len : 0.0f;
      last = ImVec2(p.x + t * (q.x - p.x), p.y + t * (q.y - p.y));
      DrawMarker(cv, last, radius, look.marker, look.color, look.hollow_markers);
      placed = true;
      p = last;
    }
    // Points on p->q at `spacing` from the last marker: |p + t (q - p) - last| = spacing.
    for (int guard = 0; guard < 1000; ++guard) {
      const float dx = q.x - p.x, dy = q.y - p.y, fx = p.x - last.x, fy = p.y - last.y;
      const float A = dx * dx + dy * dy, B = 2 * (fx * dx + fy * dy),
                  C = fx * fx + fy * fy - spacing * spacing;
      if (!(A > 0)) break;
      const float disc = B * B - 4 * A * C;
      if (disc < 0) break;
      const float t = (-B + std::sqrt(disc)) / (2 * A);
      if (!(t >= 0 && t <= 1)) break;
      last = ImVec2(p.x + t * dx, p.y + t * dy);
      DrawMarker(cv, last, radius, look.marker, look.color, look.hollow_markers);
      p = last;
    }
  }
}

}  // namespace

void PlotFrame::DrawSeries(double cursor_x) {
  const FontRole label_font = st.label_font, tick_font = st.tick_font;
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
        const std::string value = std::isfinite(v) ? sim::FormatSignificant(v, 3) : "no data";
        std::string txt = k < h.cell_labels.size() && !h.cell_labels[k].empty() ? h.cell_labels[k]
                                                                                : value;
        if (cv.TextSize(tick_font, txt).x + 6 > hi.x - lo.x) txt = value;
        const ImVec2 ts = cv.TextSize(tick_font, txt);
        if (h.cell_values && ts.x + 6 <= hi.x - lo.x && ts.y + 4 <= hi.y - lo.y) {
          const bool light = 0.299f * col.r + 0.587f * col.g + 0.114f * col.b > 0.55f;
          cv.Text(ImVec2(0.5f * (lo.x + hi.x) - ts.x / 2, 0.5f * (lo.y + hi.y) - ts.y / 2),
                  tick_font, light ? sim::Color{0.08f, 0.08f, 0.08f, 1} : sim::Color{1, 1, 1, 1},
                  txt);
        }
      }
  }
  for (const auto& s : data.series)
    if (!s.band_lo.empty())
      DrawBand(cv, s, th.Series(s.color, s.style_index, false).color.WithAlpha(s.band_alpha),
               [&](double x, double y) { return ImVec2(X(x), Y(y)); });
  for (double r : data.reference_lines)
    cv.Line(ImVec2(a.x, Y(r)), ImVec2(b.x, Y(r)), {th.reference, 1.2f, LineDash::Dashes(6, 4)});
  if (!data.error.empty()) cv.Text(ImVec2(a.x + 8, a.y + 8), label_font, th.error, data.error);
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
    // Markers along a line (print): staggered per series, one each kMarkerSpacing pixels.
    const float marker_offset = 8.0f + static_cast<float>((std::max(0, s.style_index) * 17) % 60);
    for (const auto& run : ScreenRuns(s, x0, x1, y0, y1, a, b)) {
      if (s.markers_only) {
        const MarkerShape shape =
            look.marker == MarkerShape::kNone ? MarkerShape::kCircle : look.marker;
        for (const ImVec2& p : run) DrawMarker(cv, p, 2.6f, shape, look.color, look.hollow_markers);
      } else if (run.size() > 1) {
        cv.Polyline(run.data(), static_cast<int>(run.size()), stroke);
        if (look.marker != MarkerShape::kNone)
          MarkersAlong(cv, run, marker_offset, kMarkerSpacing, look, 3.2f);
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
}

}  // namespace formsim::app::plot_detail
