// Figures and the scene drawing of the velocity-control experiment.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "sim/core/number_format.hpp"
#include "sim/velocity/velocity_experiment.hpp"

namespace formsim::sim::velocity {

namespace {

Vec2 ToVec2(const cv::Vec2d& v) {
  return {v.x(), v.y()};
}

// A unit's name in figure text (label markup): the paper's R_odo and R_fused are R with a
// subscript, so a name with one inner '_' is written R_{odo}; any other name as it stands, the
// characters markup gives a meaning to escaped.
std::string UnitLabel(const std::string& name) {
  const std::size_t u = name.find('_');
  if (name.find_first_of("\\^{}") == std::string::npos && u != std::string::npos && u > 0 &&
      u + 1 < name.size() && name.find('_', u + 1) == std::string::npos)
    return name.substr(0, u) + "_{" + name.substr(u + 1) + "}";
  std::string out;
  for (char c : name) {
    if (std::strchr("\\_^{}", c) != nullptr) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

void VelocityExperiment::Bounds(Vec2& lo, Vec2& hi) const {
  Experiment::Bounds(lo, hi);
  for (const auto& u : units_)
    for (const Vec2& p : u->trail) {
      lo = {std::min(lo.x, p.x - 1.0), std::min(lo.y, p.y - 1.0)};
      hi = {std::max(hi.x, p.x + 1.0), std::max(hi.y, p.y + 1.0)};
    }
}

void VelocityExperiment::DrawScene(DrawSink& draw) const {
  const Color grey{0.45f, 0.45f, 0.45f, 0.7f};
  for (const Landmark& l : landmarks_) draw.Circle(l.p, 0.03, grey, grey);

  std::string label;  // reused: the scene is drawn every frame
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    const Color c = PaletteColor(u.index);
    const Pose2 pose = u.robot->pose();
    std::vector<Vec2> trail(u.trail.begin(), u.trail.end());
    trail.push_back(pose.p());
    draw.Polyline(trail, c.WithAlpha(0.8f), 2.0f, true);

    // Camera field of view.
    const CameraDef& cam = u.camera.def();
    const Vec2 cp = pose.ToWorld({cam.offset, 0.0});
    for (double s : {-0.5, 0.5}) {
      const double a = pose.theta + s * cam.fov;
      draw.Segment(cp, cp + Vec2{std::cos(a), std::sin(a)} * cam.range, c.WithAlpha(0.25f), 1.0f);
    }

    // The fused estimator's sliding window: keyframes (estimated poses) and landmarks.
    const auto& window = u.fused.window();
    std::vector<Vec2> chain;
    for (const auto& k : window) {
      const Vec2 p = ToVec2(k.p());
      chain.push_back(p);
      draw.Circle(p, 0.05, c.WithAlpha(0.35f), c);
      draw.Segment(p, p + Vec2{std::cos(k.theta()), std::sin(k.theta())} * 0.15, c, 2.0f);
    }
    if (chain.size() > 1) draw.Polyline(chain, c.WithAlpha(0.9f), 1.5f, false);
    if (!window.empty()) {
      const auto& newest = window.back();
      const Vec2 kp = ToVec2(newest.p() + cv::Rot(newest.theta()) * cv::Vec2d(cam.offset, 0.0));
      for (const auto& l : u.fused.Landmarks()) {
        if (!l.initialized) continue;
        const Vec2 lp = ToVec2(l.position);
        if (l.seen_in_latest) draw.Segment(kp, lp, c.WithAlpha(0.3f), 1.0f);
        draw.Circle(lp, 0.07, c.WithAlpha(0.0f), c);
      }
    }

    DrawRobotBody(draw, pose, u.robot->outline(), c, u.spec.name);
    // Wheels: red when at the friction limit.
    const double half = 0.5 * cfg_.drive.track_width, r = cfg_.drive.wheel_radius;
    for (int side = 0; side < 2; ++side) {
      const double y = side == 0 ? half : -half;
      const bool hot =
          u.drive->wheel_slipping(static_cast<DiffDrive::Side>(side)) || u.drive->skidding();
      const std::vector<Vec2> wheel = {pose.ToWorld({-r, y - 0.025}), pose.ToWorld({r, y - 0.025}),
                                       pose.ToWorld({r, y + 0.025}), pose.ToWorld({-r, y + 0.025})};
      const Color wc = hot ? Color{0.85f, 0.1f, 0.1f, 1.0f} : Color{0.15f, 0.15f, 0.15f, 1.0f};
      draw.Polygon(wheel, wc, wc);
    }
    if (u.drive->slipping() || u.drive->skidding())
      draw.Flash(pose.p(), 0.35, Color{0.85f, 0.1f, 0.1f, 1.0f}, 0.5f);
    label.clear();
    AppendSprintf(label, "v %.3f | odo %.3f | fused %.3f m/s", u.robot->forward_speed(),
                  u.odo.speed, u.est_fused.v);
    draw.Text(pose.p(), label, Color{0.1f, 0.1f, 0.1f, 1.0f}, 10.0f, 14.0f);
  }
}

void VelocityExperiment::RobotFigures(const RobotUnit& u, std::vector<FigureSpec>& out) const {
  const std::string p = u.spec.name + ".";
  const std::string suffix = units_.size() > 1 ? "_" + u.spec.name : "";
  const std::string who = units_.size() > 1 ? " (" + UnitLabel(u.spec.name) + ")" : "";
  const bool vi = cfg_.estimator.vi_baseline;

  FigureSpec speed = TimeFigure(
      "speed" + suffix,
      "Forward speed: true, odometry, fused" + std::string(vi ? ", visual-inertial" : "") + who,
      "v [m/s]",
      {Line("commanded", p + "v_cmd", 6, true), Line("odometry", p + "v_odo", 1),
       Line("fused", p + "v_fused", 2)});
  if (vi) speed.series.push_back(Line("visual-inertial only", p + "v_vi", 3));
  speed.series.push_back(Line("true", p + "v_true", 0));
  out.push_back(speed);

  FigureSpec err = TimeFigure(
      "speed_error" + suffix, "Speed estimate error (estimate − true)" + who, "error [m/s]",
      {Line("odometry", p + "err_odo", 1), Line("fused", p + "err_fused", 2)});
  if (vi) err.series.push_back(Line("visual-inertial only", p + "err_vi", 3));
  err.reference_lines = {0.0};
  out.push_back(err);

  out.push_back(
      TimeFigure("yaw_rate" + suffix, "Yaw rate: true, odometry, fused" + who, "ω [rad/s]",
                 {Line("commanded", p + "w_cmd", 6, true), Line("odometry", p + "w_odo", 1),
                  Line("fused", p + "w_fused", 2), Line("true", p + "w_true", 0)}));

  FigureSpec slip = TimeFigure(
      "slip" + suffix, "Wheel slip ratio κ = (rω − v_{contact}) / max(|rω|, |v_{contact}|)" + who,
      "κ", {Line("left wheel", p + "slip_l", 0), Line("right wheel", p + "slip_r", 1)});
  slip.reference_lines = {0.0};
  out.push_back(slip);

  out.push_back(
      TimeFigure("floor" + suffix, "Ground friction μ under each wheel" + who, "μ",
                 {Line("left wheel", p + "mu_l", 0), Line("right wheel", p + "mu_r", 1, true)}));

  FigureSpec bias = TimeFigure(
      "biases" + suffix,
      "Bias estimates: odometry speed bias b_{v} vs true odometry error, gyro bias" + who,
      "m/s, rad/s",
      {Line("odometry error v_{odo} − v (true)", p + "err_odo", 6),
       Line("b_{v} estimated", p + "bv", 2), Line("b_{ψ} estimated", p + "bw", 4),
       Line("gyro bias true", p + "bg_true", 0, true), Line("gyro bias estimated", p + "bg", 5)});
  bias.reference_lines = {0.0};
  out.push_back(bias);

  out.push_back(TimeFigure("motors" + suffix, "Motor voltages from the incremental PIDs" + who, "V",
                           {Line("left", p + "u_l", 0), Line("right", p + "u_r", 1)}));
}

std::vector<FigureSpec> VelocityExperiment::Figures() const {
  std::vector<FigureSpec> out;
  for (const auto& u : units_) RobotFigures(*u, out);
  FigureSpec traj = PlaneFigure("trajectory", "Trajectories (true)", {});
  for (const auto& u : units_)
    traj.series.push_back(
        Path(UnitLabel(u->spec.name), u->spec.name + ".x", u->spec.name + ".y", u->index));
  out.push_back(traj);
  return out;
}

}  // namespace formsim::sim::velocity
