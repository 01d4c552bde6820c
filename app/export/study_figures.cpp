#include "app/export/study_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/gui/offscreen_renderer.hpp"
#include "app/export/png_writer.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A value of an axis as a short tick label ("0.03162", "ukf").
std::string Label(const sim::SweepAxis& a, std::size_t i) {
  if (a.categorical()) return a.values[i];
  return sim::Sprintf("%.4g", a.Numeric(i));
}

// Where value i of axis a goes on a figure's x axis.
double Position(const sim::SweepAxis& a, std::size_t i) {
  if (a.categorical()) return static_cast<double>(i);
  const double v = a.Numeric(i);
  return a.log_scale ? std::log10(v) : v;
}

std::string AxisTitle(const sim::SweepAxis& a) {
  return a.log_scale ? "log₁₀ " + a.key : a.key;
}

std::string SeedsText(const sim::SweepDefinition& def) {
  return std::to_string(def.seeds.size()) + (def.seeds.size() == 1 ? " seed" : " seeds");
}

// The metric's value in each completed run of point p, in seed order.
std::vector<std::pair<std::uint64_t, double>> RunValues(
    const sim::SweepDefinition& def, const std::vector<sim::SweepRecord>& records, std::size_t p,
    const std::string& metric) {
  std::vector<std::pair<std::uint64_t, double>> out;
  for (const sim::SweepRecord& r : records) {
    if (def.PointOf(r.run) != p || r.failed()) continue;
    for (const auto& m : r.metrics)
      if (m.first == metric && std::isfinite(m.second))
        out.emplace_back(def.SeedOf(r.run), m.second);
  }
  return out;
}

}  // namespace

bool SweepFigure(const sim::SweepDefinition& def, const sim::SweepTables& t,
                 const std::vector<sim::SweepRecord>& records, int m, PlotData* out) {
  if (m < 0 || m >= static_cast<int>(t.metrics.size())) return false;
  const std::string& metric = t.metrics[m];
  PlotData d;
  d.y_label = metric;
  if (def.axes.empty()) {
    // One point: the metric per seed.
    PlotSeries s;
    s.label = "each seed";
    s.markers_only = true;
    s.color = sim::PaletteColor(0);
    for (std::size_t k = 0; k < def.seeds.size(); ++k)
      d.x_tick_labels.push_back(std::to_string(def.seeds[k]));
    for (const auto& [seed, v] : RunValues(def, records, 0, metric)) {
      const auto it = std::find(def.seeds.begin(), def.seeds.end(), seed);
      s.x.push_back(static_cast<double>(it - def.seeds.begin()));
      s.y.push_back(v);
    }
    if (!t.stats.empty() && t.stats[0][m].n > 0) d.reference_lines.push_back(t.stats[0][m].mean);
    d.series.push_back(s);
    d.x_label = "seed";
    d.title = metric + " per seed (dashed: mean)";
    *out = d;
    return true;
  }
  if (def.axes.size() == 1) {
    const sim::SweepAxis& a = def.axes[0];
    // Points in the order of their x (random samples and lists may come in any order).
    std::vector<std::size_t> order(t.points.size());
    for (std::size_t e = 0; e < order.size(); ++e) order[e] = e;
    auto x_of = [&](std::size_t e) { return Position(a, def.points[t.points[e]][0]); };
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t i, std::size_t j) { return x_of(i) < x_of(j); });
    PlotSeries mean, seeds;
    mean.label = "mean ± 1σ over " + SeedsText(def);
    mean.color = sim::PaletteColor(0);
    seeds.label = "each seed";
    seeds.markers_only = true;
    seeds.color = sim::PaletteColor(1).WithAlpha(0.75f);
    for (std::size_t e : order) {
      const sim::MetricStats& st = t.stats[e][m];
      const double x = x_of(e);
      mean.x.push_back(x);
      mean.y.push_back(st.n > 0 ? st.mean : kNaN);
      const double sd = std::isfinite(st.std) ? st.std : 0.0;
      mean.band_lo.push_back(st.n > 0 ? st.mean - sd : kNaN);
      mean.band_hi.push_back(st.n > 0 ? st.mean + sd : kNaN);
      for (const auto& run : RunValues(def, records, t.points[e], metric)) {
        seeds.x.push_back(x);
        seeds.y.push_back(run.second);
      }
    }
    if (a.categorical())
      for (std::size_t i = 0; i < a.values.size(); ++i) d.x_tick_labels.push_back(a.values[i]);
    d.series = {mean, seeds};
    if (!a.categorical()) d.x_margin = 0.03;  // the first and last points are drawn whole
    d.x_label = AxisTitle(a);
    d.title = metric + " against " + a.key;
    *out = d;
    return true;
  }
  if (def.axes.size() == 2 && def.IsGrid()) {
    const sim::SweepAxis &ax = def.axes[0], &ay = def.axes[1];
    d.heatmap.columns = static_cast<int>(ax.values.size());
    d.heatmap.rows = static_cast<int>(ay.values.size());
    d.heatmap.values.assign(ax.values.size() * ay.values.size(), kNaN);
    d.heatmap.value_label = "mean of " + metric;
    for (std::size_t e = 0; e < t.points.size(); ++e) {
      const auto& idx = def.points[t.points[e]];
      if (t.stats[e][m].n > 0)
        d.heatmap.values[idx[1] * ax.values.size() + idx[0]] = t.stats[e][m].mean;
    }
    for (std::size_t i = 0; i < ax.values.size(); ++i) d.x_tick_labels.push_back(Label(ax, i));
    for (std::size_t i = 0; i < ay.values.size(); ++i) d.y_tick_labels.push_back(Label(ay, i));
    d.x_label = ax.key;
    d.y_label = ay.key;
    d.title = metric + ", mean over " + SeedsText(def);
    *out = d;
    return true;
  }
  return false;
}

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
  PlotSeries each, best;
  each.label = "each evaluation";
  each.markers_only = true;
  each.color = sim::PaletteColor(1);
  best.label = "best so far";
  best.color = sim::PaletteColor(0);
  double b = std::numeric_limits<double>::infinity();
  for (const sim::TuneEvaluation& e : r.history) {
    each.x.push_back(static_cast<double>(e.index));
    each.y.push_back(y(e.objective));
    b = std::min(b, e.objective);
    best.x.push_back(static_cast<double>(e.index));
    best.y.push_back(y(b));
  }
  d.series = {each, best};
  // A long sum would not fit in the title: name the number of terms instead (history.csv and
  // best.yaml hold the expression).
  const std::size_t terms = static_cast<std::size_t>(std::count(expr.begin(), expr.end(), '+')) + 1;
  d.title =
      "formsim tune (" + settings.algorithm + ", " + std::to_string(settings.seeds.size()) +
      " seeds): " + (expr.size() <= 60 ? expr : "sum of " + std::to_string(terms) + " metrics");
  d.x_label = "evaluation";
  d.y_label = log ? "log₁₀ objective" : "objective";
  return d;
}

void WriteFigurePng(const PlotData& data, const std::string& path, int width, int height) {
  OffscreenRenderer renderer(width, height);
  const auto& px = renderer.RenderFigure(data, width, height);
  WritePng(path, width, height, px.data());
}

}  // namespace formsim::app
