#pragma once
/// \file The scenario of a Mecanum AGV experiment (type "mecanum_agv"), read strictly from YAML.
///
///   robot:       name, pose [x, y, θ] (default: path start), body {size, mass},
///                wheels {radius, half_wheelbase, half_track, radius_error [4], speed_max,
///                        motor_time_constant, accel_max, slip_damping},
///                encoders {ticks_per_rev, speed_noise}
///   beacon:      period, sigma_xy, sigma_theta, outlier_probability, outlier_size,
///                outlier_heading, dropout_probability
///   path:        type rounded_rectangle {center, size, corner_radius, direction ccw|cw}
///              | polyline {points, corner_radius, closed}
///              | segments {start [x, y, θ], segments [{line: L} | {arc: [R, angle_deg]}], closed}
///   control:     rate (Hz), v_ref, accel, v_max, omega_max, heading tangent|fixed, fixed_heading,
///                laps, window, along/cross/heading_pid {kp, ki, kd, limit, integral_limit}
///   localisation: mode odometry|beacon|fused
///   estimation:  q_xy, q_theta, r_xy, r_theta, p0_xy, p0_theta, gate, gate_probability,
///                gate_reset_after, adaptive_r, adaptive_window, adaptive_min_xy,
///                adaptive_min_theta
///   metrics:     completion_tolerance (m), jump_threshold (m)
///   world, patches, obstacles: the shared blocks.

#include <string>
#include <vector>

#include "control/agv/path.hpp"
#include "control/agv/path_tracker.hpp"
#include "control/agv/pose_filter.hpp"
#include "sim/core/world.hpp"
#include "sim/agv/beacon_sensor.hpp"
#include "sim/agv/mecanum_drive.hpp"
#include "sim/agv/wheel_encoders.hpp"

namespace formsim::sim {

/// Which estimate the path tracker uses.
enum class LocalisationMode { kOdometry = 0, kBeacon = 1, kFused = 2 };
inline const std::vector<std::string>& LocalisationModeNames() {
  static const std::vector<std::string> names = {"odometry", "beacon", "fused"};
  return names;
}

struct AgvConfig {
  WorldDef world;
  std::vector<ObstacleDef> obstacles;
  std::vector<PatchDef> patches;
  RobotDef body;  ///< name, pose, shape and mass
  bool pose_given = false;
  MecanumDriveDef drive;
  bool radius_error_given = false;  ///< robot.wheels.radius_error is in the file (a tunable list)
  WheelEncoderDef encoders;
  BeaconDef beacon;
  control::Path path;
  control::PathTrackerDef tracker;
  double control_rate = 15.0;  ///< Hz
  int control_every = 20;      ///< world steps per control period (derived from dt)
  LocalisationMode mode = LocalisationMode::kFused;
  control::PoseFilterDef filter;
  double completion_tolerance =
      0.1;  ///< m: the loop counts as done if the true cross-track stays below
  double jump_threshold =
      0.05;  ///< m: a jump is an estimate error change larger than this in one control period
};

/// Reads every AGV block from the scenario root (the loader has read the shared root keys).
AgvConfig ReadAgvConfig(YamlReader& root, double dt);

}  // namespace formsim::sim
