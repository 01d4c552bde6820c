#pragma once
/// \file What the interface keeps for tuning beside the running session: pinned runs (exact
/// replays made on a thread of their own), the timeline's replay, the Monte Carlo under way and
/// the run history. Plain data; the panels and commands that use it are in app/ui_*.cpp.

#include <atomic>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/render/plot.hpp"
#include "sim/study/monte_carlo.hpp"
#include "sim/session/run_history.hpp"
#include "sim/session/run_log.hpp"

namespace formsim::app {

/// Tunable values of a run (key -> YAML text) and its seed under the key "seed".
using RunValues = std::vector<std::pair<std::string, std::string>>;

/// A run kept as a reference. The copy is a replay of the run's log from step 0 (the simulation
/// is deterministic, so it is the run itself, bit for bit), made in the background.
struct PinnedRun {
  PinnedRun() = default;
  PinnedRun(const PinnedRun&) = delete;
  PinnedRun& operator=(const PinnedRun&) = delete;
  /// Stops the replay (the future then waits only for its next poll).
  ~PinnedRun() {
    if (cancel) *cancel = true;
  }
  int id = 0;          ///< "pin 1", "pin 2", ...
  std::string origin;  ///< "the run at t = 7.00 s", "history row 3"
  long steps = 0;      ///< the step it is pinned at
  std::shared_ptr<const sim::ScenarioSource> source;  ///< what it replays (the comparison
  sim::RunLog log;                                    ///< table replays it to a common span)
  struct Result {
    std::unique_ptr<sim::Experiment> exp;
    RunValues values;
    std::string error;
  };
  std::shared_ptr<std::atomic<bool>> cancel;
  std::future<Result> job;               ///< valid while the replay runs
  std::unique_ptr<sim::Experiment> exp;  ///< the replayed run once ready
  RunValues values;
  std::optional<sim::Metrics> results;
  std::string error;                      ///< why the replay failed
  std::map<std::string, PlotData> plots;  ///< figures resolved once (the run no longer changes)
  bool ready() const { return exp != nullptr; }
};

/// The timeline: the world at an earlier step of the live run, from a replay of its log that
/// moves forward step by step and is rebuilt only to go back.
struct Timeline {
  bool active = false;  ///< the world view shows `target`, not the live end
  long target = 0;      ///< step shown
  long run_id = -1;     ///< the session run the replay belongs to
  std::unique_ptr<sim::RunReplay> replay;
  long rebuilds = 0;  ///< replays started (for the status line and tests)
};

/// "Run N seeds" under way or done.
struct MonteCarloState {
  std::unique_ptr<sim::MonteCarlo> run;
  int seeds = 0;
  std::string settings;  ///< what differs from the loaded file ("as loaded" when nothing)
  RunValues values;      ///< the settings it ran (to say when the current ones differ)
  sim::ChannelBands bands;
  double bands_at = -1;                    ///< wall time the bands were last copied
  std::optional<sim::SweepTables> tables;  ///< once finished
  std::vector<std::pair<std::string, sim::MetricStats>> headlines;
  bool written = false;  ///< tables written to --out
};

}  // namespace formsim::app
