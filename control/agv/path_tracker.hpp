#pragma once
/// \file PID path tracking for an omnidirectional base (paper 002, eq. 18-19).
///
/// Each control period the tracker projects the estimated pose on the path (nearest point,
/// searched near the previous progress) and forms the errors of Fig. 3 in the body frame:
///   [es ed]ᵀ = R(θ)ᵀ (p_ref - p)   (es: forward, ed: lateral error; > 0 when the reference is
///                                   ahead / to the left of the robot)
///   eθ = wrap(θ_ref - θ)           (θ_ref: the path tangent, or a fixed heading)
/// Three PID loops (anti-windup by clamping) act on them, added to a feed-forward that moves
/// along the path tangent at the reference speed (with start and stop ramps) and turns with
/// the path curvature when the heading follows the tangent:
///   vx = v_ff cos(ψ - θ) + PID_s(es),  vy = v_ff sin(ψ - θ) + PID_d(ed),
///   ω  = v_ff κ [tangent mode] + PID_θ(eθ).
/// The twist is then limited (|v| ≤ v_max, |ω| ≤ omega_max) and mapped to wheel speeds by the
/// inverse kinematics (eq. 19) by the caller.

#include "control/common/geometry.hpp"
#include "control/common/pid.hpp"
#include "control/agv/kinematics.hpp"
#include "control/agv/path.hpp"

namespace formsim::control::agv {

struct PathTrackerDef {
  PidGains along{1.5, 0.0, 0.0, -0.15, 0.15, 0.05};  ///< es -> vx correction, m/s
  PidGains cross{2.0, 0.5, 0.0, -0.15, 0.15, 0.05};  ///< ed -> vy correction, m/s
  PidGains heading{2.5, 0.2, 0.0, -0.8, 0.8, 0.2};   ///< eθ -> ω correction, rad/s
  double v_ref = 0.3;                                ///< speed along the path, m/s
  double accel = 0.3;      ///< start/stop ramp of the feed-forward speed, m/s²
  double v_max = 0.6;      ///< body speed limit, m/s
  double omega_max = 1.5;  ///< yaw rate limit, rad/s
  enum class HeadingMode { kTangent, kFixed } heading_mode = HeadingMode::kTangent;
  double fixed_heading = 0.0;  ///< rad, for HeadingMode::kFixed
  double projection_window =
      0.5;       ///< m around the previous progress searched for the nearest point
  int laps = 1;  ///< closed paths: stop after this many laps (0: never stop)
};
inline PathTrackerDef DefaultPathTrackerDef() {
  return PathTrackerDef{};
}

/// The errors and reference of the last control step.
struct TrackingErrors {
  double es = 0.0;           ///< forward error, body frame, m
  double ed = 0.0;           ///< lateral error, body frame, m
  double etheta = 0.0;       ///< heading error, rad, wrapped
  double cross_track = 0.0;  ///< signed distance of the (estimated) pose from the path, m
  double s = 0.0;            ///< progress along the path (unwrapped: laps add `length`), m
  double v_ff = 0.0;         ///< feed-forward speed, m/s
  PathPoint ref;             ///< nearest path point
  double theta_ref = 0.0;    ///< desired heading, rad
};

class PathTracker {
 public:
  explicit PathTracker(const PathTrackerDef& def = DefaultPathTrackerDef()) { SetDef(def); }
  /// Changes gains and limits (PID states are kept so live tuning does not jerk).
  void SetDef(const PathTrackerDef& def);
  const PathTrackerDef& def() const { return def_; }
  void SetPath(const Path& path) { path_ = path; }
  const Path& path() const { return path_; }

  /// Starts tracking from `pose` (global nearest point; zero PID states, speed ramp from 0).
  void Reset(const Pose2& pose);
  /// One control period dt with the estimated pose; returns the limited body twist.
  BodyTwist Step(const Pose2& pose, double dt);

  const TrackingErrors& errors() const { return errors_; }
  /// True when the path end (or the last lap) was reached; the twist is then zero.
  bool finished() const { return finished_; }
  /// True when the last Step had to limit the twist or a PID output saturated.
  bool saturated() const { return saturated_; }
  /// Arc length at which tracking stops (open path: its length; closed: laps × length, or ∞).
  double goal_s() const;

 private:
  PathTrackerDef def_;
  Path path_;
  Pid pid_s_, pid_d_, pid_theta_;
  TrackingErrors errors_;
  double s_start_ = 0.0;
  double v_ff_ = 0.0;
  bool finished_ = false;
  bool saturated_ = false;
};

}  // namespace formsim::control::agv
