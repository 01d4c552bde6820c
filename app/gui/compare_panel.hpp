#pragma once
/// \file The Compare panel: runs kept to compare the live run with. It owns the pinned runs
/// (exact replays of a run's log, made on a thread of their own), the Monte Carlo ("Run N
/// seeds" in the background, as `formsim sweep --seeds 1..N`) and the runs cut to a common
/// span for the comparison table. It draws the Compare section of the control panel, the
/// pinned runs of the History tab and the comparison table of the Tables tab, decorates every
/// live plot (pins dashed, the Monte Carlo's bands) and hands the world view the pins to draw
/// faded. It registers pin, unpin, unpin-all, seeds and cancel-seeds.

#include <memory>
#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"
#include "app/gui/span_metrics.hpp"
#include "app/gui/tuning_state.hpp"
#include "sim/session/run_log.hpp"

namespace formsim::sim {
class Metrics;
class Session;
struct FigureSpec;
}  // namespace formsim::sim

namespace formsim::app {

struct PlotData;
struct WorldViewOptions;

/// Tunable values and seed of the session's current run (what a pin's label compares with).
RunValues CurrentValues(const sim::Session& session);

class ComparePanel : public Panel {
 public:
  explicit ComparePanel(const PanelContext& ctx) : ctx_(ctx) {}
  /// pin, unpin, unpin-all, seeds, cancel-seeds (Compare menu).
  static std::vector<Command> Rows();

  const char* Name() const override { return "Compare"; }
  /// The Compare section of the control panel: pin, Monte Carlo, undo/redo, save session.
  void Draw(const Fonts& fonts) override;

  // ---- Commands: "" or why refused (also in the status line).
  /// Pins the current run as it stands: a reference drawn faded (world) and dashed (plots).
  std::string CmdPin();
  /// Pins history row `number` (replayed exactly from its log).
  std::string CmdPinRow(int number);
  std::string CmdUnpin(int id);
  std::string CmdUnpinAll();
  /// Runs the current settings over seeds 1..n in the background (as `formsim sweep`).
  std::string CmdSeeds(int n);
  std::string CmdCancelSeeds();

  /// Per frame: collects finished pin replays and the Monte Carlo's bands and tables.
  void Update();
  /// Another scenario was loaded: pins, Monte Carlo and cut runs go.
  void Clear();
  /// A pin replays, the Monte Carlo runs, or a run is being cut to the common span.
  bool Busy() const;
  /// A Monte Carlo is under way.
  bool SeedsRunning() const;
  /// Writes the tables of the finished Monte Carlo (runs.csv, aggregate.csv, as `formsim sweep`
  /// writes them) into `dir`/montecarlo. Returns false when there is none.
  bool WriteMonteCarlo(const std::string& dir);
  const std::vector<std::unique_ptr<PinnedRun>>& pins() const { return pins_; }

  /// "pin 1: k_l 0.15 -> 0.4" (what differs from the current run).
  std::string PinLabel(const PinnedRun& pin) const;
  /// Adds the pinned runs and the Monte Carlo bands to a live plot of figure `fig`.
  void DecoratePlot(const sim::FigureSpec& fig, PlotData& data);
  /// What DecoratePlot adds, as text: a plot drawn before is redrawn when it changes.
  std::string Decoration() const;
  /// The ready pins, drawn faded in the world view.
  void AddWorldOverlays(WorldViewOptions& opt) const;

  /// One run's column of the comparison table.
  struct CompareRun {
    std::string header;                     ///< "now (9.4 of 11.0 s)", "pin 1 (9.4 s)"
    const sim::Metrics* metrics = nullptr;  ///< over the common span; null while replayed
    std::string why;                        ///< why there are no metrics yet
    bool no_data = false;  ///< the live run has not started: nothing to show, nothing to wait for
  };
  /// The runs of the comparison table, the live run then each ready pin, every one cut to the
  /// common span (the shortest run's time) by an exact replay; `title` gets the table's title,
  /// which says so. `now`: the live run's metrics over all of it.
  std::vector<CompareRun> CompareRuns(const sim::Metrics& now, std::string* title);
  /// The comparison table (Tables tab): nothing while nothing is pinned and no Monte Carlo ran.
  void DrawCompareTable(const sim::Metrics& now);
  /// The History tab's list of the pinned runs (above the history table).
  void DrawPinnedRuns();

 private:
  std::string PinReplay(std::shared_ptr<const sim::ScenarioSource> source, sim::RunLog log,
                        long steps, const std::string& origin);
  /// A note in the session record (pin, unpin, seeds) at the live run's step.
  void Note(const std::string& key, const std::string& value);

  const PanelContext& ctx_;
  std::vector<std::unique_ptr<PinnedRun>> pins_;
  int next_pin_ = 1;
  MonteCarloState mc_;
  int mc_seeds_ = 20;  ///< the Compare section's "Run N seeds"
  SpanMetrics span_;   ///< runs cut to the common span of the comparison table
};

}  // namespace formsim::app
