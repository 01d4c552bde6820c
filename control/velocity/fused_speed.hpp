#pragma once
/// \file The paper's speed-estimation strategy between optimiser updates (section 2.2): when
/// the window was just optimised, the newest keyframe's velocity (rotated into the body frame)
/// is the estimate; until the next update, the odometry reading corrected by the last
/// estimated odometry biases is: v_e = ṽ_O - b̂_v, ω_e = ψ̃_O - b̂_ψ.

namespace formsim::control::velocity {

/// Body forward speed and yaw rate.
struct BodyTwist {
  double v = 0.0;
  double omega = 0.0;
};

class FusedSpeedEstimate {
 public:
  /// An optimiser update: newest keyframe's forward speed and the odometry biases.
  void OnUpdate(double window_speed, double speed_bias, double yaw_rate_bias) {
    window_speed_ = window_speed;
    bv_ = speed_bias;
    bw_ = yaw_rate_bias;
    fresh_ = true;
  }
  /// The estimate for this control step from the current odometry reading. The first call after
  /// an update returns the window's speed; later calls the bias-corrected odometry.
  BodyTwist Estimate(double odo_speed, double odo_yaw_rate) {
    BodyTwist t{odo_speed - bv_, odo_yaw_rate - bw_};
    if (fresh_) t.v = window_speed_;
    fresh_ = false;
    return t;
  }
  /// The estimate the next call would give, without consuming the update.
  BodyTwist Peek(double odo_speed, double odo_yaw_rate) const {
    return {fresh_ ? window_speed_ : odo_speed - bv_, odo_yaw_rate - bw_};
  }
  double speed_bias() const { return bv_; }
  double yaw_rate_bias() const { return bw_; }

 private:
  double window_speed_ = 0.0, bv_ = 0.0, bw_ = 0.0;
  bool fresh_ = false;
};

}  // namespace formsim::control::velocity
