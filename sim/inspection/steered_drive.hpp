#pragma once
/// \file The inspection robot's drive (paper section 2): left and right rear drive motors
/// commanded in speed levels u1, u2 ∈ [0, 4] and a front steering servo commanded in units
/// u3 ∈ [220, 500], as the fuzzy controller outputs them. Scales (documented, tunable):
///   rear wheel rim speed   v_L = speed_per_level · u1,  v_R = speed_per_level · u2
///   steering angle         δ = steer_per_unit · (u3 − servo_center), > 0 steers right,
///                          limited to ±steer_max and slewed at steer_rate.
/// Physics (a tricycle in Box2D): each rear motor is a proportional speed loop with time
/// constant motor_time_constant and force limit motor_force_max; the steered front wheel rolls
/// freely (rolling resistance). Every wheel resists sliding sideways; all wheel forces are
/// limited by the friction circle μ·N of the ground under that wheel (N from the static load
/// split), solved by sequential impulses on the body's velocity, then applied as forces. When a
/// rear wheel reaches its friction limit it spins: its encoder reads the motor speed, not the
/// ground speed, which is what makes odometry drift on slippery patches.

#include <array>

#include "control/common/geometry.hpp"
#include "sim/core/world.hpp"

namespace formsim::sim {
class YamlReader;
}  // namespace formsim::sim

namespace formsim::sim::inspection {

struct SteeredDriveDef {
  double speed_per_level = 0.15;             ///< rim speed per u1/u2 level, m/s
  double servo_center = 360.0;               ///< u3 that steers straight
  double steer_per_unit_deg = 30.0 / 140.0;  ///< steering angle per servo unit, deg
  double steer_max_deg = 30.0;               ///< steering stop, deg
  double steer_rate_deg_s = 90.0;            ///< servo slew rate, deg/s
  double wheelbase = 0.6;                    ///< rear axle to front wheel, m
  double track = 0.5;                        ///< rear wheel spacing, m
  double rear_axle = -0.3;                   ///< rear axle position along the body axis, m
  double motor_force_max = 40.0;             ///< per rear motor, N
  double motor_time_constant = 0.15;         ///< speed loop time constant, s
  double rolling_resistance = 0.015;         ///< front wheel rolling resistance coefficient
  double front_load = 0.4;                   ///< share of the weight on the front wheel
};
inline SteeredDriveDef DefaultSteeredDriveDef() {
  return SteeredDriveDef{};
}

/// Reads `robot.drive:` (keys as in SteeredDriveDef), checking ranges; the scales and limits
/// are tunables (group "Gains/vehicle scales").
SteeredDriveDef ReadSteeredDrive(YamlReader& drive_map);

class SteeredDrive : public DriveModel {
 public:
  static constexpr double kLevelMax = 4.0;
  static constexpr double kServoMin = 220.0, kServoMax = 500.0;

  explicit SteeredDrive(const SteeredDriveDef& def) : def_(def) {}
  /// The controller's outputs, clamped to [0, 4] and [220, 500] (non-finite values stop).
  void SetCommand(double u1, double u2, double u3);
  void Apply(Robot& robot, World& world, double dt) override;
  bool saturated() const override { return slipping_ || motor_limited_; }

  SteeredDriveDef& def() { return def_; }
  const SteeredDriveDef& def() const { return def_; }
  double u1() const { return u1_; }
  double u2() const { return u2_; }
  double u3() const { return u3_; }
  /// Current steering angle, rad, > 0 right (paper convention).
  double steer_angle() const { return steer_; }
  /// Steering angle the servo is heading for, rad.
  double steer_target() const;
  /// Cumulative rolling distance of the left / right rear wheel (what the encoders count), m.
  double wheel_distance_left() const { return wheel_dist_[0]; }
  double wheel_distance_right() const { return wheel_dist_[1]; }
  /// A wheel was at its friction limit in the last step (the robot slid or a wheel spun).
  bool slipping() const { return slipping_; }
  bool motor_limited() const { return motor_limited_; }
  /// Front wheel contact point in the body frame (x forward, y left), for drawing.
  Vec2 front_wheel() const { return {def_.rear_axle + def_.wheelbase, 0.0}; }

 private:
  SteeredDriveDef def_;
  double u1_ = 0.0, u2_ = 0.0, u3_ = 360.0;
  double steer_ = 0.0;
  std::array<double, 2> wheel_dist_{0.0, 0.0};
  bool slipping_ = false, motor_limited_ = false;
};

}  // namespace formsim::sim::inspection
