#pragma once
/// \file The unicycle drive model (paper 000, eq. 1): commands (v, ω), two modes.
///  - kIdeal: the body follows the commanded (v, ω) exactly unless it collides (velocities set
///    before each step; contacts still act).
///  - kTraction: longitudinal force, lateral no-slip force and yaw torque needed to reach the
///    command in one step, limited together by the ground's friction μ·m·g (friction circle), so
///    the robot slides when asked for more than the ground gives.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sim/core/world.hpp"

namespace formsim::sim {

struct UnicycleDriveDef {
  enum class Mode { kIdeal, kTraction } mode = Mode::kIdeal;
  double v_max = 6.0;                                          ///< |v| limit, m/s
  double omega_max = 12.0;                                     ///< |ω| limit, rad/s
  double accel_max = std::numeric_limits<double>::infinity();  ///< |dv/dt| limit, m/s² (motors)
  double track_half_width = 0.06;  ///< wheel half-track for the yaw-torque friction limit, m
};
inline UnicycleDriveDef DefaultUnicycleDriveDef() {
  return UnicycleDriveDef{};
}

class UnicycleDrive : public DriveModel {
 public:
  explicit UnicycleDrive(const UnicycleDriveDef& def) : def_(def) {}
  /// The command for the next steps (clamped to the limits; the clamping is reported). Inline:
  /// a caller reading the command back right away gets it from registers (loading it from the
  /// two separate stores of an out-of-line call stalled store forwarding).
  void SetCommand(double v, double omega) {
    if (!std::isfinite(v)) v = 0.0;
    if (!std::isfinite(omega)) omega = 0.0;
    v_cmd_ = std::clamp(v, -def_.v_max, def_.v_max);
    w_cmd_ = std::clamp(omega, -def_.omega_max, def_.omega_max);
    saturated_v_ = v_cmd_ != v;
    saturated_omega_ = w_cmd_ != omega;
  }
  void Apply(Robot& robot, World& world, double dt) override;
  bool saturated() const override { return saturated_v_ || saturated_omega_ || slipping_; }
  bool saturated_v() const { return saturated_v_; }
  bool saturated_omega() const { return saturated_omega_; }
  /// Traction mode: the friction limit was reached in the last step (the robot slid).
  bool slipping() const { return slipping_; }
  double v_command() const { return v_cmd_; }      ///< after clamping
  double omega_command() const { return w_cmd_; }  ///< after clamping
  UnicycleDriveDef& def() { return def_; }

 private:
  UnicycleDriveDef def_;
  double v_cmd_ = 0.0, w_cmd_ = 0.0;
  bool saturated_v_ = false, saturated_omega_ = false, slipping_ = false;
};

/// Reads `drive: {mode: ideal|traction, v_max, omega_max, accel_max, track_half_width}`; mode,
/// v_max and omega_max are tunables shown in GUI group `group`.
UnicycleDriveDef ReadUnicycleDrive(class YamlReader& drive_map, const std::string& group);

}  // namespace formsim::sim
