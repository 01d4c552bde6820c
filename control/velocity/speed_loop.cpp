#include "control/velocity/speed_loop.hpp"

namespace formsim::control::velocity {

WheelSpeedLoop::WheelSpeedLoop(const SpeedLoopDef& def) {
  SetDef(def);
}

void WheelSpeedLoop::SetDef(const SpeedLoopDef& def) {
  def_ = def;
  left_.SetGains(def.gains);
  right_.SetGains(def.gains);
}

void WheelSpeedLoop::Reset() {
  left_.Reset();
  right_.Reset();
}

WheelSpeedLoop::Output WheelSpeedLoop::Step(double v_cmd, double omega_cmd, double v_est,
                                            double omega_est) {
  Output out;
  out.target = ToWheelSpeeds(v_cmd, omega_cmd, def_.track_width);
  out.estimate = ToWheelSpeeds(v_est, omega_est, def_.track_width);
  out.error = {out.target.left - out.estimate.left, out.target.right - out.estimate.right};
  out.u_left = left_.Step(out.error.left);
  out.u_right = right_.Step(out.error.right);
  return out;
}

void WheelSpeedLoop::CompensateEstimateJump(double dv, double domega) {
  // The estimate rose by Δ, so the error fell by Δ: move the past errors by -Δ as well.
  const WheelSpeeds d = ToWheelSpeeds(dv, domega, def_.track_width);
  left_.ShiftErrorHistory(-d.left);
  right_.ShiftErrorHistory(-d.right);
}

}  // namespace formsim::control::velocity
