#pragma once
/// \file `formsim tune`: derivative-free minimisation with NLopt (local, global, or a global
/// stage then a local polish: sim/study/tune_plan.hpp) of a metric, or a weighted sum of
/// metrics, averaged over a set of seeds, over chosen real tunables within bounds, subject to
/// constraints `METRIC<=VALUE` / `METRIC>=VALUE` on the same averages. The optimiser works in
/// coordinates scaled to [0, 1] per tunable (logarithmic for tunables with a log slider),
/// starts from the scenario's values, and every evaluation runs the seeds in parallel on a
/// TaskPool. The function values depend only on the arguments, and the methods that draw random
/// numbers draw them from `search_seed`, so the same call gives the same history.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "sim/core/metrics.hpp"
#include "sim/core/param_table.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/core/task_pool.hpp"
#include "sim/study/tune_plan.hpp"

namespace formsim::sim {

/// One term of --metric: weight * (metric averaged over the seeds).
struct MetricTerm {
  double weight = 1.0;
  std::string path;  ///< dotted path under summary.json's `results`
};

/// Parses "PATH", "W*PATH" and sums of them with '+' ("a.b + 10*c.d", weights may be negative:
/// "-0.5*x.y"). Throws std::runtime_error naming --metric.
std::vector<MetricTerm> ParseMetricExpr(const std::string& expr);

/// One tuned tunable and its search interval. The optimiser sees every key as a coordinate in
/// [0, 1]: a real key maps it linearly (or logarithmically) onto [lo, hi]; an integer key rounds
/// that to a whole number; a choice key (an enum, a flag) splits [0, 1] into equal slots, one
/// per choice. Integer and choice keys are searched by a global stage only, then held at the
/// best value for the local polish.
struct TuneParam {
  enum class Kind { kReal, kInteger, kChoice };
  std::string key;
  Kind kind = Kind::kReal;
  double lo = 0, hi = 1;  ///< kChoice: 0 ... choices - 1
  bool log_scale = false;  ///< searched in log space (the tunable's slider is logarithmic)
  double start = 0;        ///< the scenario's value, clamped into [lo, hi] (kChoice: its index)
  std::vector<std::string> choices;  ///< kChoice: the YAML strings, in order

  bool discrete() const { return kind != Kind::kReal; }
  /// The value at coordinate u in [0, 1] (clamped), and back (a choice: its slot's middle).
  double FromUnit(double u) const;
  double ToUnit(double value) const;
  /// The value as YAML text: a number, or the choice's name.
  std::string Text(double value) const;
};

/// Parses `KEY` or `KEY:LO:HI` against the scenario's tunables: a real or integer tunable
/// (default bounds its declared slider range; explicit bounds must be valid values with LO < HI,
/// whole numbers for an integer), or a choice or flag (`KEY` alone: every choice). Throws
/// ScenarioError naming the --param argument.
TuneParam ParseTuneParam(const std::string& arg, const ParamTable& params);

/// One `--constraint`: the mean over the seeds of a result metric, at most or at least a bound.
struct TuneConstraint {
  std::string path;      ///< dotted path under summary.json's `results`
  bool at_most = true;   ///< PATH<=BOUND (else PATH>=BOUND)
  double bound = 0;
  std::string Text() const;  ///< "PATH<=BOUND"
  /// How far `mean` is on the wrong side of the bound (> 0: violated; NaN counts as violated).
  double Violation(double mean) const;
};

/// Parses "PATH<=VALUE" or "PATH>=VALUE" (spaces allowed). Throws std::runtime_error naming
/// --constraint.
TuneConstraint ParseTuneConstraint(const std::string& arg);

/// `--over`: how the objective and the constraints fold the runs of an evaluation (every
/// scenario times every seed) into one number. mean (default), max (the worst case), or
/// quantile:Q (0 < Q < 1, type 7). For a `>=` constraint the fold is mirrored (max: the smallest
/// value), so max is the worst case for every constraint.
struct TuneOver {
  enum class Kind { kMean, kMax, kQuantile } kind = Kind::kMean;
  double q = 0.5;
  std::string Text() const;
  /// The fold of `values` (not empty; finite).
  double Of(std::vector<double> values) const;
};

/// Parses `mean`, `max` or `quantile:Q`. Throws std::runtime_error naming --over.
TuneOver ParseTuneOver(const std::string& text);

struct TuneSettings {
  std::vector<TuneParam> params;
  std::vector<MetricTerm> objective;
  std::vector<TuneConstraint> constraints;
  std::vector<std::uint64_t> seeds;
  std::vector<Override> sets;  ///< --set overrides applied to every run
  int budget = 60;             ///< evaluations at most (each runs every seed)
  /// `--method`: one method or GLOBAL+LOCAL (sim/study/tune_plan.hpp).
  std::string algorithm = "bobyqa";
  std::uint64_t search_seed = 1;  ///< NLopt's random stream (crs2, mlsl, isres)
  TuneOver over;                  ///< the fold of the runs of an evaluation
};

/// Checks that every scenario after the first has each tuned key as a tunable of the kind it
/// has in the first (the bounds are the first scenario's): CheckScenarioKeys. Throws
/// ScenarioError naming --scenario and the key.
void CheckTunedKeys(const std::vector<ScenarioSource>& sources, const TuneSettings& s);

/// One evaluation: a point, the mean of each term's metric over the runs (every scenario times
/// every seed), the objective (the `--over` fold of each run's weighted sum) and each
/// constraint's fold.
struct TuneEvaluation {
  std::size_t index = 0;                 ///< 1-based, in the order NLopt asked
  std::size_t stage = 0;                 ///< 0-based stage of the plan that asked for it
  std::vector<double> values;            ///< per tunable
  std::vector<double> term_means;        ///< per term (NaN when a run failed)
  std::vector<double> constraint_means;  ///< per constraint, its `--over` fold (NaN: a run failed)
  double objective = 0;                  ///< +inf when a run failed (message says which)
  double violation = 0;  ///< the largest constraint violation, relative to its bound; 0: feasible
  std::size_t failed_runs = 0;
  std::string message;
  bool failed() const { return failed_runs > 0 || !message.empty(); }
  /// Ran, and every constraint holds.
  bool feasible() const { return !failed() && !(violation > 0); }
};

struct TuneResult {
  std::vector<TuneEvaluation> history;
  /// Index into history of the lowest objective among the feasible evaluations (first of
  /// equals); without a feasible one, the evaluation closest to feasible.
  std::size_t best = 0;
  std::string stop_reason;  ///< why NLopt stopped ("budget used", "converged (x tolerance)", ...)
  std::vector<TuneStage> plan;  ///< the stages run and their budgets
  /// What the kind declared about the objective's and the constraints' metrics (label with
  /// markup, unit, direction), from the first completed run; for the figures' labels.
  std::vector<std::pair<std::string, MetricInfo>> info;
  bool has_best() const { return !history.empty() && history[best].feasible(); }
};

/// Every override of an evaluation at `values`: --set, then the tuned values (no seed).
std::vector<Override> TuneOverrides(const TuneSettings& s, const std::vector<double>& values);

/// Runs the optimisation. `progress(evaluation, best so far)` after each evaluation; when
/// `stop()` turns true the optimisation ends after the current evaluation's runs are
/// abandoned (that evaluation is not recorded). Throws std::runtime_error before the search
/// when --method or --budget is refused (PlanTune), and at evaluation 1 (the scenario's own
/// values, before the optimiser starts) when a term or a constraint names a metric the runs do
/// not have (with the names that exist) or a setting rather than a result.
/// `recorded`: evaluations of an earlier run of the same tune (--resume), replayed in order
/// instead of run (progress is called for them too); a point that differs from the record
/// throws.
TuneResult RunTune(
    const std::vector<ScenarioSource>& sources, const TuneSettings& settings, TaskPool& pool,
    const std::function<void(const TuneEvaluation&, const TuneEvaluation&)>& progress = {},
    const std::function<bool()>& stop = {}, const std::vector<TuneEvaluation>& recorded = {});
/// One scenario.
TuneResult RunTune(
    const ScenarioSource& source, const TuneSettings& settings, TaskPool& pool,
    const std::function<void(const TuneEvaluation&, const TuneEvaluation&)>& progress = {},
    const std::function<bool()>& stop = {});

/// history.csv and --resume: sim/study/tune_history.hpp.

}  // namespace formsim::sim
