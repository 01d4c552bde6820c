#pragma once
/// \file Scenario settings of the velocity-control experiment (type "velocity_control") and
/// their strict YAML reader. Every value has a default here; the YAML keys are the field names:
///
///   world: {floor_friction}        patches: [...]        obstacles: [...]
///   terrain: {floor: {rolling_resistance, shear_slip}, <patch name>: {...}}
///   landmarks: {count, area: [x0, y0, x1, y1], points: [[x, y], ...]}
///   body: {shape, size: [length, width], radius, mass, collide_with_robots}  (ReadRobotBody)
///   drive: {wheel_radius, track_width, wheel_inertia, caster_load, caster_x, slip_speed_floor,
///           substeps, motor: {resistance, torque_constant, gear_ratio, voltage_max,
///           current_max, viscous_friction}}
///   sensors: {encoders: {rate, ticks_per_rev, angle_noise, radius_error, track_error},
///             imu: {rate, gyro_noise_density, accel_noise_density, gyro_bias, accel_bias: [x, y],
///             gyro_bias_rw, accel_bias_rw}, camera: {rate, fov_deg, range, bearing_noise, offset,
///             max_features}}   (see vio_sensors.hpp)
///   estimator: {window_size, keyframe_every, max_iterations, nonholonomic, nonholonomic_sigma,
///               min_parallax_deg, vi_baseline, odometry: {speed_noise_density,
///               yaw_rate_noise_density, speed_bias_rw, yaw_rate_bias_rw}}
///   control: {rate, kp, ki, kd}
///   command: {type: constant|steps, v, omega, steps: [{t, v, omega}], accel_limit,
///             angular_accel_limit, start_delay}
///   metrics: {settle_time}
///   robots: [{name, pose: [x, y, θ], feedback: odometry|fused}]

#include <string>
#include <vector>

#include "control/velocity/command_profile.hpp"
#include "control/velocity/sliding_window_estimator.hpp"
#include "sim/core/world.hpp"
#include "sim/velocity/diff_drive.hpp"
#include "sim/velocity/vio_sensors.hpp"

namespace formsim::sim {
class YamlReader;
}

namespace formsim::sim::vio {

/// Where the speed loop takes its speed from (switchable live).
enum class Feedback { kOdometry = 0, kFused = 1 };
inline const std::vector<std::string>& FeedbackNames() {
  static const std::vector<std::string> names{"odometry", "fused"};
  return names;
}

struct RobotSpec {
  std::string name = "R1";
  Pose2 pose;
  int feedback = static_cast<int>(Feedback::kFused);
};

struct LandmarkDef {
  int count = 300;
  double area[4] = {-5.0, -6.0, 25.0, 6.0};  ///< x0, y0, x1, y1
  std::vector<Vec2> points;                  ///< extra landmarks at fixed places
};

struct EstimatorSettings {
  /// IMU and camera noise are taken from the sensors. Ten keyframes 0.25 s apart: a 2.5 s
  /// window, long enough for landmark baselines that hold the visual scale.
  control::vio::SlidingWindowDef window = [] {
    control::vio::SlidingWindowDef d;
    d.window_size = 10;
    return d;
  }();
  int keyframe_every = 5;   ///< camera frames per keyframe (optimiser update)
  bool vi_baseline = true;  ///< also run the visual-inertial-only estimator (comparison)
};

struct ControlSettings {
  double rate = 50.0;  ///< Hz (the speed loop and the encoders share it by default)
  double kp = 3.0, ki = 1.0, kd = 0.0;  ///< incremental PID per sample, V per (m/s)
};

struct CommandSettings {
  int type = 0;  ///< 0 constant (also circles: ω ≠ 0), 1 steps
  double v = 0.445, omega = 0.0;
  std::vector<control::vio::CommandStep> steps;
  double accel_limit = 1e9, angular_accel_limit = 1e9;
  /// The robot stands still this long first: the estimators see the IMU at rest, which makes
  /// the accelerometer bias (and with it the visual-inertial scale) observable.
  double start_delay = 1.0;
  control::vio::CommandProfile Profile() const;
};

struct VelocityConfig {
  WorldDef world;
  std::vector<ObstacleDef> obstacles;
  std::vector<PatchDef> patches;
  RobotDef body;
  DiffDriveDef drive;
  EncoderDef encoders;
  ImuDef imu;
  CameraDef camera;
  LandmarkDef landmarks;
  EstimatorSettings estimator;
  ControlSettings control;
  CommandSettings command;
  double settle_time = 3.0;  ///< metrics ignore the start-up transient before this time, s
  std::vector<RobotSpec> robots;
};

/// Reads everything but the loader's root keys; errors name file, line and key.
VelocityConfig ReadVelocityConfig(YamlReader& root);

}  // namespace formsim::sim::vio
