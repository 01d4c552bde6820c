#include "sim/study/metric_stats.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace formsim::sim {

double Quantile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return MetricStats::kNaN;
  const double h = p * static_cast<double>(sorted.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

double StudentT975(std::size_t dof) {
  // t(0.975, ν) for ν = 1 ... 30 (any statistics table; checked against R's qt in the tests).
  static constexpr double kTable[30] = {
      12.706205, 4.302653, 3.182446, 2.776445, 2.570582, 2.446912, 2.364624, 2.306004,
      2.262157,  2.228139, 2.200985, 2.178813, 2.160369, 2.144787, 2.131450, 2.119905,
      2.109816,  2.100922, 2.093024, 2.085963, 2.079614, 2.073873, 2.068658, 2.063899,
      2.059539,  2.055529, 2.051831, 2.048407, 2.045230, 2.042272};
  if (dof == 0) throw std::invalid_argument("StudentT975: needs at least 1 degree of freedom");
  if (dof <= 30) return kTable[dof - 1];
  // Cornish-Fisher expansion of t around the normal quantile z (Abramowitz and Stegun 26.7.5).
  const double z = 1.959963984540054, v = static_cast<double>(dof);
  const double z2 = z * z, z3 = z2 * z, z5 = z3 * z2, z7 = z5 * z2, z9 = z7 * z2;
  return z + (z3 + z) / (4 * v) + (5 * z5 + 16 * z3 + 3 * z) / (96 * v * v) +
         (3 * z7 + 19 * z5 + 17 * z3 - 15 * z) / (384 * v * v * v) +
         (79 * z9 + 776 * z7 + 1482 * z5 - 1920 * z3 - 945 * z) / (92160 * v * v * v * v);
}

MetricStats StatsOf(const std::vector<double>& v) {
  MetricStats s;
  s.n = v.size();
  if (v.empty()) return s;
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  double sum = 0;
  for (double x : v) sum += x;  // in the given order: the same bytes as before for the mean
  s.min = sorted.front();
  s.max = sorted.back();
  s.mean = sum / static_cast<double>(v.size());
  s.median = Quantile(sorted, 0.5);
  s.q05 = Quantile(sorted, 0.05);
  s.q95 = Quantile(sorted, 0.95);
  if (v.size() >= 2) {
    double ss = 0;
    for (double x : v) ss += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(ss / static_cast<double>(v.size() - 1));
    s.sem = s.std / std::sqrt(static_cast<double>(v.size()));
    const double half = StudentT975(v.size() - 1) * s.sem;
    s.ci95_lo = s.mean - half;
    s.ci95_hi = s.mean + half;
  }
  return s;
}

}  // namespace formsim::sim
