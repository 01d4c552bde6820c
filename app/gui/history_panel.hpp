#pragma once
/// \file The History panel: the run history of the scenario, a row for every run that reaches
/// its end or is reset (when, how far, status, seed, what differs from the loaded file,
/// headline metrics), sortable by any column, drawn in the History tab. A row's settings can be
/// edited back in (`restore`) or the run pinned (`pin-row`, replayed exactly from its log). The
/// histories of scenarios opened before are kept for when they are opened again. It owns the
/// histories and registers history, restore and pin-row.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"
#include "sim/session/run_history.hpp"

namespace formsim::app {

class HistoryPanel : public Panel {
 public:
  explicit HistoryPanel(const PanelContext& ctx) : ctx_(ctx) {}
  /// history, restore, pin-row (Compare menu).
  static std::vector<Command> Rows();

  const char* Name() const override { return "History"; }
  /// The history table of the History tab (under the pinned runs).
  void Draw(const Fonts& fonts) override;

  /// Edits the settings of history row `number` back in (seed into the seed field).
  std::string CmdRestore(int number);
  /// History row `number`; null when there is none, with the reason in `why` and the status.
  const sim::HistoryRow* RowOrRefuse(const std::string& action, int number, std::string* why);

  /// Before the current run is replaced (reset, reload, branch, load): its history row.
  std::optional<sim::HistoryRow> PendingRow(const std::string& status) const;
  /// Adds a row made by PendingRow.
  void Add(sim::HistoryRow row) { history_.Add(std::move(row)); }
  /// Adds the current run to the history when it has run and has no row yet.
  void NoteRun(const std::string& status);
  /// Another scenario replaces the current one: its last run goes into its history, kept
  /// (by `file`) for when it is opened again.
  void Shelve(const std::string& file);
  /// The history of scenario `file`: kept from before, else read from beside the file.
  void LoadFor(const std::string& file);
  /// The current run has no history row yet (another scenario was loaded).
  void Forget() { history_run_ = -1; }
  const sim::RunHistory& history() const { return history_; }

 private:
  const sim::ParamTable& TextParams(const sim::ScenarioSource& source);

  const PanelContext& ctx_;
  sim::RunHistory history_;
  std::map<std::string, sim::RunHistory> histories_;    ///< of scenarios opened before, by file
  long history_run_ = -1;                               ///< run id that has its history row
  std::map<std::string, sim::ParamTable> text_params_;  ///< by SHA-256 of a scenario text
  std::vector<int> history_order_;  ///< rows in the order shown (sorted by a column)
};

}  // namespace formsim::app
