#include "sim/core/figure_spec.hpp"

namespace formsim::sim {

SeriesSpec Line(const std::string& label, const std::string& column, int color_index, bool dashed) {
  SeriesSpec s;
  s.label = label;
  s.column = column;
  s.color_index = color_index;
  s.dashed = dashed;
  return s;
}

SeriesSpec Path(const std::string& label, const std::string& x_column, const std::string& y_column,
                int color_index, bool dashed) {
  SeriesSpec s = Line(label, y_column, color_index, dashed);
  s.x_column = x_column;
  return s;
}

SeriesSpec Markers(const std::string& label, int color_index) {
  SeriesSpec s = Line(label, "", color_index);
  s.markers_only = true;
  return s;
}

SeriesSpec Bars(const std::string& label, std::vector<double> heights, std::vector<double> lo,
                std::vector<double> hi, int color_index) {
  SeriesSpec s = Line(label, "", color_index);
  s.bars = true;
  s.x.resize(heights.size());
  for (std::size_t k = 0; k < heights.size(); ++k) s.x[k] = static_cast<double>(k);
  s.y = std::move(heights);
  s.err_lo = std::move(lo);
  s.err_hi = std::move(hi);
  return s;
}

FigureSpec BarFigure(const std::string& id, const std::string& title, const std::string& y_label,
                     std::vector<std::string> categories, std::vector<SeriesSpec> series) {
  FigureSpec f;
  f.id = id;
  f.title = title;
  f.x_label.clear();
  f.y_label = y_label;
  f.categories = std::move(categories);
  f.series = std::move(series);
  return f;
}

FigureSpec TimeFigure(const std::string& id, const std::string& title, const std::string& y_label,
                      std::vector<SeriesSpec> series) {
  FigureSpec f;
  f.id = id;
  f.title = title;
  f.y_label = y_label;
  f.series = std::move(series);
  return f;
}

FigureSpec PlaneFigure(const std::string& id, const std::string& title,
                       std::vector<SeriesSpec> series) {
  FigureSpec f;
  f.id = id;
  f.title = title;
  f.x_label = "x [m]";
  f.y_label = "y [m]";
  f.equal_aspect = true;
  f.series = std::move(series);
  return f;
}

}  // namespace formsim::sim
