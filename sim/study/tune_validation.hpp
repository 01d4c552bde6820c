#pragma once
/// \file `formsim tune --holdout SEEDS`: the start point and the best point run again on seeds
/// the search never saw. Per seed, the objective (the weighted sum of the metrics of that run)
/// of each; then each one's mean with its 95% confidence interval (Student t), the paired
/// difference best - start with its interval, and on how many seeds the best point is better.
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
  std::vector<double> start, best;  ///< per seed: the objective of that run (NaN: the run failed)
  /// Per seed: every constraint holds for the best point's run (true without constraints).
  std::vector<bool> best_feasible;
  MetricStats start_stats, best_stats;  ///< over the seeds where both runs completed
  MetricStats difference;               ///< of best - start, paired by seed
  std::size_t compared = 0;             ///< seeds where both runs completed
  std::size_t best_better = 0;          ///< of those, where best < start
};

/// Refuses holdout seeds that overlap the search's seeds (naming --holdout and the seeds).
void CheckHoldout(const std::vector<std::uint64_t>& holdout,
                  const std::vector<std::uint64_t>& seeds);

/// Runs the start and the best values on every holdout seed (in parallel on `pool`). Null when
/// `stop()` turned true. Throws like RunTune when a metric is missing.
std::optional<TuneValidation> ValidateTune(const ScenarioSource& source, const TuneSettings& s,
                                           const std::vector<double>& start_values,
                                           const std::vector<double>& best_values,
                                           const std::vector<std::uint64_t>& holdout,
                                           TaskPool& pool, const std::function<bool()>& stop = {});

/// validation.csv: seed, objective_start, objective_best, difference, best_feasible; then
/// summary rows (mean, ci95_lo, ci95_hi) for each column.
std::string TuneValidationCsv(const TuneValidation& v);

/// The lines printed: each point's mean ± CI half-width, the paired difference, the count.
std::string TuneValidationText(const TuneValidation& v);

}  // namespace formsim::sim
