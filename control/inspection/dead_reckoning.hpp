#pragma once
/// \file Dead reckoning of the inspection robot (paper eq. 1), heading from the Y axis:
///   x(k+1) = x(k) + ΔS(k) sin θ(k),   y(k+1) = y(k) + ΔS(k) cos θ(k).
/// ΔS and the heading increment come from the rear wheel encoders (differential odometry).

#include "control/common/geometry.hpp"

namespace formsim::control::inspection {

/// One odometry increment from the two rear wheel encoders.
struct OdometryIncrement {
  double ds = 0.0;      ///< distance travelled by the axle centre, m
  double dtheta = 0.0;  ///< heading change, rad, paper convention (clockwise positive)
};

/// Differential odometry: ΔS = (ΔS_L + ΔS_R)/2, Δθ = (ΔS_L − ΔS_R)/track (a faster left wheel
/// turns the robot clockwise, i.e. increases the paper heading).
OdometryIncrement DifferentialOdometry(double ds_left, double ds_right, double track);

/// A pose in the paper convention (x, y in metres, θ from +Y towards +X).
struct PaperPose {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  Vec2 p() const { return {x, y}; }
};

/// Eq. 1: advances (x, y) by ΔS along heading θ (the heading at the start of the step).
PaperPose DeadReckonStep(const PaperPose& pose, double ds, double theta);

/// A pure dead-reckoning integrator (eq. 1 with the encoder heading), never corrected: the
/// baseline that drifts.
class DeadReckoning {
 public:
  void Reset(const PaperPose& pose) { pose_ = pose; }
  /// Moves along the current heading by inc.ds, then turns by inc.dtheta.
  void Step(const OdometryIncrement& inc);
  const PaperPose& pose() const { return pose_; }

 private:
  PaperPose pose_;
};

}  // namespace formsim::control::inspection
