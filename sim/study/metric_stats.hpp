#pragma once
/// \file Statistics of one metric over the runs of one sweep point (or one reproduction cell):
/// what aggregate.csv writes per metric and what sweep figures draw as bands.
///   n, mean, std (sample, n - 1), min, max
///   median, q05, q95   quantiles by linear interpolation between order statistics (Hyndman and
///                      Fan's type 7, the default of R and NumPy)
///   sem                standard error of the mean, std / sqrt(n)
///   ci95_lo, ci95_hi   95% confidence interval of the mean, mean ∓ t(0.975, n - 1) · sem
///                      (Student t), NaN when n < 2

#include <cstddef>
#include <limits>
#include <vector>

namespace formsim::sim {

/// One metric over the completed runs of one point (non-finite values left out).
struct MetricStats {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::size_t n = 0;
  double mean = kNaN, std = kNaN, min = kNaN, max = kNaN;  ///< std: sample (n - 1); NaN when n < 2
  double median = kNaN, q05 = kNaN, q95 = kNaN;
  double sem = kNaN, ci95_lo = kNaN, ci95_hi = kNaN;  ///< NaN when n < 2
  /// Half the width of the 95% confidence interval (NaN when n < 2).
  double ci95_half() const { return 0.5 * (ci95_hi - ci95_lo); }
};

/// The statistics of `values` (all of them; the caller leaves out what does not count).
MetricStats StatsOf(const std::vector<double>& values);

/// The p-quantile (0 <= p <= 1) of `sorted` (ascending, not empty), type 7.
double Quantile(const std::vector<double>& sorted, double p);

/// The 0.975 quantile of Student's t distribution with `dof` >= 1 degrees of freedom: exact
/// (to 6 decimals) from a table up to 30, a Cornish-Fisher expansion beyond (error < 1e-6).
double StudentT975(std::size_t dof);

}  // namespace formsim::sim
