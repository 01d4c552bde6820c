#pragma once
/// \file Wheel-level Mecanum drive in Box2D (paper 002's platform).
///
/// Each wheel has a speed-controlled motor (first-order lag, acceleration and speed limits). The
/// floor acts on a wheel only along the axis a_i of its contact roller (see
/// control/agv/kinematics.hpp for the wheel order and sign convention); the roller turns
/// freely across it. The slip velocity of wheel i along a_i is
///   σ_i = a_i · (v + ω × p_i) − r_i ω_i / √2      (r_i: the wheel's TRUE radius)
/// and the floor pushes back with a viscous contact force f_i = −c σ_i⁺ (c: `slip_damping`,
/// σ_i⁺ the slip at the end of the step, solved implicitly so any c is stable), limited by
/// friction |f_i| ≤ μ(p_i) N_i with N_i = m g / 4 and μ the floor under that wheel (patches).
/// The coupled 4×4 problem (I/c + dt·D M⁻¹ Dᵀ) f = −σ with the friction box is solved by
/// projected Gauss-Seidel. When a wheel is at its friction limit it slides: its encoder keeps
/// counting wheel rotation that the body does not follow. Wheels whose radii disagree fight each
/// other through small internal forces, as on a real platform.

#include <array>

#include "control/agv/kinematics.hpp"
#include "sim/core/world.hpp"

namespace formsim::sim::agv {

struct MecanumDriveDef {
  control::agv::MecanumGeometry geometry;  ///< nominal geometry (what the controller knows)
  control::agv::WheelArray radius_error{0, 0, 0, 0};  ///< true radius = nominal · (1 + e_i)
  double wheel_speed_max = 12.0;      ///< |ω_i| limit, rad/s
  double motor_time_constant = 0.04;  ///< speed-loop lag, s (0: ideal)
  double wheel_accel_max = 40.0;      ///< |dω_i/dt| limit, rad/s²
  double slip_damping = 3000.0;       ///< contact force per slip speed, N·s/m
};
inline MecanumDriveDef DefaultMecanumDriveDef() {
  return MecanumDriveDef{};
}

class MecanumDrive : public DriveModel {
 public:
  explicit MecanumDrive(const MecanumDriveDef& def) : def_(def) {}
  MecanumDriveDef& def() { return def_; }
  const MecanumDriveDef& def() const { return def_; }

  /// Wheel speed set-points [rad/s], FL FR RL RR. Non-finite values become 0; each is clamped
  /// to the speed limit (the clamping is reported by `command_limited()`).
  void SetWheelCommand(const control::agv::WheelArray& w);
  void Apply(Robot& robot, World& world, double dt) override;
  bool saturated() const override { return command_limited_ || slipping(); }

  const control::agv::WheelArray& command() const { return cmd_; }
  /// Actual motor speeds and accumulated wheel angles (what an ideal encoder sees).
  const control::agv::WheelArray& wheel_speeds() const { return speed_; }
  const control::agv::WheelArray& wheel_angles() const { return angle_; }
  /// Slip speed along each roller axis at the start of the last step, m/s.
  const control::agv::WheelArray& slip() const { return slip_; }
  /// Floor force on each wheel along its roller axis in the last step, N.
  const control::agv::WheelArray& traction() const { return force_; }
  /// Wheel i was at its friction limit in the last step.
  bool wheel_slipping(int i) const { return slipping_[i]; }
  bool slipping() const;
  bool command_limited() const { return command_limited_; }
  /// True radius of wheel i.
  double true_radius(int i) const;

 private:
  MecanumDriveDef def_;
  control::agv::WheelArray cmd_{}, speed_{}, angle_{}, slip_{}, force_{};
  std::array<bool, 4> slipping_{};
  bool command_limited_ = false;
};

}  // namespace formsim::sim::agv
