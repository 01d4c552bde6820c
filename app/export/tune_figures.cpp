#include "app/export/tune_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/common/float_limits.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

using control::kNaN;

// A title's expression: a long sum names its number of terms (history.csv and best.yaml hold
// the expression).
std::string ExprText(const std::string& expr) {
  const std::size_t terms = static_cast<std::size_t>(std::count(expr.begin(), expr.end(), '+')) + 1;
  return expr.size() <= 60 ? expr : "sum of " + std::to_string(terms) + " metrics";
}

// Tick labels for `cells` columns: the key's value at each cell's centre (the plot thins them).
std::vector<std::string> Ticks(const sim::TuneParam& p, int cells) {
  std::vector<std::string> out;
  for (int c = 0; c < cells; ++c) {
    const double v = p.FromUnit((c + 0.5) / cells);
    out.push_back(p.discrete() ? p.Text(v) : sim::FormatSignificant(v, 3));
  }
  return out;
}

// What the objective is, for titles and labels: a single metric by the label its kind declares
// (with markup) and its unit; a weighted sum as written.
struct ObjectiveName {
  std::string name;  ///< title text: the label, or the expression
  std::string unit;  ///< "m", "rad"; empty for a sum or an undeclared metric
  std::string axis;  ///< "label [unit]", or "objective"
};

ObjectiveName NameOf(const sim::TuneSettings& s, const sim::TuneResult& r,
                     const std::string& expr) {
  ObjectiveName n{ExprText(expr), "", "objective"};
  if (s.objective.size() != 1 || s.objective[0].weight != 1) return n;
  for (const auto& [path, info] : r.info)
    if (path == s.objective[0].path && !info.label.empty()) {
      sim::MetricInfo plain = info;
      plain.unit.clear();
      n.name = plain.AxisLabel(path);  // the label with its captures filled in
      n.unit = info.unit;
      n.axis = info.AxisLabel(path);
    }
  return n;
}

}  // namespace

PlotData TuneConvergenceFigure(const sim::TuneSettings& settings, const sim::TuneResult& r,
                               const std::string& expr) {
  PlotData d;
  // Objectives that span decades read better on a log scale.
  double lo = kNaN, hi = kNaN;
  for (const sim::TuneEvaluation& e : r.history) {
    if (!std::isfinite(e.objective)) continue;
    if (!(e.objective >= lo)) lo = e.objective;
    if (!(e.objective <= hi)) hi = e.objective;
  }
  const bool log = lo > 0 && hi / lo > 30;
  auto y = [&](double v) { return !std::isfinite(v) ? kNaN : log ? std::log10(v) : v; };
  // With constraints, the points that break one are drawn apart, and "best so far" is the best
  // feasible one (what best.yaml holds).
  const bool constrained = !settings.constraints.empty();
  PlotSeries each, infeasible, best;
  each.label = constrained ? "feasible evaluation" : "each evaluation";
  each.markers_only = true;
  each.color = sim::PaletteColor(1);
  infeasible.label = "breaks a constraint";
  infeasible.markers_only = true;
  infeasible.color = sim::Color{0.6f, 0.6f, 0.6f, 1.0f};  // grey: not a candidate for best.yaml
  infeasible.style_index = 3;
  best.label = constrained ? "best feasible so far" : "best so far";
  best.color = sim::PaletteColor(0);
  double b = std::numeric_limits<double>::infinity();
  for (const sim::TuneEvaluation& e : r.history) {
    PlotSeries& dots = e.feasible() || !constrained ? each : infeasible;
    dots.x.push_back(static_cast<double>(e.index));
    dots.y.push_back(y(e.objective));
    if (e.feasible()) b = std::min(b, e.objective);
    best.x.push_back(static_cast<double>(e.index));
    best.y.push_back(std::isfinite(b) ? y(b) : kNaN);
  }
  d.series = {each, best};
  if (!infeasible.x.empty()) d.series.insert(d.series.begin() + 1, infeasible);
  const ObjectiveName name = NameOf(settings, r, expr);
  d.title = "formsim tune (" + settings.algorithm + ", " + std::to_string(settings.seeds.size()) +
            " seeds): " + name.name;
  d.x_label = "evaluation";
  d.y_label = log ? "log₁₀ " + name.axis : name.axis;
  return d;
}

PlotData TuneLandscapeFigure(const sim::TuneSettings& settings, const sim::TuneResult& r,
                             const std::string& expr, int cells) {
  PlotData d;
  if (settings.params.size() != 2) {
    d.error = "a landscape needs exactly two tuned keys";
    return d;
  }
  const sim::TuneParam &px = settings.params[0], &py = settings.params[1];
  // Inverse-distance weighting (Shepard, power 2) of every evaluation that ran (the objective
  // is defined where a constraint breaks too), in the scaled box: an estimate between the
  // visited points, exact at them.
  std::vector<double> ux, uy, f;
  for (const sim::TuneEvaluation& e : r.history)
    if (std::isfinite(e.objective)) {
      ux.push_back(px.ToUnit(e.values[0]));
      uy.push_back(py.ToUnit(e.values[1]));
      f.push_back(e.objective);
    }
  d.heatmap.columns = d.heatmap.rows = cells;
  d.heatmap.values.assign(static_cast<std::size_t>(cells * cells), kNaN);
  d.heatmap.cell_values = false;
  const ObjectiveName name = NameOf(settings, r, expr);
  d.heatmap.value_label = name.axis + ", estimated between the points";
  for (int row = 0; row < cells && !f.empty(); ++row)
    for (int col = 0; col < cells; ++col) {
      const double cx = (col + 0.5) / cells, cy = (row + 0.5) / cells;
      double num = 0, den = 0, exact = kNaN;
      for (std::size_t i = 0; i < f.size() && std::isnan(exact); ++i) {
        const double d2 = (ux[i] - cx) * (ux[i] - cx) + (uy[i] - cy) * (uy[i] - cy);
        if (d2 < 1e-18) exact = f[i];
        num += f[i] / d2;
        den += 1 / d2;
      }
      d.heatmap.values[static_cast<std::size_t>(row * cells + col)] =
          std::isnan(exact) ? num / den : exact;
    }
  // The points in cell coordinates (cell c spans c - 0.5 ... c + 0.5); the start and the best
  // as crosses a cell and a half wide, so they show over a crowd of points.
  auto cell = [&](const sim::TuneParam& p, double v) { return p.ToUnit(v) * cells - 0.5; };
  const bool constrained = !settings.constraints.empty();
  PlotSeries visited, infeasible;
  visited.label = constrained ? "evaluated, meets the constraints" : "evaluated";
  visited.markers_only = true;
  visited.color = sim::Color{0.05f, 0.05f, 0.05f, 1};
  infeasible.label = "breaks a constraint";
  infeasible.markers_only = true;
  infeasible.color = sim::Color{0.6f, 0.6f, 0.6f, 1};
  infeasible.style_index = 3;
  for (const sim::TuneEvaluation& e : r.history) {
    PlotSeries& s = e.feasible() ? visited : infeasible;
    s.x.push_back(cell(px, e.values[0]));
    s.y.push_back(cell(py, e.values[1]));
  }
  d.series.push_back(visited);
  if (!infeasible.x.empty()) d.series.push_back(infeasible);
  auto cross = [&](const std::string& label, const sim::TuneEvaluation& e, int palette) {
    PlotSeries c;
    c.label = label;
    c.color = sim::PaletteColor(palette);
    c.style_index = palette;
    const double x = cell(px, e.values[0]), y = cell(py, e.values[1]), h = 0.75;
    // Inside the map: a point on the box's edge keeps the range the map's.
    auto in = [&](double v) { return std::clamp(v, -0.5, cells - 0.5); };
    c.x = {in(x - h), in(x + h), kNaN, in(x), in(x)};
    c.y = {in(y), in(y), kNaN, in(y - h), in(y + h)};
    d.series.push_back(c);
  };
  if (!r.history.empty()) cross("start (the scenario's values)", r.history.front(), 1);
  if (r.has_best()) cross("best", r.history[r.best], 5);
  d.x_tick_labels = Ticks(px, cells);
  d.y_tick_labels = Ticks(py, cells);
  d.title = "objective landscape: " + name.name;
  d.x_label = px.key + (px.log_scale ? " (log scale)" : "");
  d.y_label = py.key + (py.log_scale ? " (log scale)" : "");
  return d;
}

PlotData TuneValidationFigure(const sim::TuneValidation& v, const sim::TuneSettings& settings,
                              const sim::TuneResult& r, const std::string& expr) {
  PlotData d;
  const ObjectiveName name = NameOf(settings, r, expr);
  PlotSeries diff, mean;
  diff.label = "best − start, each held-out run";
  diff.markers_only = true;
  diff.color = sim::PaletteColor(0);
  // One category per held-out run, labelled by its seed (and scenario, when there are several).
  const bool several = v.scenarios.size() > 1;
  for (std::size_t i = 0; i < v.start.size(); ++i) {
    const std::string seed = std::to_string(v.seeds[i % v.seeds.size()]);
    d.x_tick_labels.push_back(several ? v.scenarios[i / v.seeds.size()] + " " + seed : seed);
    if (!std::isfinite(v.start[i]) || !std::isfinite(v.best[i])) continue;
    diff.x.push_back(static_cast<double>(i));
    diff.y.push_back(v.best[i] - v.start[i]);
  }
  const double x = static_cast<double>(v.start.size()) - 1;
  d.series.push_back(diff);
  if (std::isfinite(v.difference.mean)) {
    mean.label = "mean and its 95% CI";
    mean.color = sim::PaletteColor(1);
    mean.style_index = 1;
    mean.x = {-0.5, x + 0.5};
    mean.y = {v.difference.mean, v.difference.mean};
    if (std::isfinite(v.difference.ci95_lo)) {
      mean.band_lo = {v.difference.ci95_lo, v.difference.ci95_lo};
      mean.band_hi = {v.difference.ci95_hi, v.difference.ci95_hi};
    }
    d.series.push_back(mean);
  }
  d.reference_lines = {0.0};
  d.title = "held out: best − start of " + name.name + " (better on " +
            std::to_string(v.best_better) + " of " + std::to_string(v.compared) + " runs)";
  d.x_label = several ? "held-out run (scenario, seed)" : "held-out seed";
  d.y_label = "best − start" + (name.unit.empty() ? "" : " [" + name.unit + "]") +
              " (below 0: better)";
  return d;
}

}  // namespace formsim::app
