/// \file The Compare panel's comparisons (app/gui/compare_panel.hpp): the pinned runs drawn dashed over every live plot (one dash pattern per
/// pin, a legend entry naming what differs), the Monte Carlo spread as bands (min-max light,
/// mean ± σ darker) on every time plot, and the comparison table: the headline metrics and every
/// number of the results' tables for the current run, each pinned run and the Monte Carlo
/// (mean ± σ), the better value of each row marked by the metric's declared direction.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "app/export/figure_data.hpp"
#include "app/gui/table_header.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/display_unit.hpp"
#include "app/render/label_markup.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {

namespace {

// Significant digits of every number of the comparison table (and of σ's decimal place).
constexpr int kDigits = 4;

// Figures can change with the settings (an estimator switched on adds series): a pin's resolved
// figure is kept per figure and list of columns.
std::string FigureKey(const sim::FigureSpec& fig) {
  std::string k = fig.id;
  for (const auto& s : fig.series) k += "|" + s.column + "/" + s.x_column;
  return k;
}

}  // namespace

void ComparePanel::DecoratePlot(const sim::FigureSpec& fig, PlotData& data) {
  const sim::Color legend_ink = GetTheme(ctx_.state->theme).axis;
  // The spread of the Monte Carlo under each time series.
  if (data.x_is_time && mc_.bands.runs > 1) {
    for (std::size_t i = 0; i < fig.series.size(); ++i) {
      const sim::SeriesSpec& s = fig.series[i];
      const sim::ChannelBands::Band* band = mc_.bands.Find(s.column);
      if (band == nullptr) continue;
      const int style = s.color_index >= 0 ? s.color_index : static_cast<int>(i);
      PlotSeries range, sigma;
      range.x = sigma.x = mc_.bands.t;
      range.color = sigma.color = sim::PaletteColor(style);
      range.style_index = sigma.style_index = style;
      range.band_lo = band->lo;
      range.band_hi = band->hi;
      range.band_alpha = 0.10f;
      sigma.band_lo.resize(band->mean.size());
      sigma.band_hi.resize(band->mean.size());
      for (std::size_t k = 0; k < band->mean.size(); ++k) {
        // One seed has no σ: its band is the line itself.
        const double sd = std::isfinite(band->sd[k]) ? band->sd[k] : 0.0;
        sigma.band_lo[k] = band->mean[k] - sd;
        sigma.band_hi[k] = band->mean[k] + sd;
      }
      sigma.band_alpha = 0.25f;
      sigma.y = band->mean;  // the mean, dotted, on the darker band
      sigma.dash_style = 2;
      data.series.push_back(std::move(range));
      data.series.push_back(std::move(sigma));
    }
    PlotSeries legend;
    legend.label =
        std::to_string(mc_.bands.runs) + " seeds: mean (dotted) ± σ (dark), min-max (light)";
    legend.color = legend_ink;
    legend.dash_style = 2;
    data.series.push_back(std::move(legend));
  }
  // Pinned runs, dashed, in the colours of the live series.
  int slot = 0;
  for (const auto& p : pins_) {
    if (!p->ready()) continue;
    ++slot;
    const std::string key = FigureKey(fig);
    auto it = p->plots.find(key);
    if (it == p->plots.end())
      it = p->plots.emplace(key, ResolveFigure(fig, p->exp->recorder())).first;
    for (PlotSeries s : it->second.series) {
      s.label.clear();
      s.dash_style = slot;
      s.color = s.color.WithAlpha(0.75f);
      data.series.push_back(std::move(s));
    }
    PlotSeries legend;
    legend.label = EscapeMarkup(PinLabel(*p));  // key names and values drawn as they are
    legend.color = legend_ink;
    legend.dash_style = slot;
    data.series.push_back(std::move(legend));
  }
}

std::vector<ComparePanel::CompareRun> ComparePanel::CompareRuns(const sim::Metrics& now, std::string* title) {
  std::vector<const PinnedRun*> pins;
  for (const auto& p : pins_)
    if (p->ready() && p->results) pins.push_back(p.get());
  // Runs of different lengths are compared over their common span: each longer run is cut to
  // it by an exact replay of its log (span_), so a pin that stops at 9.4 s is not measured
  // against 11 s of the live run.
  const sim::Experiment& live = ctx_.session().exp();
  // A live run that has not started (just reset, or loaded paused) has no data: it neither
  // cuts the others to 0 s nor shows zeros of its own.
  const bool started = live.steps() > 0;
  double span = started ? live.time() : std::numeric_limits<double>::infinity();
  for (const PinnedRun* p : pins) span = std::min(span, p->exp->time());
  if (!std::isfinite(span)) span = live.time();
  constexpr double kSameTime = 1e-9;
  bool cut = false;
  // The live run is the shortest and still running: the span moves every step, so the longer
  // runs are cut to it once the run stops (paused or finished).
  const bool moving = ctx_.state->playing && !live.finished() && live.time() <= span + kSameTime;
  std::vector<CompareRun> runs;
  auto column = [&](const std::string& name, const std::string& id, const sim::Experiment& x,
                    const sim::Metrics& whole, const std::function<SpanMetrics::Replayed()>& log) {
    CompareRun c;
    if (x.time() <= span + kSameTime || pins.empty()) {
      c.header = name + sim::Sprintf(" (%.1f s)", x.time());
      c.metrics = &whole;
    } else {
      cut = true;
      c.header = name + sim::Sprintf(" (%.1f of %.1f s)", span, x.time());
      std::string error;
      if (moving) c.why = "cut to the common span when the run pauses";
      else c.metrics = span_.Get(id, StepAtTime(x.steps(), x.time(), span), log, &error);
      if (c.metrics == nullptr && c.why.empty())
        c.why = error.empty() ? "replaying to the common span..." : "replay failed: " + error;
    }
    runs.push_back(std::move(c));
  };
  if (started) {
    column("now", "now:" + std::to_string(ctx_.session().run_id()), live, now, [this] {
      return SpanMetrics::Replayed{std::make_shared<sim::ScenarioSource>(ctx_.session().source()),
                                   ctx_.session().run_log()};
    });
  } else {
    CompareRun c;
    c.header = "now (no data yet)";
    c.why = "the run has not started: press Play (space)";
    c.no_data = true;
    runs.push_back(std::move(c));
  }
  for (const PinnedRun* p : pins)
    column("pin " + std::to_string(p->id), "pin:" + std::to_string(p->id), *p->exp, *p->results,
           [p] { return SpanMetrics::Replayed{p->source, p->log}; });
  *title = cut ? sim::Sprintf("Compare over the common span 0 ... %.1f s: the longer runs cut "
                              "to it (seeds: whole runs)",
                              span)
               : std::string("Compare: the current run, the pinned runs and the Monte Carlo");
  return runs;
}

void ComparePanel::DrawCompareTable(const sim::Metrics& now) {
  const bool mc = mc_.tables.has_value();
  std::size_t pinned = 0;
  for (const auto& p : pins_) pinned += p->ready() && p->results;
  if (pinned == 0 && !mc) return;
  std::string title;
  const std::vector<CompareRun> runs = CompareRuns(now, &title);
  ImGui::TextWrapped("%s", title.c_str());
  const int cols = 1 + static_cast<int>(runs.size()) + (mc ? 1 : 0);
  if (!ImGui::BeginTable(
          "compare", cols,
          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp))
    return;
  ImGui::TableSetupColumn("metric", ImGuiTableColumnFlags_WidthStretch, 2.0f);
  // Each run's column says how far it got (and, cut, of how long): a run just reset has no
  // errors yet.
  std::vector<std::string> headers = {"metric"};
  for (const CompareRun& c : runs) headers.push_back(c.header);
  if (mc) headers.push_back(std::to_string(mc_.seeds) + " seeds, mean ± σ");
  for (std::size_t i = 1; i < headers.size(); ++i) ImGui::TableSetupColumn(headers[i].c_str());
  TableHeaders(headers);

  // One row: the values of each run (NaN: none) and the Monte Carlo's, shown in the unit of the
  // label (angles in the window's unit) with one formatter and kDigits significant digits.
  const bool degrees = ctx_.state->settings.degrees;
  auto row = [&](const std::string& label, const std::vector<double>& v, sim::Better better,
                 const sim::MetricStats* stats) {
    const double k = ShownUnit(LabelUnit(label), degrees).scale;
    double best = std::nan("");
    int finite = 0;
    for (double x : v)
      if (std::isfinite(x)) {
        ++finite;
        if (std::isnan(best) || (better == sim::Better::kLower ? x < best : x > best)) best = x;
      }
    bool differ = false;
    for (double x : v) differ = differ || (std::isfinite(x) && x != best);
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextUnformatted(ShownLabel(label, degrees).c_str());
    if (better != sim::Better::kNone && ImGui::IsItemHovered())
      ImGui::SetTooltip(better == sim::Better::kLower ? "lower is better" : "higher is better");
    for (std::size_t i = 0; i < v.size(); ++i) {
      ImGui::TableSetColumnIndex(1 + static_cast<int>(i));
      if (better != sim::Better::kNone && finite > 1 && differ && v[i] == best) MarkBestCell();
      const std::string text = runs[i].no_data            ? "-"
                               : runs[i].metrics == nullptr ? "..."
                               : std::isnan(v[i])         ? "-"
                                                          : sim::FormatCell(v[i] * k, kDigits);
      ImGui::TextUnformatted(text.c_str());
      if (!runs[i].why.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", runs[i].why.c_str());
    }
    if (mc) {
      ImGui::TableSetColumnIndex(cols - 1);
      const std::string text = stats == nullptr || stats->n == 0
                                   ? "-"
                                   : sim::FormatMeanSigma(stats->mean * k, stats->std * k, kDigits);
      ImGui::TextUnformatted(text.c_str());
    }
  };
  // Headlines first.
  const auto head_now = now.Headlines();
  for (const auto& h : head_now) {
    std::vector<double> v;
    for (const CompareRun& c : runs) {
      double x = std::nan("");
      if (c.metrics != nullptr)
        for (const auto& o : c.metrics->Headlines())
          if (o.label == h.label) x = o.value;
      v.push_back(x);
    }
    const sim::MetricStats* stats = nullptr;
    for (const auto& [label, s] : mc_.headlines)
      if (label == h.label) stats = &s;
    row(h.label, v, h.better, stats);
  }
  // Then every number of the results' tables.
  for (const sim::Metrics::Table& t : now.tables())
    for (const auto& [row_label, prefix] : t.rows)
      for (const sim::Metrics::Column& c : t.columns) {
        const std::string path = prefix.empty() ? c.path : prefix + "." + c.path;
        if (now.Find(path) == nullptr) continue;  // texts (a mode, an estimator) are not compared
        std::vector<double> v;
        for (const CompareRun& run : runs) {
          const double* x = run.metrics ? run.metrics->Find(path) : nullptr;
          v.push_back(x ? *x : std::nan(""));
        }
        const sim::MetricStats* stats = nullptr;
        if (mc) {
          const int m = mc_.tables->MetricIndex(path);
          if (m >= 0 && !mc_.tables->stats.empty()) stats = &mc_.tables->stats[0][m];
        }
        const std::string label = (row_label.empty() ? t.title : row_label) + " · " + c.header;
        row(label, v, now.BetterOf(path), stats);
      }
  ImGui::EndTable();
  ImGui::Spacing();
}

}  // namespace formsim::app
