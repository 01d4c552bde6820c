#include "app/export/figure_data.hpp"

#include "app/render/label_markup.hpp"

namespace formsim::app {

std::string FigureMarkupError(const sim::FigureSpec& spec) {
  auto check = [](const std::string& what, const std::string& text) {
    const std::string e = MarkupError(text);
    return e.empty() ? e : what + ": " + e;
  };
  for (const auto& [what, text] : {std::pair<const char*, const std::string&>{"title", spec.title},
                                   {"x label", spec.x_label},
                                   {"y label", spec.y_label}})
    if (std::string e = check(what, text); !e.empty()) return e;
  for (std::size_t i = 0; i < spec.series.size(); ++i)
    if (std::string e = check("series " + std::to_string(i + 1), spec.series[i].label); !e.empty())
      return e;
  return "";
}

bool IsTimePlot(const sim::FigureSpec& spec) {
  bool time = !spec.equal_aspect && spec.categories.empty() && !spec.series.empty();
  for (const sim::SeriesSpec& s : spec.series)
    time = time && (s.x_column.empty() || s.x_column == "t");
  return time;
}

PlotData ResolveFigure(const sim::FigureSpec& spec, const sim::Recorder& rec) {
  PlotData d;
  d.title = spec.title;
  d.x_label = spec.x_label;
  d.y_label = spec.y_label;
  d.reference_lines = spec.reference_lines;
  d.equal_aspect = spec.equal_aspect;
  d.marker_x = spec.marker_x;
  d.x_is_time = !spec.series.empty() && spec.categories.empty();
  d.x_tick_labels = spec.categories;
  d.error = FigureMarkupError(spec);
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const sim::SeriesSpec& s = spec.series[i];
    PlotSeries p;
    p.label = s.label;
    p.dashed = s.dashed;
    p.markers_only = s.markers_only;
    p.bars = s.bars;
    p.err_lo = s.err_lo;
    p.err_hi = s.err_hi;
    p.style_index = s.color_index >= 0 ? s.color_index : static_cast<int>(i);
    p.color = sim::PaletteColor(p.style_index);
    if (s.column.empty() || !(s.x_column.empty() || s.x_column == "t")) d.x_is_time = false;
    if (s.column.empty()) {
      p.x = s.x;
      p.y = s.y;
    } else {
      const int cy = rec.Column(s.column);
      const std::string xname = s.x_column.empty() ? "t" : s.x_column;
      const int cx = rec.Column(xname);
      if (cy < 0 || cx < 0) {
        d.error += (d.error.empty() ? "" : "; ") + std::string("no recorded column '") +
                   (cy < 0 ? s.column : xname) + "'";
        continue;
      }
      p.x = rec.Series(cx);
      p.y = rec.Series(cy);
    }
    d.series.push_back(std::move(p));
  }
  return d;
}

}  // namespace formsim::app
