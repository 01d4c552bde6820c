/// \file Comparing runs: the pinned runs drawn dashed over every live plot (one dash pattern per
/// pin, a legend entry naming what differs), the Monte Carlo spread as bands (min-max light,
/// mean ± σ darker) on every time plot, and the comparison table: the headline metrics and every
/// number of the results' tables for the current run, each pinned run and the Monte Carlo
/// (mean ± σ), the better value of each row marked by the metric's declared direction.
#include <algorithm>
#include <cmath>

#include "app/export/figure_data.hpp"
#include "app/gui/ui.hpp"
#include "app/render/label_markup.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {

namespace {

const ImVec4 kBest(0.55f, 0.85f, 0.55f, 0.45f);

// Figures can change with the settings (an estimator switched on adds series): a pin's resolved
// figure is kept per figure and list of columns.
std::string FigureKey(const sim::FigureSpec& fig) {
  std::string k = fig.id;
  for (const auto& s : fig.series) k += "|" + s.column + "/" + s.x_column;
  return k;
}

}  // namespace

void AppUi::DecoratePlot(const sim::FigureSpec& fig, PlotData& data) {
  const sim::Color legend_ink = GetTheme(state_.theme).axis;
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

void AppUi::DrawCompareTable(const sim::Metrics& now) {
  std::vector<const PinnedRun*> pins;
  for (const auto& p : pins_)
    if (p->ready() && p->results) pins.push_back(p.get());
  const bool mc = mc_.tables.has_value();
  if (pins.empty() && !mc) return;
  ImGui::TextUnformatted("Compare: the current run, the pinned runs and the Monte Carlo");
  const int cols = 2 + static_cast<int>(pins.size()) + (mc ? 1 : 0);
  if (!ImGui::BeginTable(
          "compare", cols,
          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp))
    return;
  ImGui::TableSetupColumn("metric", ImGuiTableColumnFlags_WidthStretch, 2.0f);
  // Each run's column says how far it got: a run just reset has no errors yet.
  ImGui::TableSetupColumn(sim::Sprintf("now (%.1f s)", session_->exp().time()).c_str());
  for (const PinnedRun* p : pins)
    ImGui::TableSetupColumn(sim::Sprintf("pin %d (%.1f s)", p->id, p->exp->time()).c_str());
  if (mc) ImGui::TableSetupColumn((std::to_string(mc_.seeds) + " seeds, mean ± σ").c_str());
  ImGui::TableHeadersRow();

  // One row: the values of each run (NaN: none), their texts, the direction.
  auto row = [&](const std::string& label, const std::vector<double>& v,
                 const std::vector<std::string>& text, sim::Better better,
                 const std::string& mc_text) {
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
    ImGui::TextUnformatted(label.c_str());
    if (better != sim::Better::kNone && ImGui::IsItemHovered())
      ImGui::SetTooltip(better == sim::Better::kLower ? "lower is better" : "higher is better");
    for (std::size_t i = 0; i < v.size(); ++i) {
      ImGui::TableSetColumnIndex(1 + static_cast<int>(i));
      if (better != sim::Better::kNone && finite > 1 && differ && v[i] == best)
        ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, ImGui::GetColorU32(kBest));
      ImGui::TextUnformatted(text[i].c_str());
    }
    if (mc) {
      ImGui::TableSetColumnIndex(cols - 1);
      ImGui::TextUnformatted(mc_text.c_str());
    }
  };
  auto mean_sd = [](const sim::MetricStats& s) {
    if (s.n == 0) return std::string("-");
    return sim::Sprintf("%.4g", s.mean) +
           (std::isnan(s.std) ? "" : " ± " + sim::Sprintf("%.2g", s.std));
  };
  // Headlines first.
  const auto head_now = now.Headlines();
  for (const auto& h : head_now) {
    std::vector<double> v;
    std::vector<std::string> text;
    auto add = [&](const std::vector<sim::Metrics::HeadlineValue>& hs) {
      double x = std::nan("");
      for (const auto& o : hs)
        if (o.label == h.label) x = o.value;
      v.push_back(x);
      text.push_back(std::isnan(x)      ? "-"
                     : h.format.empty() ? sim::FormatDouble(x)
                                        : sim::Sprintf(h.format.c_str(), x));
    };
    add(head_now);
    for (const PinnedRun* p : pins) add(p->results->Headlines());
    std::string mc_text;
    for (const auto& [label, stats] : mc_.headlines)
      if (label == h.label) mc_text = mean_sd(stats);
    row(h.label, v, text, h.better, mc_text);
  }
  // Then every number of the results' tables.
  for (const sim::Metrics::Table& t : now.tables())
    for (const auto& [row_label, prefix] : t.rows)
      for (const sim::Metrics::Column& c : t.columns) {
        const std::string path = prefix.empty() ? c.path : prefix + "." + c.path;
        if (now.Find(path) == nullptr) continue;  // texts (a mode, an estimator) are not compared
        std::vector<double> v;
        std::vector<std::string> text;
        auto add = [&](const sim::Metrics& m) {
          const double* x = m.Find(path);
          v.push_back(x ? *x : std::nan(""));
          text.push_back(m.Cell(path, c.format));
        };
        add(now);
        for (const PinnedRun* p : pins) add(*p->results);
        std::string mc_text = "-";
        if (mc) {
          const int m = mc_.tables->MetricIndex(path);
          if (m >= 0 && !mc_.tables->stats.empty()) mc_text = mean_sd(mc_.tables->stats[0][m]);
        }
        const std::string label = (row_label.empty() ? t.title : row_label) + " · " + c.header;
        row(label, v, text, now.BetterOf(path), mc_text);
      }
  ImGui::EndTable();
  ImGui::Spacing();
}

}  // namespace formsim::app
