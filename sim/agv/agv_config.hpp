#pragma once
/// \file The parsed configuration of a `type: agv` scenario (the Mecanum AGV of paper 002) and
/// its strict reader, which also declares every tunable of the kind.
///
/// Scenario layout (every key optional; unknown keys are errors; [a, b] closed, (a, b) open):
///   robot:       name (no '.' or ','), pose [x, y, θ] (default: the path start; x, y in
///                [-1000, 1000] m), body {size [0.001, 1000] m, mass [0.001, 1e6] kg},
///                wheels {radius, half_wheelbase, half_track [0.001, 1000] m,
///                        radius_error [4] in (-0.5, 0.5), speed_max (0, 1e4] rad/s,
///                        motor_time_constant [0, 100] s, accel_max (0, 1e6] rad/s²,
///                        slip_damping (0, 1e9] N·s/m},
///                encoders {ticks_per_rev [0, 1e6] (0: ideal), speed_noise [0, 100] rad/s}
///   beacon:      period >= 0.005 s and >= one world step, sigma_xy [0, 100] m,
///                sigma_theta [0, 10] rad, outlier_probability [0, 1], outlier_size [0, 1000] m,
///                outlier_heading [0, 2π] rad, dropout_probability [0, 1]
///   path:        type rounded_rectangle {center, size, corner_radius, direction ccw|cw}
///              | polyline {points, corner_radius, closed}
///              | segments {start [x, y, θ], segments [{line: L} | {arc: [R, angle_deg]}], closed}
///                (coordinates in [-1000, 1000] m, lengths and radii in [0.001, 1000] m,
///                 arc angles in [-360, 360] deg and not 0, the start heading any (wrapped))
///   control:     rate (Hz; 1/rate a whole number of world steps), v_ref (0, 100] m/s,
///                accel (0, 1000] m/s², v_max (0, 100] m/s, omega_max (0, 1000] rad/s,
///                heading tangent|fixed, fixed_heading (rad, wrapped), laps [0, 1e6] (0: keep
///                going), window [0.001, 1000] m,
///                along/cross/heading_pid {kp, ki, kd [0, 1e4], limit (0, 1000],
///                                         integral_limit [0, 1000]}
///   localisation: mode odometry|beacon|fused
///   estimation:  q_xy, q_theta [0, 100], r_xy, r_theta [0, 100], p0_xy, p0_theta [0, 1000],
///                gate, gate_probability (0, 1), gate_reset_after [0, 1e6] (0: never),
///                adaptive_r, adaptive_window [2, 1e6], adaptive_min_xy, adaptive_min_theta
///                [0, 100]
///   metrics:     completion_tolerance (0, 1000] m, jump_threshold (0, 1000] m
///   world, patches, obstacles: the shared blocks.
///
/// Tunables (GUI group): localisation.mode (Localisation); estimation.q_*, r_*, gate,
/// gate_probability, gate_reset_after, adaptive_r, adaptive_window (Estimation/...);
/// beacon.* (Noise/beacon); robot.encoders.speed_noise and ticks_per_rev (on reset)
/// (Noise/encoders); robot.wheels.radius_error.0-3 when the list is in the file (Noise/wheels);
/// control.v_ref and the kp/ki/kd of the three PID loops (Gains/...).

#include <string>
#include <vector>

#include "control/agv/path.hpp"
#include "control/agv/path_tracker.hpp"
#include "control/agv/pose_filter.hpp"
#include "sim/agv/beacon_sensor.hpp"
#include "sim/agv/mecanum_drive.hpp"
#include "sim/agv/wheel_encoders.hpp"
#include "sim/core/world.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim::agv {

namespace ca = control::agv;

/// Which estimate the path tracker uses.
enum class LocalisationMode { kOdometry = 0, kBeacon = 1, kFused = 2 };
const std::vector<std::string>& LocalisationModeNames();
inline const std::string& ModeName(LocalisationMode m) {
  return LocalisationModeNames()[static_cast<int>(m)];
}

struct AgvConfig {
  WorldDef world;
  std::vector<ObstacleDef> obstacles;
  std::vector<PatchDef> patches;
  RobotDef body;  ///< name, pose, shape and mass
  MecanumDriveDef drive;
  WheelEncoderDef encoders;
  BeaconDef beacon;
  ca::Path path;
  ca::PathTrackerDef tracker;
  double control_rate = 15.0;  ///< Hz
  int control_every = 20;      ///< world steps per control period (derived from dt)
  LocalisationMode mode = LocalisationMode::kFused;
  ca::PoseFilterDef filter;
  double completion_tolerance =
      0.1;  ///< m: the loop counts as done if the true cross-track stays below
  double jump_threshold =
      0.05;  ///< m: a jump is an estimate error change larger than this in one control period
};

/// Reads every AGV block from the scenario root (strict) and declares the tunables. `dt` is
/// the world step (the control period must be a whole number of steps). Throws ScenarioError.
AgvConfig ReadAgvConfig(YamlReader& root, double dt);

}  // namespace formsim::sim::agv
