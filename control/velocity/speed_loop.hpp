#pragma once
/// \file The paper's speed control (section 2): a body speed estimate (v, ω) is turned into
/// wheel speed estimates with the track width d (left v - ω d/2, right v + ω d/2), the
/// commanded (v_t, ω_t) into wheel targets the same way, and one incremental PID per wheel
/// motor outputs its voltage. When the speed estimate jumps because the estimator updated (or
/// because the feedback source was switched), the jump Δv_s is compensated: the PIDs' error
/// history is shifted by it so that the proportional and derivative increments do not kick.

#include "control/common/pid.hpp"

namespace formsim::control::velocity {

/// Speeds of the left and right wheel contact points, m/s.
struct WheelSpeeds {
  double left = 0.0;
  double right = 0.0;
};

/// Differential-drive kinematics: body (v, ω) to wheel speeds and back.
inline WheelSpeeds ToWheelSpeeds(double v, double omega, double track_width) {
  return {v - 0.5 * omega * track_width, v + 0.5 * omega * track_width};
}
inline double BodySpeed(const WheelSpeeds& w) {
  return 0.5 * (w.left + w.right);
}
inline double BodyYawRate(const WheelSpeeds& w, double track_width) {
  return (w.right - w.left) / track_width;
}

struct SpeedLoopDef {
  double track_width = 0.3;  ///< d, m
  PidGains gains;            ///< per-sample gains, output limits = motor voltage limits
};

class WheelSpeedLoop {
 public:
  explicit WheelSpeedLoop(const SpeedLoopDef& def = SpeedLoopDef{});
  void SetDef(const SpeedLoopDef& def);
  const SpeedLoopDef& def() const { return def_; }
  void Reset();

  /// What one control step computed.
  struct Output {
    WheelSpeeds target, estimate, error;
    double u_left = 0.0, u_right = 0.0;  ///< motor voltages
  };
  /// One control step from the commanded and estimated body speeds.
  Output Step(double v_cmd, double omega_cmd, double v_est, double omega_est);
  /// The body-speed estimate just jumped by (dv, dω) without the robot moving differently:
  /// shift the error history so the next increment ignores the jump (paper's Δv_s compensation).
  void CompensateEstimateJump(double dv, double domega);

 private:
  SpeedLoopDef def_;
  IncrementalPid left_, right_;
};

}  // namespace formsim::control::velocity
