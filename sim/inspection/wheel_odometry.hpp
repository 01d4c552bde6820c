#pragma once
/// \file The rear wheel encoders of the inspection robot: per-step distance increments with a
/// scale error per wheel (tyre wear, wrong wheel radius) and random noise growing with √distance.

#include "control/inspection/dead_reckoning.hpp"
#include "sim/core/rng.hpp"

namespace formsim::sim {
class YamlReader;
}  // namespace formsim::sim

namespace formsim::sim::inspection {

struct WheelOdometryDef {
  double sigma_per_sqrt_m = 0.003;  ///< random error, m per √m rolled
  double scale_error_left = 0.01;   ///< relative scale error of the left encoder
  double scale_error_right = -0.005;
  double track = 0.5;  ///< the track the estimator believes, m
};

/// Reads `odometry:` (keys as in WheelOdometryDef); noise and scale errors are tunables
/// (group "Noise/odometry").
WheelOdometryDef ReadWheelOdometry(YamlReader& odometry_map);

class WheelOdometry {
 public:
  WheelOdometry(const WheelOdometryDef& def, Rng rng) : def_(def), rng_(rng) {}
  WheelOdometryDef& def() { return def_; }
  /// Reads the encoders (cumulative true wheel distances) and returns the measured increment
  /// since the last call (the first call only latches the counters).
  control::inspection::OdometryIncrement Read(double left_distance, double right_distance);

 private:
  WheelOdometryDef def_;
  Rng rng_;
  bool latched_ = false;
  double last_left_ = 0.0, last_right_ = 0.0;
};

}  // namespace formsim::sim::inspection
