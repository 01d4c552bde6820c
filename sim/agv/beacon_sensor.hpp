#pragma once
/// \file A ceiling infrared beacon localiser in the style of Hagisonic's StarGazer: an absolute
/// pose [x y θ] every `period` seconds with Gaussian noise, interference outliers (a wrong
/// reading displaced by `outlier_size`·U(0.5, 1.5) in a random direction, heading off by up to
/// ±outlier_heading) and dropouts (no reading). Every sample draws the same random numbers
/// whatever happens, so changing one rate does not reshuffle the others.

#include "control/common/geometry.hpp"
#include "sim/core/rng.hpp"

namespace formsim::sim::agv {

struct BeaconDef {
  double period = 0.1;               ///< Ts, s
  double sigma_xy = 0.01;            ///< m
  double sigma_theta = 0.01;         ///< rad
  double outlier_probability = 0.0;  ///< per sample
  double outlier_size = 0.5;         ///< m (typical displacement of a wrong reading)
  double outlier_heading = 0.5;      ///< rad (max heading error of a wrong reading)
  double dropout_probability = 0.0;  ///< per sample
};

/// One beacon sample.
struct BeaconFix {
  double t = 0.0;
  Pose2 pose;            ///< the reading (θ wrapped)
  bool valid = false;    ///< false: dropout, no reading
  bool outlier = false;  ///< ground truth: the reading is an interference outlier
};

class BeaconSensor {
 public:
  BeaconSensor(const BeaconDef& def, Rng rng) : def_(def), rng_(rng) {}
  void SetDef(const BeaconDef& def) { def_ = def; }
  const BeaconDef& def() const { return def_; }
  /// True when a sample is due at time t (first at t = 0, then every period).
  bool Due(double t) const { return t >= next_time_ - 1e-9; }
  /// Samples the true pose at time t and schedules the next sample.
  BeaconFix Sample(double t, const Pose2& truth);

 private:
  BeaconDef def_;
  Rng rng_;
  double next_time_ = 0.0;
};

}  // namespace formsim::sim::agv
