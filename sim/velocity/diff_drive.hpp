#pragma once
/// \file Differential drive with DC motors and slip-based traction (paper 004's platform).
///
/// Each driven wheel: a DC motor through a gearbox, i = clamp((V - k G ω) / R, ±i_max),
/// wheel torque τ = G k i - b ω, wheel inertia J (rotor inertia reflected included), and a
/// longitudinal ground force from the slip ratio κ = (r ω - v_c) / max(|r ω|, |v_c|, v_floor)
/// (v_c: speed of the contact point along the heading) with the terrain-shear law of
/// Janosi-Hanamoto form
///   F = F_max (1 - exp(-|κ| / κ0)) sign κ,    F_max = √((μ N)² - F_lat²),
/// μ = world.FrictionAt(wheel contact), N the wheel load and κ0 the terrain's shear slip: a
/// wheel needs more slip to push on a soft or slippery floor, and spins freely beyond μ N.
/// Rolling resistance c_rr N opposes each wheel's rolling and the caster's motion. The lateral
/// force that keeps the axle from side-slipping (centripetal force plus the correction of any
/// side velocity within a step) has priority on the friction circle and is itself limited by
/// μ N: beyond it the robot skids.
///
/// Stiffness: near zero speed ∂F/∂v is large, so body speed, yaw rate and both wheel speeds are
/// integrated together over `substeps` sub-steps with a linearly implicit Euler step (numerical
/// Jacobian), and the mean forces of the step are handed to Box2D, which then reproduces the
/// same velocity change. Slip is not scripted: it comes out of this physics.

#include <array>
#include <map>
#include <string>

#include "sim/core/world.hpp"

namespace formsim::sim::velocity {

/// A brushed DC motor with gearbox, values at the motor side unless said otherwise.
struct DcMotorDef {
  double resistance = 1.2;          ///< armature resistance R, Ω
  double torque_constant = 0.03;    ///< k, N·m/A (= back-EMF constant, V·s/rad)
  double gear_ratio = 20.0;         ///< G, motor turns per wheel turn
  double voltage_max = 12.0;        ///< |V| limit, V
  double current_max = 8.0;         ///< |i| limit (driver), A
  double viscous_friction = 0.002;  ///< bearing and gearbox friction at the wheel, N·m·s/rad
};

/// Ground properties beyond friction (which comes from the world's patches).
struct TerrainDef {
  double rolling_resistance = 0.015;  ///< c_rr, force per normal load
  double shear_slip = 0.05;           ///< κ0, slip ratio at which 63 % of μN is reached
};

struct DiffDriveDef {
  double wheel_radius = 0.05;    ///< true radius, m
  double track_width = 0.30;     ///< distance between the wheels, m
  double wheel_inertia = 0.004;  ///< per wheel, including the reflected rotor inertia, kg·m²
  double caster_load = 0.2;      ///< share of the weight on the passive caster
  double caster_x = -0.15;       ///< caster position along the body x axis, m
  DcMotorDef motor;
  TerrainDef floor_terrain;                   ///< where no named terrain applies
  std::map<std::string, TerrainDef> terrain;  ///< by patch name (world.PatchNameAt)
  double slip_speed_floor = 0.05;             ///< m/s, regularises κ near standstill
  int substeps = 10;
};
inline DiffDriveDef DefaultDiffDriveDef() {
  return DiffDriveDef{};
}

class DiffDrive : public DriveModel {
 public:
  enum Side { kLeft = 0, kRight = 1 };
  explicit DiffDrive(const DiffDriveDef& def) : def_(def) {}
  DiffDriveDef& def() { return def_; }
  const DiffDriveDef& def() const { return def_; }

  /// Motor voltages for the next steps; clamped to ±voltage_max (reported by saturated()).
  void SetVoltages(double left, double right);
  void Apply(Robot& robot, World& world, double dt) override;
  bool saturated() const override { return voltage_limited_ || slipping() || skidding_; }

  /// True wheel speeds (rad/s) and accumulated angles (rad): what an ideal encoder reads.
  double wheel_speed(Side s) const { return omega_[s]; }
  double wheel_angle(Side s) const { return angle_[s]; }
  /// Slip ratio κ of each wheel at the end of the last step (positive: spinning faster than
  /// the ground moves under it).
  double slip_ratio(Side s) const { return slip_[s]; }
  /// Mean longitudinal ground force on each wheel over the last step, N.
  double traction(Side s) const { return force_[s]; }
  double current(Side s) const { return current_[s]; }
  double voltage(Side s) const { return volts_[s]; }
  /// μ under each wheel in the last step.
  double friction(Side s) const { return mu_[s]; }
  /// A wheel used more than 90 % of its friction limit (it is spinning or locking).
  bool slipping() const { return wheel_slipping_[0] || wheel_slipping_[1]; }
  bool wheel_slipping(Side s) const { return wheel_slipping_[s]; }
  /// The lateral force needed to hold the track exceeded the friction: the robot slid sideways.
  bool skidding() const { return skidding_; }
  bool voltage_limited() const { return voltage_limited_; }

 private:
  const TerrainDef& TerrainAt(const World& world, Vec2 p) const;

  DiffDriveDef def_;
  std::array<double, 2> cmd_{0, 0}, volts_{0, 0}, omega_{0, 0}, angle_{0, 0}, slip_{0, 0};
  std::array<double, 2> force_{0, 0}, current_{0, 0}, mu_{0, 0};
  std::array<bool, 2> wheel_slipping_{false, false};
  bool voltage_limited_ = false, skidding_ = false;
};

}  // namespace formsim::sim::velocity
