// The stages that draw around the data: title, grid, ticks and axis labels; the heatmap's
// colour bar; the legend.
#include <algorithm>
#include <cmath>

#include "app/render/label_markup.hpp"
#include "app/render/plot_frame.hpp"
#include "app/render/plot_marker.hpp"


namespace formsim::app::plot_detail {

ImVec2 LegendTextSize(const Canvas& cv, FontRole font, const std::string& label) {
  return cv.LabelSize(font, ShortenMarkup(label, kLegendBytes));
}

void DrawLegendText(Canvas& cv, ImVec2 pos, FontRole font, sim::Color color,
                    const std::string& label) {
  cv.Label(pos, font, color, ShortenMarkup(label, kLegendBytes));
}

void PlotFrame::DrawAxes() {
  const FontRole title_font = st.title_font, label_font = st.label_font, tick_font = st.tick_font;
  if (title_h > 0) {
    // Centred over the data, kept inside the figure.
    const float avail = std::max(0.0f, max.x - min.x - 2 * pad);
    // A title wider than the figure is cut at a character boundary and ends in "…": the
    // longest cut that fits, found by halving (a title may be very long).
    std::string title = data.title;
    if (cv.LabelSize(title_font, title).x > avail) {
      std::size_t lo = 0, hi = 0;
      for (const MarkupRun& r : ParseMarkup(data.title).runs) hi += r.text.size();
      while (lo < hi) {
        const std::size_t mid = (lo + hi + 1) / 2;
        if (cv.LabelSize(title_font, ShortenMarkup(data.title, mid)).x <= avail)
          lo = mid;
        else
          hi = mid - 1;
      }
      title = ShortenMarkup(data.title, lo);
    }
    const ImVec2 ts = cv.LabelSize(title_font, title);
    const float x =
        std::max(min.x + pad, std::min(0.5f * (a.x + b.x) - ts.x / 2, max.x - pad - ts.x));
    cv.Label(ImVec2(x, min.y + pad), title_font, th.text, title);
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
    const std::string s = XText(t);
    const ImVec2 ts = cv.TextSize(tick_font, s);
    cv.Text(ImVec2(x - ts.x / 2, b.y + 5), tick_font, th.text, s);
  }
  for (double t : L.y_ticks) {
    const float y = Y(t);
    cv.FillRect(ImVec2(a.x, px_row(t)), ImVec2(a.x + 5, px_row(t) + 1), th.axis);
    const std::string s = YText(t);
    const ImVec2 ts = cv.TextSize(tick_font, s);
    cv.Text(ImVec2(a.x - 6 - ts.x, y - ts.y / 2), tick_font, th.text, s);
  }
  if (ey != 0) cv.Text(ImVec2(a.x, a.y - tick_h - 3), tick_font, th.text, PowerLabel(ey));
  if (log_y && log_dropped > 0)
    cv.Text(ImVec2(a.x, a.y - tick_h - 3), tick_font, th.text,
            "log y: " + std::to_string(log_dropped) + (log_dropped == 1 ? " value" : " values") +
                " ≤ 0 not drawn");
  if (ex != 0) {
    const std::string s = PowerLabel(ex);
    cv.Text(ImVec2(b.x - cv.TextSize(tick_font, s).x, b.y + 5 + tick_h + 2), tick_font, th.text, s);
  }
  if (!data.x_label.empty()) {
    const ImVec2 ts = cv.LabelSize(label_font, data.x_label);
    cv.Label(ImVec2(0.5f * (a.x + b.x) - ts.x / 2, max.y - pad - ts.y - bottom_reserve), label_font,
             th.text, data.x_label);
  }
  if (!data.y_label.empty())
    cv.LabelVertical(ImVec2(min.x + pad + cv.FontSize(label_font) / 2, 0.5f * (a.y + b.y)),
                     label_font, th.text, data.y_label);
}

// The map from bottom (min) to top (max), ticks on its right.
void PlotFrame::DrawColourBar() {
  if (!heat || cticks.empty()) return;
  const FontRole tick_font = st.tick_font, label_font = st.label_font;
  const float x0b = b.x + 12, x1b = x0b + 16;
  const int steps = 64;
  for (int k = 0; k < steps; ++k) {
    const float ya = b.y - (b.y - a.y) * k / steps, yb = b.y - (b.y - a.y) * (k + 1) / steps;
    cv.FillRect(ImVec2(x0b, std::floor(yb)), ImVec2(x1b, std::ceil(ya)),
                Viridis((k + 0.5) / steps));
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
    const ImVec2 ts = cv.TextSize(tick_font, s);
    wmax = std::max(wmax, ts.x);
    cv.Text(ImVec2(x1b + 6, y - ts.y / 2), tick_font, th.text, s);
  }
  if (ce != 0) cv.Text(ImVec2(x0b, a.y - tick_h - 3), tick_font, th.text, PowerLabel(ce));
  if (!data.heatmap.value_label.empty())
    cv.LabelVertical(ImVec2(x1b + 6 + wmax + 8 + cv.FontSize(label_font) / 2, 0.5f * (a.y + b.y)),
                     label_font, th.text, data.heatmap.value_label);
}

void PlotFrame::DrawLegend() {
  if (legend_items.empty()) return;
  ImVec2 lo, hi;
  CornerBox(corner, lo, hi);
  L.legend_min = lo, L.legend_max = hi;
  cv.FillRect(lo, hi, th.legend_fill, 3.0f);
  cv.StrokeRect(lo, hi, th.legend_border, 1.0f, 3.0f);
  for (std::size_t k = 0; k < legend_items.size(); ++k) {
    const auto& s = data.series[legend_items[k]];
    SeriesLook look = th.Series(s.color, s.style_index, s.dashed);
    if (s.dash_style > 0) look.dash = DashStyle(s.dash_style);
    const float x = lo.x + (col_x.empty() ? col_w * static_cast<float>(k % leg_cols)
                                          : col_x[static_cast<std::size_t>(k % leg_cols)]);
    const float y = lo.y + 4 + row_h * static_cast<float>(k / leg_cols);
    const float cy = y + row_h / 2;
    const ImVec2 p0(x + 7, cy), p1(x + 7 + sample_w, cy);
    if (s.bars) {
      const ImVec2 blo(p0.x + 4, cy - 6), bhi(p1.x - 4, cy + 6);
      cv.FillRect(blo, bhi, look.color.WithAlpha(0.75f));
      cv.StrokeRect(blo, bhi, look.color, 1.0f);
    } else if (s.markers_only) {
      const MarkerShape shape =
          look.marker == MarkerShape::kNone ? MarkerShape::kCircle : look.marker;
      DrawMarker(cv, ImVec2(0.5f * (p0.x + p1.x), cy), 3.0f, shape, look.color,
                 look.hollow_markers);
    } else {
      cv.Line(p0, p1, {look.color, line_w, look.dash});
      if (look.marker != MarkerShape::kNone)
        DrawMarker(cv, ImVec2(0.5f * (p0.x + p1.x), cy), 3.2f, look.marker, look.color,
                   look.hollow_markers);
    }
    DrawLegendText(cv, ImVec2(p1.x + 7, y + 2), st.label_font, th.text, s.label);
  }
}

}  // namespace formsim::app::plot_detail
