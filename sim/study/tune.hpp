#pragma once
/// \file `formsim tune`: derivative-free minimisation (NLopt's BOBYQA, Nelder-Mead or COBYLA)
/// of a metric, or a weighted sum of metrics, averaged over a set of seeds, over chosen real
/// tunables within bounds. The optimiser works in coordinates scaled to [0, 1] per tunable
/// (logarithmic for tunables with a log slider), starts from the scenario's values, and every
/// evaluation runs the seeds in parallel on a TaskPool. The function values depend only on the
/// arguments and NLopt's algorithms are deterministic, so the same call gives the same history.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sim/core/param_table.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/core/task_pool.hpp"

namespace formsim::sim {

/// One term of --metric: weight * (metric averaged over the seeds).
struct MetricTerm {
  double weight = 1.0;
  std::string path;  ///< dotted path under summary.json's `results`
};

/// Parses "PATH", "W*PATH" and sums of them with '+' ("a.b + 10*c.d", weights may be negative:
/// "-0.5*x.y"). Throws std::runtime_error naming --metric.
std::vector<MetricTerm> ParseMetricExpr(const std::string& expr);

/// One tuned tunable and its search interval.
struct TuneParam {
  std::string key;
  double lo = 0, hi = 1;
  bool log_scale = false;  ///< searched in log space (the tunable's slider is logarithmic)
  double start = 0;        ///< the scenario's value, clamped into [lo, hi]
};

/// Parses `KEY` or `KEY:LO:HI` against the scenario's tunables: a real tunable; default bounds
/// its declared slider range; explicit bounds must be valid values with LO < HI. Throws
/// ScenarioError naming the --param argument.
TuneParam ParseTuneParam(const std::string& arg, const ParamTable& params);

/// The algorithms offered: "bobyqa" (default), "neldermead", "cobyla".
std::vector<std::string> TuneAlgorithms();

struct TuneSettings {
  std::vector<TuneParam> params;
  std::vector<MetricTerm> objective;
  std::vector<std::uint64_t> seeds;
  std::vector<Override> sets;  ///< --set overrides applied to every run
  int budget = 60;             ///< evaluations at most (each runs every seed)
  std::string algorithm = "bobyqa";
};

/// One evaluation: a point, the mean of each term's metric over the seeds and the objective.
struct TuneEvaluation {
  std::size_t index = 0;           ///< 1-based, in the order NLopt asked
  std::vector<double> values;      ///< per tunable
  std::vector<double> term_means;  ///< per term (NaN when a run failed)
  double objective = 0;            ///< +inf when a run failed (message says which)
  std::size_t failed_runs = 0;
  std::string message;
  bool failed() const { return failed_runs > 0; }
};

struct TuneResult {
  std::vector<TuneEvaluation> history;
  std::size_t best = 0;     ///< index into history of the lowest objective (first of equals)
  std::string stop_reason;  ///< why NLopt stopped ("budget used", "converged (x tolerance)", ...)
  bool has_best() const { return !history.empty() && !history[best].failed(); }
};

/// Every override of an evaluation at `values`: --set, then the tuned values (no seed).
std::vector<Override> TuneOverrides(const TuneSettings& s, const std::vector<double>& values);

/// Runs the optimisation. `progress(evaluation, best so far)` after each evaluation; when
/// `stop()` turns true the optimisation ends after the current evaluation's runs are
/// abandoned (that evaluation is not recorded). Throws std::runtime_error when a term names a
/// metric the runs do not have (after the first evaluation, with the names that exist).
TuneResult RunTune(
    const ScenarioSource& source, const TuneSettings& settings, TaskPool& pool,
    const std::function<void(const TuneEvaluation&, const TuneEvaluation&)>& progress = {},
    const std::function<bool()>& stop = {});

/// history.csv: eval, the tuned keys, objective, each term's mean, failed_runs, best_so_far,
/// message; numbers as shortest round-trip text.
std::string TuneHistoryCsv(const TuneSettings& s, const TuneResult& r);

}  // namespace formsim::sim
