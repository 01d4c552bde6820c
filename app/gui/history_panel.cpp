/// \file The History panel (app/gui/history_panel.hpp): the run history, its restore, its tab.
#include "app/gui/history_panel.hpp"

#include "app/gui/compare_panel.hpp"
#include "app/gui/run_panel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/gui/command_row_makers.hpp"
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

void HistoryPanel::Draw(const Fonts&) {
  // ---- history ----
  const auto& rows = history_.rows();
  ImGui::Text("History (%zu runs; saved beside the scenario when it is saved)", rows.size());
  if (rows.empty()) {
    ImGui::TextDisabled("A row is added when a run reaches its end or is reset.");
    return;
  }
  // Metric columns: every headline label, in order of first appearance.
  std::vector<std::string> labels;
  std::vector<sim::Better> better;
  for (const auto& r : rows)
    for (const auto& m : r.metrics)
      if (std::find(labels.begin(), labels.end(), m.label) == labels.end()) {
        labels.push_back(m.label);
        better.push_back(m.better);
      }
  auto metric = [&](const sim::HistoryRow& r, std::size_t c) -> const sim::Metrics::HeadlineValue* {
    for (const auto& m : r.metrics)
      if (m.label == labels[c]) return &m;
    return nullptr;
  };
  // The best value of each metric column (by its declared direction).
  std::vector<double> best(labels.size(), std::nan(""));
  for (std::size_t c = 0; c < labels.size(); ++c)
    for (const auto& r : rows)
      if (const auto* m = metric(r, c);
          m && std::isfinite(m->value) && better[c] != sim::Better::kNone)
        if (std::isnan(best[c]) ||
            (better[c] == sim::Better::kLower ? m->value < best[c] : m->value > best[c]))
          best[c] = m->value;
  // What each row's settings differ in from the loaded file.
  std::vector<std::pair<std::string, std::string>> loaded;
  for (const sim::Param& p : ctx_.session().loaded_params().all())
    loaded.emplace_back(p.key, p.Text());
  std::vector<std::string> settings(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const sim::ParamTable& text = TextParams(*rows[i].source);
    RunValues values;
    for (const auto& [key, v] : loaded) values.emplace_back(key, rows[i].Value(key, text));
    settings[i] = sim::DescribeDifferences(loaded, values, ctx_.session().loaded_params());
    if (settings[i].empty()) settings[i] = "as loaded";
    const int changes = rows[i].mid_run_changes();
    if (changes > 0) settings[i] += " (" + std::to_string(changes) + " mid-run)";
  }

  // Columns: number, buttons, settings (wrapped in a column of fixed width), the metrics, t, seed,
  // status and when: the metrics stay in view in a narrow window.
  enum { kNumber, kButtons, kSettings, kFixed };
  const int settings_col = kSettings;
  const int kTime = kFixed + static_cast<int>(labels.size()), kSeed = kTime + 1;
  const int kStatus = kSeed + 1, kWhen = kStatus + 1;
  const int cols = kWhen + 1;
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_Sortable | ImGuiTableFlags_ScrollX |
                                ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit;
  if (!ImGui::BeginTable("history", cols, flags, ImVec2(0, ImGui::GetContentRegionAvail().y)))
    return;
  ImGui::TableSetupScrollFreeze(2, 1);
  ImGui::TableSetupColumn("#", ImGuiTableColumnFlags_DefaultSort);
  ImGui::TableSetupColumn("", ImGuiTableColumnFlags_NoSort);
  ImGui::TableSetupColumn("settings (vs the file)", ImGuiTableColumnFlags_WidthFixed,
                          11 * ImGui::GetFontSize());
  // Metric columns as wide as their header (in the unit shown) and their numbers need: with
  // ScrollX every one of them can be scrolled to, none is squeezed away.
  const bool degrees = ctx_.state->settings.degrees;
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

  // Sorted by the column the user clicked (its header toggles the direction).
  if (history_order_.size() != rows.size()) {
    history_order_.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) history_order_[i] = static_cast<int>(i);
  }
  if (ImGuiTableSortSpecs* sort = ImGui::TableGetSortSpecs(); sort && sort->SpecsCount > 0) {
    const int c = sort->Specs[0].ColumnIndex;
    const bool asc = sort->Specs[0].SortDirection == ImGuiSortDirection_Ascending;
    auto key = [&](int i) -> double {
      const sim::HistoryRow& r = rows[i];
      if (c == kTime) return r.t_end;
      if (c == kSeed) return static_cast<double>(r.seed);
      if (c >= kFixed && c < kStatus) {
        const auto* m = metric(r, c - kFixed);
        return m ? m->value : std::nan("");
      }
      return r.number;  // number and when: the order they were added
    };
    auto text = [&](int i) { return c == kStatus ? rows[i].status : settings[i]; };
    std::stable_sort(history_order_.begin(), history_order_.end(), [&](int a, int b) {
      if (c == kStatus || c == settings_col) return asc ? text(a) < text(b) : text(b) < text(a);
      const double x = key(a), y = key(b);
      if (std::isnan(x) || std::isnan(y)) return !std::isnan(x) && std::isnan(y);  // no value last
      return asc ? x < y : y < x;
    });
  }
  int restore = 0, pin = 0;
  for (int i : history_order_) {
    const sim::HistoryRow& r = rows[i];
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(kNumber);
    ImGui::Text("%d", r.number);
    ImGui::TableSetColumnIndex(kButtons);
    ImGui::PushID(r.number);
    if (ImGui::SmallButton("↺")) restore = r.number;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "Restore: edit these settings back in (through the normal edit path);\n"
          "the seed goes into the seed field");
    ImGui::SameLine();
    if (ImGui::SmallButton("pin")) pin = r.number;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Replay this run exactly and pin it");
    ImGui::PopID();
    ImGui::TableSetColumnIndex(settings_col);
    ImGui::TextWrapped("%s", settings[i].c_str());
    for (std::size_t c = 0; c < labels.size(); ++c) {
      ImGui::TableSetColumnIndex(kFixed + static_cast<int>(c));
      const auto* m = metric(r, c);
      if (m == nullptr) continue;
      if (std::isfinite(m->value) && m->value == best[c] && rows.size() > 1) MarkBestCell();
      ImGui::TextUnformatted(MetricText(*m, degrees).c_str());
    }
    ImGui::TableSetColumnIndex(kTime);
    ImGui::Text("%.2f", r.t_end);
    ImGui::TableSetColumnIndex(kSeed);
    ImGui::Text("%s", std::to_string(r.seed).c_str());
    ImGui::TableSetColumnIndex(kStatus);
    ImGui::TextUnformatted(r.status.c_str());
    ImGui::TableSetColumnIndex(kWhen);
    ImGui::TextUnformatted(r.when.size() > 11 ? r.when.substr(11).c_str() : r.when.c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", r.when.c_str());
  }
  ImGui::EndTable();
  if (restore) CmdRestore(restore);
  if (pin) ctx_.run("pin-row " + std::to_string(pin));
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
