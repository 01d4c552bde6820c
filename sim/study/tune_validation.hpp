#pragma once
/// \file `formsim tune --holdout SEEDS`: the start point and the best point run again on seeds
/// the search never saw, in every scenario of the tune. Per run (scenario and seed), the
/// objective (the weighted sum of the metrics of that run) of each; then each one's mean with
/// its 95% confidence interval (Student t), the paired difference best - start with its
/// interval, and on how many runs the best point is better.
/// Written as validation.csv and printed.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sim/core/task_pool.hpp"
#include "sim/study/metric_stats.hpp"
#include "sim/study/tune.hpp"

namespace formsim::sim {

struct TuneValidation {
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> scenarios;  ///< the scenarios' file stems
  /// Per run (scenario-major, then seed): the objective of that run (NaN: the run failed).
  std::vector<double> start, best;
  /// Per run: every constraint holds for the best point's run (true without constraints).
  std::vector<bool> best_feasible;
  MetricStats start_stats, best_stats;  ///< over the runs where both points completed
  MetricStats difference;               ///< of best - start, paired by scenario and seed
  std::size_t compared = 0;             ///< runs where both points completed
  std::size_t best_better = 0;          ///< of those, where best < start
};

/// Refuses holdout seeds that overlap the search's seeds (naming --holdout and the seeds).
void CheckHoldout(const std::vector<std::uint64_t>& holdout,
                  const std::vector<std::uint64_t>& seeds);

/// Runs the start and the best values of every scenario on every holdout seed (in parallel on
/// `pool`). Null when `stop()` turned true. Throws like RunTune when a metric is missing.
std::optional<TuneValidation> ValidateTune(const std::vector<ScenarioSource>& sources,
                                           const TuneSettings& s,
                                           const std::vector<double>& start_values,
                                           const std::vector<double>& best_values,
                                           const std::vector<std::uint64_t>& holdout,
                                           TaskPool& pool, const std::function<bool()>& stop = {});

/// validation.csv: scenario, seed, objective_start, objective_best, difference, best_feasible;
/// then summary rows (mean, ci95_lo, ci95_hi; scenario empty) for each column.
std::string TuneValidationCsv(const TuneValidation& v);

/// The lines printed: each point's mean ± CI half-width, the paired difference, the count.
std::string TuneValidationText(const TuneValidation& v);

}  // namespace formsim::sim
