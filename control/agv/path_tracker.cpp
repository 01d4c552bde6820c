#include "control/agv/path_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/common/angle.hpp"

namespace formsim::control::agv {

void PathTracker::SetDef(const PathTrackerDef& def) {
  def_ = def;
  pid_s_.SetGains(def.along);
  pid_d_.SetGains(def.cross);
  pid_theta_.SetGains(def.heading);
}

double PathTracker::goal_s() const {
  if (!path_.closed()) return path_.length();
  if (def_.laps <= 0) return std::numeric_limits<double>::infinity();
  return s_start_ + def_.laps * path_.length();
}

void PathTracker::Reset(const Pose2& pose) {
  pid_s_.Reset();
  pid_d_.Reset();
  pid_theta_.Reset();
  const PathProjection pr = path_.Project(pose.p());
  s_start_ = pr.s;
  errors_ = TrackingErrors{};
  errors_.s = pr.s;
  errors_.ref = pr.ref;
  v_ff_ = 0.0;
  finished_ = false;
  saturated_ = false;
}

BodyTwist PathTracker::Step(const Pose2& pose, double dt) {
  TrackingErrors& e = errors_;
  const PathProjection pr = path_.ProjectNear(pose.p(), e.s, def_.projection_window);
  e.s = pr.s;
  e.ref = pr.ref;
  e.cross_track = pr.cross_track;
  e.theta_ref = def_.heading_mode == PathTrackerDef::HeadingMode::kTangent ? pr.ref.heading
                                                                           : def_.fixed_heading;
  const Vec2 d = pr.ref.p - pose.p();
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  e.es = c * d.x + s * d.y;
  e.ed = -s * d.x + c * d.y;
  e.etheta = AngleDiff(e.theta_ref, pose.theta);

  // Feed-forward speed: ramp up at `accel`, and brake so as to stop at the goal.
  const double remaining = goal_s() - e.s;
  if (remaining <= 0.0) finished_ = true;
  if (finished_) {
    e.v_ff = v_ff_ = 0.0;
    saturated_ = false;
    return {};
  }
  const double v_brake = std::sqrt(2.0 * std::max(def_.accel, 1e-6) * std::max(remaining, 0.0));
  v_ff_ = std::min({def_.v_ref, v_ff_ + def_.accel * dt, v_brake});
  e.v_ff = v_ff_;

  const double rel = pr.ref.heading - pose.theta;  // path tangent in the body frame
  BodyTwist t;
  t.vx = v_ff_ * std::cos(rel) + pid_s_.Step(e.es, dt);
  t.vy = v_ff_ * std::sin(rel) + pid_d_.Step(e.ed, dt);
  t.omega = pid_theta_.Step(e.etheta, dt);
  if (def_.heading_mode == PathTrackerDef::HeadingMode::kTangent)
    t.omega += v_ff_ * pr.ref.curvature;

  saturated_ = pid_s_.saturated() || pid_d_.saturated() || pid_theta_.saturated();
  const double v = std::hypot(t.vx, t.vy);
  if (v > def_.v_max && v > 0.0) {
    t.vx *= def_.v_max / v;
    t.vy *= def_.v_max / v;
    saturated_ = true;
  }
  if (std::abs(t.omega) > def_.omega_max) {
    t.omega = std::copysign(def_.omega_max, t.omega);
    saturated_ = true;
  }
  return t;
}

}  // namespace formsim::control::agv
