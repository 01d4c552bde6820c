#pragma once
/// \file Figures and tables an experiment describes (exported by --plots, drawn live in the GUI),
/// and builders for the figures every kind makes, so a kind lists its series and nothing else.

#include <limits>
#include <string>
#include <vector>

namespace formsim::sim {

/// One line of a figure: a recorded column against time (or against `x_column`), or inline data.
struct SeriesSpec {
  std::string label;
  std::string column;    ///< recorder column for y; empty when x/y inline data are given
  std::string x_column;  ///< empty: time ("t")
  std::vector<double> x, y;  ///< inline data (e.g. a membership function)
  int color_index = -1;      ///< palette index; -1 = by series order
  bool dashed = false;
  bool markers_only = false;  ///< scatter (e.g. raw beacon fixes)
  /// Bars: y[k] is the height of the bar of category k (x = k) from zero; several bar series of
  /// a figure stand side by side in each category. err_lo / err_hi (empty: none) are the ends of
  /// each bar's error bar (e.g. mean ± std over seeds); NaN: no bar, or no error bar.
  bool bars = false;
  std::vector<double> err_lo, err_hi;
};

/// A figure, as exported by --plots and drawn live in the GUI.
struct FigureSpec {
  std::string id;     ///< file name stem: "phi_error" -> phi_error.png
  std::string title;  ///< e.g. "(b) Bearing error φ12"
  std::string x_label = "t [s]";
  std::string y_label;
  std::vector<SeriesSpec> series;
  std::vector<double> reference_lines;  ///< horizontal lines (targets, bounds)
  bool equal_aspect = false;            ///< trajectories: 1 m is 1 m on both axes
  double marker_x = std::numeric_limits<double>::quiet_NaN();  ///< a vertical marker (current input)
  /// A categorical x axis: label k is written at x = k (bar charts).
  std::vector<std::string> categories;
};

/// A table the GUI shows (metrics, fuzzy rules with their firing strengths...).
struct TableSpec {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<double> row_strength;  ///< optional bar in [0, 1] per row
};

/// A series of column `column` against time.
SeriesSpec Line(const std::string& label, const std::string& column, int color_index = -1,
                bool dashed = false);
/// A series of `y_column` against `x_column` (a path in the plane).
SeriesSpec Path(const std::string& label, const std::string& x_column, const std::string& y_column,
                int color_index = -1, bool dashed = false);
/// A scatter of points given inline (fill x and y), e.g. raw sensor fixes.
SeriesSpec Markers(const std::string& label, int color_index = -1);
/// Bars of `heights` (one per category) with error bars from `lo` to `hi` (may be empty).
SeriesSpec Bars(const std::string& label, std::vector<double> heights, std::vector<double> lo,
                std::vector<double> hi, int color_index = -1);
/// A bar chart: one group of bars per category, one bar per series in each.
FigureSpec BarFigure(const std::string& id, const std::string& title, const std::string& y_label,
                     std::vector<std::string> categories, std::vector<SeriesSpec> series);
/// A time plot: id, title, y label, series.
FigureSpec TimeFigure(const std::string& id, const std::string& title, const std::string& y_label,
                      std::vector<SeriesSpec> series);
/// An x-y plot with 1 m = 1 m (trajectories).
FigureSpec PlaneFigure(const std::string& id, const std::string& title,
                       std::vector<SeriesSpec> series);

}  // namespace formsim::sim
