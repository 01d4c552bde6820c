#pragma once
/// \file The parsed configuration of a `type: velocity` scenario (definition structs with
/// defaults) and its strict reader, which also declares every tunable of the kind.
///
/// Scenario layout (every key optional; unknown keys are errors):
///   world: {floor_friction}      patches: [{name, friction, ...}]      obstacles: [...]
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
///               min_parallax_deg, landmarks: inverse_depth|world_point, vi_baseline, odometry:
///               {speed_noise_density, yaw_rate_noise_density, speed_bias_rw, yaw_rate_bias_rw}}
///   control: {rate, kp, ki, kd}
///   command: {type: constant|steps, v, omega, steps: [{t, v, omega}], accel_limit,
///             angular_accel_limit, start_delay}
///   metrics: {settle_time}
///   robots: [{name, pose: [x, y, θ], feedback: odometry|fused}]   (one robot R1 when absent)
///
/// Every number has a hard range that keeps the run finite (the error message states it):
/// lengths and radii in [1e-3, 1e3] m, positions within ±1e4 m, masses in [1e-3, 1e6] kg,
/// friction μ in [0, 10], noise σ and densities >= 0 and bounded, estimator noise model values
/// >= 1e-6, |v| <= 10 m/s, |ω| <= 20 rad/s, ticks_per_rev <= 2^20, landmark count <= 1e5.
/// A rate (Hz) gives one sample every round(1 / (rate dt)) world steps and must give at least
/// one step per sample; a rate not given is its default or 1/dt, whichever is lower. Patch and
/// robot names address keys and metrics: unique, without '.' or ','.
///
/// Live tunables: control gains, command v/ω (constant command), each robot's feedback source,
/// sensor noise, floor and terrain values, estimator noise model and parallax. On reset: patch
/// friction, window size, frames per keyframe.

#include <string>
#include <vector>

#include "control/velocity/command_profile.hpp"
#include "control/velocity/sliding_window_estimator.hpp"
#include "sim/core/world.hpp"
#include "sim/core/yaml_reader.hpp"
#include "sim/velocity/diff_drive.hpp"
#include "sim/velocity/vio_sensors.hpp"

namespace formsim::sim::velocity {

namespace cv = control::velocity;

/// Where the speed loop takes its speed from (switchable live).
enum class Feedback { kOdometry = 0, kFused = 1 };
const std::vector<std::string>& FeedbackNames();

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
  cv::SlidingWindowDef window = [] {
    cv::SlidingWindowDef d;
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
  std::vector<cv::CommandStep> steps;
  double accel_limit = 1e9, angular_accel_limit = 1e9;
  /// The robot stands still this long first: the estimators see the IMU at rest, which makes
  /// the accelerometer bias (and with it the visual-inertial scale) observable.
  double start_delay = 1.0;
  cv::CommandProfile Profile() const;
};

/// World steps per sample of each multi-rate part (from the rates and the world step).
struct SampleSteps {
  int imu = 1, encoders = 1, camera = 1, control = 1;
};

struct VelocityConfig {
  WorldDef world;
  std::vector<ObstacleDef> obstacles;
  std::vector<PatchDef> patches;
  RobotDef body;
  DiffDriveDef drive;  ///< terrain has an entry for every patch (the floor's values if not given)
  EncoderDef encoders;
  ImuDef imu;
  CameraDef camera;
  LandmarkDef landmarks;
  EstimatorSettings estimator;
  ControlSettings control;
  CommandSettings command;
  SampleSteps every;
  double settle_time = 3.0;  ///< metrics ignore the start-up transient before this time, s
  std::vector<RobotSpec> robots;
};

/// Reads everything but the loader's root keys (strict) and declares the tunables; `dt` is the
/// world step the rates are checked against. Throws ScenarioError naming file, line and key.
VelocityConfig ReadVelocityConfig(YamlReader& root, double dt);

}  // namespace formsim::sim::velocity
