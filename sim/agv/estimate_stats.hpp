#pragma once
/// \file Accumulators of the Mecanum AGV experiment's results: error statistics of each
/// localisation source against the truth, and beacon/gate counters.

#include <algorithm>
#include <cmath>

#include "control/common/geometry.hpp"
#include "sim/core/error_stats.hpp"

namespace formsim::sim::agv {

/// How well one estimate (odometry, beacon, fused) follows the true pose, sampled every control
/// period while the AGV is tracking.
struct EstimateStats {
  ErrorStats position;  ///< |p̂ − p|, m
  ErrorStats heading;   ///< wrap(θ̂ − θ), rad
  double final_position_error = 0.0;
  long jumps = 0;  ///< control periods in which the error vector changed by > jump_threshold
  bool has_prev = false;
  Vec2 prev_error;
  void Add(const Pose2& estimate, const Pose2& truth, double heading_error, double jump_threshold) {
    const Vec2 e = estimate.p() - truth.p();
    position.Add(e.Norm());
    heading.Add(heading_error);
    final_position_error = e.Norm();
    if (has_prev && (e - prev_error).Norm() > jump_threshold) ++jumps;
    prev_error = e;
    has_prev = true;
  }
};

/// Beacon samples and what the filter's gate did with them (the simulator knows which samples
/// were interference outliers, so it can score the gate).
struct BeaconCounts {
  long samples = 0;
  long dropouts = 0;
  long outliers = 0;  ///< valid samples that were outliers
  long accepted = 0;
  long rejected = 0;
  long rejected_outliers = 0;  ///< rejected and truly outliers
  long accepted_outliers = 0;  ///< outliers that got through
  long reinitialisations = 0;
  long faults = 0;
  double nis_sum = 0.0;  ///< over accepted samples
};

}  // namespace formsim::sim::agv
