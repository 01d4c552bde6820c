#pragma once
/// \file Dead reckoning: integrates a body twist into a world pose (paper 002, eq. 3-4 and 6).

#include "control/common/geometry.hpp"
#include "control/agv/kinematics.hpp"

namespace formsim::control::agv {

/// World-frame velocity (ẋ, ẏ, θ̇) of a body moving with `twist` at heading `theta`:
/// [ẋ ẏ]ᵀ = R(θ) [vx vy]ᵀ, θ̇ = ω (eq. 3-4).
struct WorldVelocity {
  double x_dot = 0.0;
  double y_dot = 0.0;
  double theta_dot = 0.0;
};
WorldVelocity ToWorld(const BodyTwist& twist, double theta);

/// Advances `pose` by a constant body twist over dt, rotating with the mid-step heading
/// (second order in ω dt). The heading stays wrapped to (-π, π].
Pose2 IntegrateTwist(const Pose2& pose, const BodyTwist& twist, double dt);

/// A running dead-reckoning estimate (odometry only, never corrected).
class DeadReckoning {
 public:
  void Reset(const Pose2& pose) { pose_ = pose; }
  void Step(const BodyTwist& twist, double dt) { pose_ = IntegrateTwist(pose_, twist, dt); }
  const Pose2& pose() const { return pose_; }

 private:
  Pose2 pose_;
};

}  // namespace formsim::control::agv
