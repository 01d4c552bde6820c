/// \file The History panel (app/gui/history_panel.hpp): the run history, its restore, its tab.
#include "app/gui/history_panel.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/table_header.hpp"
#include "app/gui/ui.hpp"
#include "app/render/display_unit.hpp"
#include "sim/core/number_format.hpp"

namespace fs = std::filesystem;

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {

namespace {

// A metric cell: the comparison table's formatter and digits, in the unit its column shows.
std::string MetricText(const sim::Metrics::HeadlineValue& m, bool degrees) {
  if (std::isnan(m.value)) return "-";
  return sim::FormatCell(m.value * ShownUnit(LabelUnit(m.label), degrees).scale, 4);
}

}  // namespace

std::optional<sim::HistoryRow> HistoryPanel::PendingRow(const std::string& status) const {
  if (ctx_.session().exp().steps() == 0 || history_run_ == ctx_.session().run_id())
    return std::nullopt;
  try {
    return sim::RunHistory::RowOf(ctx_.session(), status);
  } catch (const std::exception&) {
    return std::nullopt;  // the session's text no longer reads without overrides
  }
}

void HistoryPanel::NoteRun(const std::string& status) {
  if (auto row = PendingRow(status)) {
    history_.Add(std::move(*row));
    history_run_ = ctx_.session().run_id();
  }
}

void HistoryPanel::LoadFor(const std::string& file) {
  history_run_ = -1;
  const auto kept = histories_.find(file);
  if (kept != histories_.end()) {
    history_ = std::move(kept->second);
    histories_.erase(kept);
    return;
  }
  history_ = sim::RunHistory();
  const std::string path = sim::RunHistory::PathFor(file);
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  try {
    history_ = sim::RunHistory::Load(path);
  } catch (const std::exception& e) {
    ctx_.SetStatus(std::string("the history beside the scenario was not read: ") + e.what(), true);
  }
}

void HistoryPanel::Shelve(const std::string& file) {
  if (auto row = PendingRow("closed")) history_.Add(std::move(*row));
  histories_[file] = std::move(history_);
  history_ = sim::RunHistory();
}

const sim::ParamTable& HistoryPanel::TextParams(const sim::ScenarioSource& source) {
  auto it = text_params_.find(source.sha256());
  if (it == text_params_.end()) {
    sim::ParamTable params;
    try {
      params = sim::ParseScenario(source, {}).params;
    } catch (const std::exception&) {
      // A text that reads only with overrides: its rows show their settings as recorded.
    }
    it = text_params_.emplace(source.sha256(), std::move(params)).first;
  }
  return it->second;
}

const sim::HistoryRow* HistoryPanel::RowOrRefuse(const std::string& action, int number,
                                                 std::string* why) {
  const sim::HistoryRow* row = history_.Find(number);
  if (row == nullptr) {
    *why = action + ": no history row " + std::to_string(number);
    ctx_.SetStatus(*why, true);
  }
  return row;
}

std::string HistoryPanel::CmdRestore(int number) {
  std::string why;
  const sim::HistoryRow* row = RowOrRefuse("restore", number, &why);
  if (row == nullptr) return why;
  const sim::HistoryRow r = *row;  // edits below may not touch the history, but be safe
  const sim::ParamTable& text = TextParams(*r.source);
  int edits = 0;
  std::string refused;
  for (const sim::Param& p : ctx_.session().params().all()) {
    const std::string v = r.Value(p.key, text);
    if (v.empty() || v == ctx_.session().EffectiveValue(p.key)) continue;
    const std::string err = ctx_.session().Edit(p.key, v, "restore");
    if (err.empty())
      ++edits;
    else
      refused += (refused.empty() ? "" : "; ") + p.key + ": " + err;
  }
  ctx_.Find<RunPanel>()->SetSeedField(std::to_string(r.seed));
  sim::SessionEvent note;
  note.kind = sim::SessionEvent::Kind::kNote;
  note.key = "restore";
  note.value = "history row " + std::to_string(number);
  note.step = ctx_.session().exp().steps();
  ctx_.record->Add(note);
  std::string msg = "restored row " + std::to_string(number) + ": " + std::to_string(edits) +
                    " edit" + (edits == 1 ? "" : "s");
  if (r.seed != ctx_.session().seed())
    msg += "; its seed " + std::to_string(r.seed) + " is in the seed field (Reset with seed)";
  if (!refused.empty()) {
    ctx_.SetStatus(msg + "; refused: " + refused, true);
    return refused;
  }
  ctx_.SetStatus(msg);
  return "";
}

namespace {

// The table's columns: number, buttons, settings (wrapped in a column of fixed width), the
// metrics, t, seed, status and when: the metrics stay in view in a narrow window.
enum { kHistoryNumber, kHistoryButtons, kHistorySettings, kHistoryMetrics };

// Where the columns after the metrics are, with `metrics` metric columns.
struct HistoryColumns {
  explicit HistoryColumns(std::size_t metrics)
      : time(kHistoryMetrics + static_cast<int>(metrics)),
        seed(time + 1),
        status(seed + 1),
        when(status + 1),
        count(when + 1) {}
  int time, seed, status, when, count;
};

// The metric columns: every headline label, in order of first appearance, its direction and
// the best value of the column (by that direction; nan when there is none).
struct HistoryMetricColumns {
  std::vector<std::string> labels;
  std::vector<sim::Better> better;
  std::vector<double> best;
};

// Row `r`'s value of metric `label`; null when it has none.
const sim::Metrics::HeadlineValue* HistoryMetric(const sim::HistoryRow& r,
                                                 const std::string& label) {
  for (const auto& m : r.metrics)
    if (m.label == label) return &m;
  return nullptr;
}

HistoryMetricColumns HistoryMetricColumnsOf(const std::vector<sim::HistoryRow>& rows) {
  HistoryMetricColumns out;
  std::vector<std::string>& labels = out.labels;
  std::vector<sim::Better>& better = out.better;
  for (const auto& r : rows)
    for (const auto& m : r.metrics)
      if (std::find(labels.begin(), labels.end(), m.label) == labels.end()) {
        labels.push_back(m.label);
        better.push_back(m.better);
      }
  std::vector<double>& best = out.best;
  best.assign(labels.size(), std::nan(""));
  for (std::size_t c = 0; c < labels.size(); ++c)
    for (const auto& r : rows)
      if (const auto* m = HistoryMetric(r, labels[c]);
          m && std::isfinite(m->value) && better[c] != sim::Better::kNone)
        if (std::isnan(best[c]) ||
            (better[c] == sim::Better::kLower ? m->value < best[c] : m->value > best[c]))
          best[c] = m->value;
  return out;
}

// The columns' setup and the header row; metric columns as wide as their header (in the unit
// shown) and their numbers need: with ScrollX every one of them can be scrolled to, none is
// squeezed away.
void HistorySetupColumns(const std::vector<std::string>& labels, bool degrees) {
  ImGui::TableSetupScrollFreeze(2, 1);
  ImGui::TableSetupColumn("#", ImGuiTableColumnFlags_DefaultSort);
  ImGui::TableSetupColumn("", ImGuiTableColumnFlags_NoSort);
  ImGui::TableSetupColumn("settings (vs the file)", ImGuiTableColumnFlags_WidthFixed,
                          11 * ImGui::GetFontSize());
  std::vector<std::string> headers = {"#", "", "settings (vs the file)"};
  for (const auto& l : labels) {
    headers.push_back(ShownLabel(l, degrees));
    ImGui::TableSetupColumn(headers.back().c_str(), ImGuiTableColumnFlags_WidthFixed,
                            std::max(ImGui::CalcTextSize(headers.back().c_str()).x +
                                         ImGui::GetFontSize(),
                                     ImGui::CalcTextSize("0.0000000").x));
  }
  for (const char* h : {"t [s]", "seed", "status", "when"}) {
    ImGui::TableSetupColumn(h);
    headers.push_back(h);
  }
  TableHeaders(headers, true);
}

// `order` sorted by the column the user clicked (its header toggles the direction).
void HistorySortRows(std::vector<int>& order, const std::vector<sim::HistoryRow>& rows,
                     const std::vector<std::string>& settings, const HistoryMetricColumns& metrics,
                     const HistoryColumns& col) {
  if (order.size() != rows.size()) {
    order.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) order[i] = static_cast<int>(i);
  }
  ImGuiTableSortSpecs* sort = ImGui::TableGetSortSpecs();
  if (!sort || sort->SpecsCount <= 0) return;
  const int c = sort->Specs[0].ColumnIndex;
  const bool asc = sort->Specs[0].SortDirection == ImGuiSortDirection_Ascending;
  auto key = [&](int i) -> double {
    const sim::HistoryRow& r = rows[i];
    if (c == col.time) return r.t_end;
    if (c == col.seed) return static_cast<double>(r.seed);
    if (c >= kHistoryMetrics && c < col.status) {
      const auto* m = HistoryMetric(r, metrics.labels[c - kHistoryMetrics]);
      return m ? m->value : std::nan("");
    }
    return r.number;  // number and when: the order they were added
  };
  auto text = [&](int i) { return c == col.status ? rows[i].status : settings[i]; };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (c == col.status || c == kHistorySettings)
      return asc ? text(a) < text(b) : text(b) < text(a);
    const double x = key(a), y = key(b);
    if (std::isnan(x) || std::isnan(y)) return !std::isnan(x) && std::isnan(y);  // no value last
    return asc ? x < y : y < x;
  });
}

// What a click in a row's buttons asks for (0: nothing).
struct HistoryClicks {
  int restore = 0, pin = 0;
};

// The ↺ (restore) and pin buttons of row `number`.
void HistoryRowButtons(int number, HistoryClicks& clicks) {
  ImGui::PushID(number);
  if (ImGui::SmallButton("↺")) clicks.restore = number;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Restore: edit these settings back in (through the normal edit path);\n"
        "the seed goes into the seed field");
  ImGui::SameLine();
  if (ImGui::SmallButton("pin")) clicks.pin = number;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Replay this run exactly and pin it");
  ImGui::PopID();
}

// One row of the table; its best metric values marked when there is more than one row.
void HistoryDrawRow(const sim::HistoryRow& r, const std::string& settings,
                    const HistoryMetricColumns& metrics, const HistoryColumns& col, bool mark_best,
                    bool degrees, HistoryClicks& clicks) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(kHistoryNumber);
  ImGui::Text("%s", sim::Sprintf("%d", r.number).c_str());
  ImGui::TableSetColumnIndex(kHistoryButtons);
  HistoryRowButtons(r.number, clicks);
  ImGui::TableSetColumnIndex(kHistorySettings);
  ImGui::TextWrapped("%s", settings.c_str());
  for (std::size_t c = 0; c < metrics.labels.size(); ++c) {
    ImGui::TableSetColumnIndex(kHistoryMetrics + static_cast<int>(c));
    const auto* m = HistoryMetric(r, metrics.labels[c]);
    if (m == nullptr) continue;
    if (std::isfinite(m->value) && m->value == metrics.best[c] && mark_best) MarkBestCell();
    ImGui::TextUnformatted(MetricText(*m, degrees).c_str());
  }
  ImGui::TableSetColumnIndex(col.time);
  ImGui::Text("%s", sim::Sprintf("%.2f", r.t_end).c_str());
  ImGui::TableSetColumnIndex(col.seed);
  ImGui::Text("%s", std::to_string(r.seed).c_str());
  ImGui::TableSetColumnIndex(col.status);
  ImGui::TextUnformatted(r.status.c_str());
  ImGui::TableSetColumnIndex(col.when);
  ImGui::TextUnformatted(r.when.size() > 11 ? r.when.substr(11).c_str() : r.when.c_str());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", r.when.c_str());
}

// What each row's settings differ in from the loaded file ("as loaded" when nothing), with its
// count of mid-run changes; `text_params` gives the parameters a scenario text reads with.
template <class TextParamsOf>
std::vector<std::string> HistorySettingsTexts(const std::vector<sim::HistoryRow>& rows,
                                              const sim::ParamTable& loaded_params,
                                              TextParamsOf text_params) {
  std::vector<std::pair<std::string, std::string>> loaded;
  for (const sim::Param& p : loaded_params.all()) loaded.emplace_back(p.key, p.Text());
  std::vector<std::string> settings(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const sim::ParamTable& text = text_params(*rows[i].source);
    RunValues values;
    for (const auto& [key, v] : loaded) values.emplace_back(key, rows[i].Value(key, text));
    settings[i] = sim::DescribeDifferences(loaded, values, loaded_params);
    if (settings[i].empty()) settings[i] = "as loaded";
    const int changes = rows[i].mid_run_changes();
    if (changes > 0) settings[i] += " (" + std::to_string(changes) + " mid-run)";
  }
  return settings;
}

}  // namespace

void HistoryPanel::Draw(const Fonts&) {
  const auto& rows = history_.rows();
  ImGui::Text("%s", sim::Sprintf("History (%zu runs; saved beside the scenario when it is saved)",
                                 rows.size())
                        .c_str());
  if (rows.empty()) {
    ImGui::TextDisabled("A row is added when a run reaches its end or is reset.");
    return;
  }
  const HistoryMetricColumns metrics = HistoryMetricColumnsOf(rows);
  const std::vector<std::string> settings = HistorySettingsTexts(
      rows, ctx_.session().loaded_params(),
      [this](const sim::ScenarioSource& s) -> const sim::ParamTable& { return TextParams(s); });
  const HistoryColumns col(metrics.labels.size());
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_Sortable | ImGuiTableFlags_ScrollX |
                                ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit;
  if (!ImGui::BeginTable("history", col.count, flags, ImVec2(0, ImGui::GetContentRegionAvail().y)))
    return;
  const bool degrees = ctx_.state->settings.degrees;
  HistorySetupColumns(metrics.labels, degrees);
  HistorySortRows(history_order_, rows, settings, metrics, col);
  HistoryClicks clicks;
  for (int i : history_order_)
    HistoryDrawRow(rows[i], settings[i], metrics, col, rows.size() > 1, degrees, clicks);
  ImGui::EndTable();
  if (clicks.restore) CmdRestore(clicks.restore);
  if (clicks.pin) ctx_.run("pin-row " + std::to_string(clicks.pin));
}

std::vector<Command> HistoryPanel::Rows() {
  using rows::Whole;
  using Src = CommandSource;
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "history",
       .menu = "Compare/History",
       .help = "Show the history of runs (the History tab)",
       .run = [](AppUi& ui, const CommandArgs&, Src) {
         ui.state().select_tab = "history";
         return std::string();
       }});
  row({.name = "restore",
       .args = {Whole("N", 1, 1000000000)},
       .menu = "Compare/Restore history row…",
       .help = "Edit the settings of history row N back in (its seed into the seed field)",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return ui.Find<HistoryPanel>()->CmdRestore(static_cast<int>(a.Whole(0)));
       }});
  row({.name = "pin-row",
       .args = {Whole("N", 1, 1000000000)},
       .menu = "Compare/Pin history row…",
       .help = "Replay history row N exactly and pin it",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return ui.Find<ComparePanel>()->CmdPinRow(static_cast<int>(a.Whole(0)));
       }});
  return t;
}

}  // namespace formsim::app
