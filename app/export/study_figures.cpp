#include "app/export/study_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "app/export/png_writer.hpp"
#include "app/render/offscreen_renderer.hpp"
#include "control/common/float_limits.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

using control::kNaN;

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
std::vector<std::pair<std::uint64_t, double>> SeedValues(
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

// The metric's declared label (markup, no unit), or its dotted path.
std::string MetricName(const sim::SweepTables& t, int m) {
  return m < static_cast<int>(t.info.size()) && !t.info[m].label.empty() ? t.info[m].label
                                                                         : t.metrics[m];
}

// The band of `st` around its mean (zero width where it is undefined: one seed, no spread).
void BandOf(const sim::MetricStats& st, SweepBand band, double* lo, double* hi) {
  if (st.n == 0) {
    *lo = *hi = kNaN;
    return;
  }
  switch (band) {
    case SweepBand::kSd: {
      const double sd = std::isfinite(st.std) ? st.std : 0.0;
      *lo = st.mean - sd;
      *hi = st.mean + sd;
      return;
    }
    case SweepBand::kCi95:
      *lo = std::isfinite(st.ci95_lo) ? st.ci95_lo : st.mean;
      *hi = std::isfinite(st.ci95_hi) ? st.ci95_hi : st.mean;
      return;
    case SweepBand::kMinMax:
      *lo = st.min;
      *hi = st.max;
      return;
  }
}

// "mean ± 95% CI of the mean over 4 seeds".
std::string MeanLabel(SweepBand band, const std::string& over) {
  return band == SweepBand::kMinMax ? "mean, band min–max over " + over
                                    : "mean " + SweepBandText(band) + " over " + over;
}

// Scenario s of a sweep over several, as a sweep of it alone: its definition (its run numbers
// keep their places), its rows of the tables and its records.
struct ScenarioPart {
  sim::SweepDefinition def;
  sim::SweepTables tables;
  std::vector<sim::SweepRecord> records;
};

ScenarioPart PartOf(const sim::SweepDefinition& def, const sim::SweepTables& t,
                    const std::vector<sim::SweepRecord>& records, std::size_t s) {
  ScenarioPart part{def, {}, {}};
  part.def.scenarios = {def.scenarios[s]};
  part.tables.metrics = t.metrics;
  part.tables.info = t.info;
  part.tables.settings = t.settings;
  for (std::size_t e = 0; e < t.points.size(); ++e) {
    if (t.scenarios[e] != s) continue;
    part.tables.points.push_back(t.points[e]);
    part.tables.scenarios.push_back(0);
    part.tables.runs.push_back(t.runs[e]);
    part.tables.failed.push_back(t.failed[e]);
    part.tables.stats.push_back(t.stats[e]);
  }
  for (const sim::SweepRecord& r : records)
    if (def.ScenarioOf(r.run) == s) part.records.push_back(r);
  return part;
}

// The figure of a sweep over several scenarios with no varied key (the metric per seed, a
// series per scenario) or one (the mean and band against the key, a series per scenario, each
// seed as a dot of its colour).
bool ScenarioSeriesFigure(const sim::SweepDefinition& def, const sim::SweepTables& t,
                          const std::vector<sim::SweepRecord>& records, int m, PlotData* out,
                          SweepBand band) {
  if (def.axes.size() > 1) return false;
  PlotData d;
  d.y_label = sim::MetricAxisLabel(t, m);
  const std::string metric = MetricName(t, m);
  std::vector<PlotSeries> means, dots;
  for (std::size_t s = 0; s < def.scenarios.size(); ++s) {
    const ScenarioPart part = PartOf(def, t, records, s);
    PlotData one;
    if (!SweepFigure(part.def, part.tables, part.records, m, &one, band)) return false;
    // One scenario's figure: [mean, each seed] for one key, [each seed] for none.
    PlotSeries mean = one.series.front(), seeds = one.series.back();
    mean.label = def.scenarios[s].Name();
    mean.color = sim::PaletteColor(static_cast<int>(s));
    mean.style_index = static_cast<int>(s);
    seeds.color = sim::PaletteColor(static_cast<int>(s)).WithAlpha(0.6f);
    seeds.style_index = static_cast<int>(s);
    seeds.label.clear();
    if (def.axes.empty()) {
      means.push_back(mean);  // the seeds' dots are the series
    } else {
      means.push_back(mean);
      dots.push_back(seeds);
    }
    d.x_tick_labels = one.x_tick_labels;
    d.x_margin = one.x_margin;
    d.x_label = one.x_label;
  }
  d.series = dots;
  d.series.insert(d.series.end(), means.begin(), means.end());  // the lines over the dots
  if (!def.axes.empty()) {
    // A key in grey (no data): what the line, its band and the dots of every scenario are.
    const sim::Color grey{0.45f, 0.45f, 0.45f, 1.0f};
    PlotSeries line, dot;
    line.label = MeanLabel(band, SeedsText(def));
    line.color = grey;
    dot.label = "each seed";
    dot.markers_only = true;
    dot.color = grey.WithAlpha(0.6f);
    d.series.push_back(line);
    d.series.push_back(dot);
  }
  d.title = def.axes.empty()
                ? metric + " per seed of " + std::to_string(def.scenarios.size()) + " scenarios"
                : metric + " against " + def.axes[0].key;
  *out = d;
  return true;
}

}  // namespace

SweepBand ParseSweepBand(const std::string& text) {
  if (text == "sd") return SweepBand::kSd;
  if (text == "ci95") return SweepBand::kCi95;
  if (text == "minmax") return SweepBand::kMinMax;
  throw std::runtime_error("--band '" + text +
                           "': expected sd (± 1 standard deviation), ci95 (95% confidence "
                           "interval of the mean, the default) or minmax");
}

std::string SweepBandText(SweepBand band) {
  switch (band) {
    case SweepBand::kSd:
      return "± 1σ";
    case SweepBand::kCi95:
      return "± 95% CI of the mean";
    case SweepBand::kMinMax:
      return "min–max";
  }
  return "";
}

bool SweepFigure(const sim::SweepDefinition& def, const sim::SweepTables& t,
                 const std::vector<sim::SweepRecord>& records, int m, PlotData* out,
                 SweepBand band) {
  if (m < 0 || m >= static_cast<int>(t.metrics.size())) return false;
  if (def.MultiScenario()) return ScenarioSeriesFigure(def, t, records, m, out, band);
  const std::string& path = t.metrics[m];
  const std::string metric = MetricName(t, m);
  PlotData d;
  d.y_label = sim::MetricAxisLabel(t, m);
  if (def.axes.empty()) {
    // One point: the metric per seed.
    PlotSeries s;
    s.label = "each seed";
    s.markers_only = true;
    s.color = sim::PaletteColor(0);
    for (std::size_t k = 0; k < def.seeds.size(); ++k)
      d.x_tick_labels.push_back(std::to_string(def.seeds[k]));
    for (const auto& [seed, v] : SeedValues(def, records, 0, path)) {
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
    mean.label = MeanLabel(band, SeedsText(def));
    mean.color = sim::PaletteColor(0);
    seeds.label = "each seed";
    seeds.markers_only = true;
    seeds.color = sim::PaletteColor(1).WithAlpha(0.75f);
    for (std::size_t e : order) {
      const sim::MetricStats& st = t.stats[e][m];
      const double x = x_of(e);
      mean.x.push_back(x);
      mean.y.push_back(st.n > 0 ? st.mean : kNaN);
      double lo = kNaN, hi = kNaN;
      BandOf(st, band, &lo, &hi);
      mean.band_lo.push_back(lo);
      mean.band_hi.push_back(hi);
      for (const auto& run : SeedValues(def, records, t.points[e], path)) {
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
    d.heatmap.value_label = "mean of " + sim::MetricAxisLabel(t, m);
    // Each cell: its mean ± the half-width of its 95% confidence interval (the mean alone with
    // one seed, where there is no interval).
    d.heatmap.cell_labels.assign(d.heatmap.values.size(), "");
    for (std::size_t e = 0; e < t.points.size(); ++e) {
      const auto& idx = def.points[t.points[e]];
      const sim::MetricStats& st = t.stats[e][m];
      if (st.n == 0) continue;
      const std::size_t k = idx[1] * ax.values.size() + idx[0];
      d.heatmap.values[k] = st.mean;
      d.heatmap.cell_labels[k] = std::isfinite(st.ci95_half())
                                     ? sim::Sprintf("%.3g ± %.2g", st.mean, st.ci95_half())
                                     : sim::Sprintf("%.3g", st.mean);
    }
    for (std::size_t i = 0; i < ax.values.size(); ++i) d.x_tick_labels.push_back(Label(ax, i));
    for (std::size_t i = 0; i < ay.values.size(); ++i) d.y_tick_labels.push_back(Label(ay, i));
    d.x_label = ax.key;
    d.y_label = ay.key;
    d.title = metric + ", mean ± 95% CI over " + SeedsText(def);
    *out = d;
    return true;
  }
  return false;
}

std::vector<PlotData> SweepPanels(const sim::SweepDefinition& def, const sim::SweepTables& t,
                                  int m, SweepBand band) {
  std::vector<PlotData> panels;
  const bool random = !def.IsGrid();
  if (m < 0 || m >= static_cast<int>(t.metrics.size())) return panels;
  if (def.axes.size() < 2 || (!random && def.axes.size() < 3)) return panels;
  // Colour classes of the metric: five equal steps of viridis over the points' means.
  double lo = kNaN, hi = kNaN;
  for (const auto& point : t.stats) {
    const double v = point[m].mean;
    if (point[m].n == 0) continue;
    if (!(v >= lo)) lo = v;
    if (!(v <= hi)) hi = v;
  }
  constexpr int kClasses = 5;
  const int classes = lo < hi ? kClasses : 1;
  auto class_of = [&](double v) {
    if (classes == 1) return 0;
    return std::min(classes - 1, static_cast<int>((v - lo) / (hi - lo) * classes));
  };
  for (std::size_t k = 0; k < def.axes.size(); ++k) {
    const sim::SweepAxis& a = def.axes[k];
    PlotData d;
    std::vector<PlotSeries> bins(static_cast<std::size_t>(classes));
    for (int c = 0; c < classes; ++c) {
      PlotSeries& s = bins[static_cast<std::size_t>(c)];
      s.markers_only = true;
      s.style_index = c;
      s.color = Viridis(classes == 1 ? 0.5 : (c + 0.5) / classes);
      const double from = lo + (hi - lo) * c / classes, to = lo + (hi - lo) * (c + 1) / classes;
      s.label = classes == 1 ? "each point's mean"
                             : sim::Sprintf("mean %.3g … %.3g", from, to);
    }
    // For grid keys: the mean over the points sharing each value, with its band.
    PlotSeries marginal;
    marginal.label = MeanLabel(band, "the other keys");
    marginal.color = sim::PaletteColor(0);
    std::vector<std::vector<double>> at_value(a.values.size());
    for (std::size_t e = 0; e < t.points.size(); ++e) {
      const sim::MetricStats& st = t.stats[e][m];
      if (st.n == 0) continue;
      const std::size_t i = def.points[t.points[e]][k];
      PlotSeries& s = bins[static_cast<std::size_t>(class_of(st.mean))];
      s.x.push_back(Position(a, i));
      s.y.push_back(st.mean);
      at_value[i].push_back(st.mean);
    }
    if (!random) {
      std::vector<std::size_t> order(a.values.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
        return Position(a, i) < Position(a, j);
      });
      for (std::size_t i : order) {
        const sim::MetricStats st = sim::StatsOf(at_value[i]);
        double blo = kNaN, bhi = kNaN;
        BandOf(st, band, &blo, &bhi);
        marginal.x.push_back(Position(a, i));
        marginal.y.push_back(st.mean);
        marginal.band_lo.push_back(blo);
        marginal.band_hi.push_back(bhi);
      }
    }
    for (PlotSeries& s : bins)
      if (!s.x.empty()) d.series.push_back(std::move(s));
    if (!random) d.series.push_back(std::move(marginal));
    if (a.categorical())
      for (std::size_t i = 0; i < a.values.size(); ++i) d.x_tick_labels.push_back(a.values[i]);
    else
      d.x_margin = 0.03;
    d.x_label = AxisTitle(a);
    d.y_label = sim::MetricAxisLabel(t, m);
    // The metric is the y axis' title; the panel's title names the key (long titles are cut).
    d.title = (random ? "random samples: " : "small multiples: ") + a.key;
    panels.push_back(std::move(d));
  }
  return panels;
}

std::vector<PlotData> SweepScenarioPanels(const sim::SweepDefinition& def,
                                          const sim::SweepTables& t,
                                          const std::vector<sim::SweepRecord>& records, int m,
                                          SweepBand band, int* columns) {
  std::vector<PlotData> panels;
  if (!def.MultiScenario() || m < 0 || m >= static_cast<int>(t.metrics.size())) return panels;
  for (std::size_t s = 0; s < def.scenarios.size(); ++s) {
    const ScenarioPart part = PartOf(def, t, records, s);
    std::vector<PlotData> mine;
    PlotData one;
    if (SweepFigure(part.def, part.tables, part.records, m, &one, band))
      mine.push_back(std::move(one));
    else
      mine = SweepPanels(part.def, part.tables, m, band);
    // Panels of keys: a scenario to a row; one figure each: the scenarios side by side.
    *columns = mine.size() == 1 ? std::min<int>(3, static_cast<int>(def.scenarios.size()))
                                : std::max(1, static_cast<int>(mine.size()));
    for (PlotData& p : mine) {
      p.title = def.scenarios[s].Name() + ": " + p.title;
      panels.push_back(std::move(p));
    }
  }
  return panels;
}

void WritePanelsPng(const std::vector<PlotData>& panels, const std::string& path, int panel_width,
                    int panel_height, int columns) {
  if (panels.empty()) throw std::runtime_error(path + ": no panels to write");
  columns = std::max(1, std::min(columns, static_cast<int>(panels.size())));
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  const int width = panel_width * columns, height = panel_height * rows;
  std::vector<std::uint8_t> image(static_cast<std::size_t>(width) * height * 4, 255);
  OffscreenRenderer renderer(panel_width, panel_height);
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const auto& px = renderer.RenderFigure(panels[k], panel_width, panel_height);
    const int col = static_cast<int>(k) % columns, row = static_cast<int>(k) / columns;
    for (int y = 0; y < panel_height; ++y) {
      const std::size_t from = static_cast<std::size_t>(y) * panel_width * 4;
      const std::size_t to =
          (static_cast<std::size_t>(row * panel_height + y) * width + col * panel_width) * 4;
      std::copy(px.begin() + static_cast<std::ptrdiff_t>(from),
                px.begin() + static_cast<std::ptrdiff_t>(from + panel_width * 4),
                image.begin() + static_cast<std::ptrdiff_t>(to));
    }
  }
  WritePng(path, width, height, image.data());
}

void WriteFigurePng(const PlotData& data, const std::string& path, int width, int height) {
  OffscreenRenderer renderer(width, height);
  const auto& px = renderer.RenderFigure(data, width, height);
  WritePng(path, width, height, px.data());
}

}  // namespace formsim::app
