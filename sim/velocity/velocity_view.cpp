// Drawing, figures and GUI tables of the velocity-control experiment.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/velocity/velocity_experiment.hpp"

namespace formsim::sim::vio {

namespace {

std::string Fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

Vec2 ToVec2(const control::vio::Vec2d& v) {
  return {v.x(), v.y()};
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
      const Vec2 kp = ToVec2(newest.p() + control::vio::Rot(newest.theta()) *
                                              control::vio::Vec2d(cam.offset, 0.0));
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
    char label[128];
    std::snprintf(label, sizeof label, "v %.3f | odo %.3f | fused %.3f m/s",
                  u.robot->forward_speed(), u.odo.speed, u.est_fused.v);
    draw.Text(pose.p(), label, Color{0.1f, 0.1f, 0.1f, 1.0f}, 10.0f, 14.0f);
  }
}

void VelocityExperiment::RobotFigures(const RobotUnit& u, std::vector<FigureSpec>& out) const {
  const std::string p = u.spec.name + ".";
  const std::string suffix = units_.size() > 1 ? "_" + u.spec.name : "";
  const std::string who = units_.size() > 1 ? " (" + u.spec.name + ")" : "";
  const bool vi = cfg_.estimator.vi_baseline;

  FigureSpec speed;
  speed.id = "speed" + suffix;
  speed.title =
      "Forward speed: true, odometry, fused" + std::string(vi ? ", visual-inertial" : "") + who;
  speed.y_label = "v [m/s]";
  speed.series = {{"commanded", p + "v_cmd", "", {}, {}, 6, true},
                  {"odometry", p + "v_odo", "", {}, {}, 1},
                  {"fused", p + "v_fused", "", {}, {}, 2}};
  if (vi) speed.series.push_back({"visual-inertial only", p + "v_vi", "", {}, {}, 3});
  speed.series.push_back({"true", p + "v_true", "", {}, {}, 0});
  out.push_back(speed);

  FigureSpec err;
  err.id = "speed_error" + suffix;
  err.title = "Speed estimate error (estimate − true)" + who;
  err.y_label = "error [m/s]";
  err.series = {{"odometry", p + "err_odo", "", {}, {}, 1},
                {"fused", p + "err_fused", "", {}, {}, 2}};
  if (vi) err.series.push_back({"visual-inertial only", p + "err_vi", "", {}, {}, 3});
  err.reference_lines = {0.0};
  out.push_back(err);

  FigureSpec yaw;
  yaw.id = "yaw_rate" + suffix;
  yaw.title = "Yaw rate: true, odometry, fused" + who;
  yaw.y_label = "ω [rad/s]";
  yaw.series = {{"commanded", p + "w_cmd", "", {}, {}, 6, true},
                {"odometry", p + "w_odo", "", {}, {}, 1},
                {"fused", p + "w_fused", "", {}, {}, 2},
                {"true", p + "w_true", "", {}, {}, 0}};
  out.push_back(yaw);

  FigureSpec slip;
  slip.id = "slip" + suffix;
  slip.title = "Wheel slip ratio κ = (rω − v_contact) / max(|rω|, |v_contact|)" + who;
  slip.y_label = "κ";
  slip.series = {{"left wheel", p + "slip_l", "", {}, {}, 0},
                 {"right wheel", p + "slip_r", "", {}, {}, 1}};
  slip.reference_lines = {0.0};
  out.push_back(slip);

  FigureSpec floor;
  floor.id = "floor" + suffix;
  floor.title = "Ground friction μ under each wheel" + who;
  floor.y_label = "μ";
  floor.series = {{"left wheel", p + "mu_l", "", {}, {}, 0},
                  {"right wheel", p + "mu_r", "", {}, {}, 1, true}};
  out.push_back(floor);

  FigureSpec bias;
  bias.id = "biases" + suffix;
  bias.title = "Bias estimates: odometry speed bias b_v vs true odometry error, gyro bias" + who;
  bias.y_label = "m/s, rad/s";
  bias.series = {{"odometry error v_odo − v (true)", p + "err_odo", "", {}, {}, 6},
                 {"b_v estimated", p + "bv", "", {}, {}, 2},
                 {"b_ψ estimated", p + "bw", "", {}, {}, 4},
                 {"gyro bias true", p + "bg_true", "", {}, {}, 0, true},
                 {"gyro bias estimated", p + "bg", "", {}, {}, 5}};
  bias.reference_lines = {0.0};
  out.push_back(bias);

  FigureSpec motor;
  motor.id = "motors" + suffix;
  motor.title = "Motor voltages from the incremental PIDs" + who;
  motor.y_label = "V";
  motor.series = {{"left", p + "u_l", "", {}, {}, 0}, {"right", p + "u_r", "", {}, {}, 1}};
  out.push_back(motor);
}

std::vector<FigureSpec> VelocityExperiment::Figures() const {
  std::vector<FigureSpec> out;
  for (const auto& u : units_) RobotFigures(*u, out);
  FigureSpec traj;
  traj.id = "trajectory";
  traj.title = "Trajectories (true)";
  traj.x_label = "x [m]";
  traj.y_label = "y [m]";
  traj.equal_aspect = true;
  for (const auto& u : units_)
    traj.series.push_back(
        {u->spec.name, u->spec.name + ".y", u->spec.name + ".x", {}, {}, u->index});
  out.push_back(traj);
  return out;
}

std::vector<TableSpec> VelocityExperiment::Tables() const {
  std::vector<TableSpec> out;
  TableSpec t;
  t.title = "Speed estimate RMSE and control error per floor (after settling)";
  t.header = {"robot", "floor", "odometry", "fused", "VI only", "Δv_c", "Δω_c"};
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    auto row = [&](const std::string& floor, const FloorStats& s) {
      const double T = std::max(s.time, 1e-9);
      t.rows.push_back({u.spec.name + " (" + FeedbackNames()[u.spec.feedback] + ")", floor,
                        Fmt("%.4f", s.odo.rms()), Fmt("%.4f", s.fused.rms()),
                        cfg_.estimator.vi_baseline ? Fmt("%.4f", s.vi.rms()) : "-",
                        Fmt("%.4f", std::abs(s.distance - s.v_cmd_int) / T),
                        Fmt("%.4f", std::abs(s.turn - s.w_cmd_int) / T)});
    };
    row("all", u.total);
    for (const auto& [name, s] : u.floors) row(name, s);
  }
  out.push_back(t);

  TableSpec timing;
  timing.title = "Estimator run time per update (wall clock)";
  timing.header = {"robot", "updates", "mean ms", "max ms", "period ms", "faults"};
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    timing.rows.push_back({u.spec.name, std::to_string(u.updates),
                           Fmt("%.2f", u.updates ? u.update_ms_sum / u.updates : 0.0),
                           Fmt("%.2f", u.update_ms_max), Fmt("%.0f", 1000.0 * keyframe_period()),
                           std::to_string(u.faults)});
  }
  out.push_back(timing);
  return out;
}

}  // namespace formsim::sim::vio
