#pragma once
/// \file Running statistics of an error signal, shared by every experiment's metrics (one
/// definition: experiments link into one binary, so per-area copies would clash).

#include <algorithm>
#include <cmath>

namespace formsim::sim {

/// Count, mean, RMS and largest magnitude of the samples added.
struct ErrorStats {
  long n = 0;
  double sum = 0.0;
  double sum_sq = 0.0;
  double max_abs = 0.0;
  void Add(double e) {
    ++n;
    sum += e;
    sum_sq += e * e;
    max_abs = std::max(max_abs, std::abs(e));
  }
  double rms() const { return n ? std::sqrt(sum_sq / static_cast<double>(n)) : 0.0; }
  double mean() const { return n ? sum / static_cast<double>(n) : 0.0; }
};

/// Largest magnitude over a whole run, and full statistics after a settle time.
struct SettledErrorStats {
  double max_abs = 0.0;  ///< over the whole run
  ErrorStats settled;    ///< after the settle time
  void Add(double e, bool is_settled) {
    max_abs = std::max(max_abs, std::abs(e));
    if (is_settled) settled.Add(e);
  }
  double max_abs_settled() const { return settled.max_abs; }
  double rmse_settled() const { return settled.rms(); }
};

}  // namespace formsim::sim
