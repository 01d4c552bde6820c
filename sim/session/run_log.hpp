#pragma once
/// \file The recipe of one run: the overrides it started with and every change applied during it
/// (live edits, drags, actions) with the step it took effect at. Runs are deterministic, so a
/// run log replayed from step 0 rebuilds the run bit for bit: a pinned copy of a run, the world
/// at an earlier time (the GUI's timeline), the exact starting state of a branch, a history row
/// pinned later. A replay costs what the steps cost (no state is copied or saved).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/scenario/scenario.hpp"

namespace formsim::sim {

/// One change applied between two steps of a run.
struct RunChange {
  enum class Kind { kEdits, kMove, kAction };
  Kind kind = Kind::kEdits;
  long step = 0;                ///< applied before stepping from `step` to `step + 1`
  std::vector<Override> edits;  ///< kEdits: the live edits applied together (one Retune)
  std::string name;             ///< kMove: robot or obstacle; kAction: the action id
  double x = 0, y = 0;          ///< kMove: where it was dragged to
  std::string origin;           ///< kAction: "GUI action", "script action"
};

/// How one run came about: what it started with and what changed while it ran.
struct RunLog {
  std::vector<Override> base;      ///< ParseScenario's overrides at step 0 (--set, seed, edits)
  std::vector<RunChange> changes;  ///< in the order they were applied

  /// The log of a run branched at `step`: the changes applied before it (step < `step`).
  RunLog Before(long step) const;
  /// The live edits applied during the run, in order, each with its step.
  std::vector<Override> Edits() const;
};

/// Applies `change` to `exp` between two steps, as the session does: edits retune the
/// experiment with `parsed` (the scenario read with the run's base, every earlier edit and
/// these) and enter its provenance; a drag moves a body; an action runs. Returns "" or why it
/// failed (nothing changed then).
std::string ApplyRunChange(Experiment& exp, const RunChange& change, const ParsedScenario* parsed);

/// Rebuilds a run from its log: built at step 0, then stepped with each change applied at its
/// step. Same source, same log: the same run, bit for bit.
class RunReplay {
 public:
  /// Builds the run at step 0 (`setup`, when given, is called on the new experiment first, as
  /// the session's run setup is). Throws ScenarioError.
  RunReplay(ScenarioSource source, RunLog log, const std::function<void(Experiment&)>& setup = {});

  /// Steps towards `step`, applying every change due on the way. With `changes_at_step` the
  /// changes of `step` itself are applied too (the state the live run shows after them);
  /// without, the state is the one a branch at `step` starts from. Returns true once there (or
  /// once the run has ended), false when `stop()` turned true first (call again to go on).
  bool AdvanceTo(long step, bool changes_at_step, const std::function<bool()>& stop = {});

  Experiment& exp() { return *exp_; }
  const Experiment& exp() const { return *exp_; }
  long step() const { return exp_->steps(); }
  /// The scenario as the run now uses it (base and the edits applied so far).
  const ParsedScenario& parsed() const { return parsed_; }
  const ScenarioSource& source() const { return source_; }
  const RunLog& log() const { return log_; }
  /// Hands the experiment over (the replay is unusable afterwards).
  std::unique_ptr<Experiment> Release() { return std::move(exp_); }

 private:
  void ApplyDue(long step);  ///< applies the changes of `step` not applied yet

  ScenarioSource source_;
  RunLog log_;
  ParsedScenario parsed_;
  std::unique_ptr<Experiment> exp_;
  std::vector<Override> edits_so_far_;  ///< base, then each applied edit
  std::size_t next_ = 0;                ///< first change not applied yet
};

}  // namespace formsim::sim
