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
