#include "app/gui/tables_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "app/gui/compare_panel.hpp"
#include "app/gui/table_header.hpp"
#include "app/gui/ui.hpp"
#include "app/render/display_unit.hpp"
#include "app/render/fonts.hpp"
#include "sim/core/metrics.hpp"
#include "sim/core/number_format.hpp"
#include "sim/session/session.hpp"

namespace formsim::app {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kTableRefresh = std::chrono::milliseconds(250);

}  // namespace

struct TablesPanel::Cache {
  // Which run: another run (reset, load) drops everything.
  const sim::Experiment* exp = nullptr;
  std::string file, name;
  long steps = -1;        ///< at the last frame (no step since: paused, refresh at once)
  bool paused = false;
  int frame = -1;  ///< ImGui frame of the last check
  sim::Metrics results;   ///< the results as summary.json has them
  std::vector<sim::TableSpec> tables;
  std::string summary;
  Clock::time_point tables_at, summary_at;
  long tables_steps = -1, summary_steps = -1;
  bool tables_valid = false;
};

TablesPanel::TablesPanel(const PanelContext& ctx)
    : ctx_(ctx), cache_(std::make_unique<Cache>()) {}
TablesPanel::~TablesPanel() = default;

TablesPanel::Cache& TablesPanel::Fresh() {
  const sim::Experiment& exp = ctx_.session().exp();
  Cache& cache = *cache_;
  // A new run (or the same one reset: fewer steps than before) drops everything.
  if (&exp != cache.exp || exp.steps() < cache.steps || exp.setup().file != cache.file ||
      exp.setup().name != cache.name) {
    cache = Cache{};
    cache.exp = &exp;
    cache.file = exp.setup().file;
    cache.name = exp.setup().name;
  }
  // Once a frame (the tab bar asks, then a tab draws).
  const int frame = ImGui::GetFrameCount();
  if (frame != cache.frame) {
    cache.frame = frame;
    cache.paused = exp.steps() == cache.steps;
    cache.steps = exp.steps();
  }
  return cache;
}

bool TablesPanel::HasTables() {
  Cache& cache = Fresh();
  // The results as tables (the same metrics as summary.json), then the experiment's own;
  // computed once to know whether there are any, then only while the tab is shown.
  if (!cache.tables_valid) {
    const sim::Experiment& exp = ctx_.session().exp();
    cache.results = exp.Results();
    cache.tables = cache.results.GuiTables();
    for (auto& t : exp.Tables()) cache.tables.push_back(std::move(t));
    cache.tables_at = Clock::now();
    cache.tables_steps = exp.steps();
    cache.tables_valid = true;
  }
  return !cache.tables.empty();
}

void TablesPanel::Draw(const Fonts&) {
  Cache& cache = Fresh();
  const sim::Experiment& exp = ctx_.session().exp();
  if (exp.steps() != cache.tables_steps &&
      (cache.paused || Clock::now() - cache.tables_at >= kTableRefresh))
    cache.tables_valid = false;
  HasTables();
  // A run that has not started (reset, or loaded paused) has no results: an honest empty
  // state, never a table of zeros.
  const bool no_data = exp.steps() == 0;
  if (no_data) DrawNoData();
  ctx_.Find<ComparePanel>()->DrawCompareTable(cache.results);
  if (no_data) return;
  if (cache.tables.empty()) ImGui::TextDisabled("This scenario has no tables of results.");
  const std::vector<sim::TableSpec>& tables = cache.tables;
  for (std::size_t t = 0; t < tables.size(); ++t) {
    const sim::TableSpec& spec = tables[t];
    ImGui::TextUnformatted(spec.title.c_str());
    const int cols = static_cast<int>(spec.header.size()) + (spec.row_strength.empty() ? 0 : 1);
    if (cols == 0) continue;
    ImGui::PushID(static_cast<int>(t));
    if (ImGui::BeginTable("tbl", cols,
                          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                              ImGuiTableFlags_SizingStretchProp)) {
      // Headers in the unit shown (angles in the window's unit), never cut mid-unit; the
      // numbers of a column with the comparison table's formatter, in that unit.
      std::vector<std::string> headers;
      std::vector<double> scale;
      for (const auto& h : spec.header) {
        headers.push_back(ShownLabel(h, ctx_.state->settings.degrees));
        scale.push_back(ShownUnit(LabelUnit(h), ctx_.state->settings.degrees).scale);
        ImGui::TableSetupColumn(headers.back().c_str());
      }
      if (!spec.row_strength.empty()) {
        ImGui::TableSetupColumn("strength");
        headers.push_back("strength");
      }
      TableHeaders(headers);
      // The results' own tables come first (GuiTables keeps their order).
      const auto& result_tables = cache.results.tables();
      const sim::Metrics::Table* metrics = t < result_tables.size() ? &result_tables[t] : nullptr;
      // Only the rows in view are laid out (a thousand links make thousands of rows).
      ImGuiListClipper clipper;
      clipper.Begin(static_cast<int>(spec.rows.size()));
      while (clipper.Step()) {
        for (int r = clipper.DisplayStart; r < clipper.DisplayEnd; ++r) {
          ImGui::TableNextRow();
          for (std::size_t c = 0; c < spec.header.size(); ++c) {
            ImGui::TableSetColumnIndex(static_cast<int>(c));
            if (c >= spec.rows[r].size()) continue;
            // A metric from its value (not from its rounded text), another table's number
            // from its text.
            double x = 0;
            const double* value = nullptr;
            if (metrics != nullptr && c >= 1 && static_cast<std::size_t>(r) < metrics->rows.size() &&
                c - 1 < metrics->columns.size()) {
              const std::string& prefix = metrics->rows[r].second;
              const std::string& path = metrics->columns[c - 1].path;
              value = cache.results.Find(prefix.empty() ? path : prefix + "." + path);
            }
            const std::string& cell = spec.rows[r][c];
            if (value == nullptr && sim::ParseFiniteDouble(cell, &x)) value = &x;
            ImGui::TextUnformatted(value != nullptr ? sim::FormatCell(*value * scale[c], 4).c_str()
                                                    : cell.c_str());
          }
          if (!spec.row_strength.empty()) {
            ImGui::TableSetColumnIndex(static_cast<int>(spec.header.size()));
            const double s = static_cast<std::size_t>(r) < spec.row_strength.size()
                                 ? spec.row_strength[r]
                                 : 0.0;
            ImGui::ProgressBar(
                static_cast<float>(std::clamp(std::isfinite(s) ? s : 0.0, 0.0, 1.0)),
                ImVec2(-1, 0));
          }
        }
      }
      ImGui::EndTable();
    }
    ImGui::PopID();
    ImGui::Spacing();
  }
}

void TablesPanel::DrawNoData() {
  ImGui::TextWrapped("No data yet: the run has not started. Press Play (space) and the results "
                     "fill in as it runs.");
  ImGui::Spacing();
}

void TablesPanel::DrawSummary(const Fonts& fonts) {
  Cache& cache = Fresh();
  const sim::Experiment& exp = ctx_.session().exp();
  if (exp.steps() == 0) {
    DrawNoData();
    return;
  }
  const bool paused = cache.paused;
  const Clock::time_point now = Clock::now();
  if (cache.summary_steps != exp.steps() &&
      (cache.summary.empty() || paused || now - cache.summary_at >= kTableRefresh)) {
    cache.summary = exp.SummaryText();
    cache.summary_at = now;
    cache.summary_steps = exp.steps();
  }
  ImGui::PushFont(fonts.mono);
  ImGui::TextUnformatted(cache.summary.c_str());
  ImGui::PopFont();
  ImGui::Separator();
  const auto& events = exp.events().list();
  ImGui::Text("%s", sim::Sprintf("%zu events", events.size()).c_str());
  ImGuiListClipper clipper;
  clipper.Begin(static_cast<int>(events.size()));
  while (clipper.Step())
    for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
      const auto& e = events[static_cast<std::size_t>(i)];
      ImGui::Text("%s", sim::Sprintf("%.2f s  %s  %s: %s", e.time, e.kind.c_str(), e.robots.c_str(),
                                     e.message.c_str())
                            .c_str());
    }
}

}  // namespace formsim::app
