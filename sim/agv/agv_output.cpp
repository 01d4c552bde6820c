// Recording, drawing, figures and summaries of the Mecanum AGV experiment.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "control/common/angle.hpp"
#include "sim/agv/agv_experiment.hpp"

namespace formsim::sim {

using control::kMecanumWheels;

namespace {

constexpr double kRadToDeg = 180.0 / control::kPi;
const char* const kWheel[] = {"FL", "FR", "RL", "RR"};

// Palette roles, shared by the world view and the figures.
constexpr int kTruthColor = 0, kRejectedColor = 1, kFusedColor = 2, kOdoColor = 3;
constexpr int kBeaconColor = 5, kPathColor = 6;

std::string Fmt(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

Json StatsJson(const EstimateStats& s) {
  Json j = Json::Object();
  j["position_rms_m"] = s.position.rms();
  j["position_max_m"] = s.position.max_abs;
  j["position_final_m"] = s.final_position_error;
  j["heading_rms_rad"] = s.heading.rms();
  j["heading_max_rad"] = s.heading.max_abs;
  j["jumps"] = s.jumps;
  return j;
}

}  // namespace

void AgvExperiment::DeclareColumns() {
  Recorder& r = recorder_;
  c_t_ = r.AddColumn("t");
  auto triple = [&r](const std::string& prefix) {
    const int c = r.AddColumn(prefix + "x");
    r.AddColumn(prefix + "y");
    r.AddColumn(prefix + "theta");
    return c;
  };
  c_true_ = triple("");
  c_odo_ = triple("odo_");
  c_beacon_ = triple("beacon_");
  c_fused_ = triple("fused_");
  c_sd_ = triple("fused_sd_");
  c_cross_ = r.AddColumn("cross_track");
  c_cross_mm_ = r.AddColumn("cross_track_mm");
  c_est_cross_ = r.AddColumn("est_cross_track");
  c_track_err_ = r.AddColumn("es");
  r.AddColumn("ed");
  r.AddColumn("etheta");
  c_err_ = r.AddColumn("err_odo");
  r.AddColumn("err_beacon");
  r.AddColumn("err_fused");
  c_herr_ = r.AddColumn("herr_odo");
  r.AddColumn("herr_beacon");
  r.AddColumn("herr_fused");
  c_nis_ = r.AddColumn("nis");
  c_acc_ = r.AddColumn("accepted");
  c_rej_ = r.AddColumn("rejected");
  c_twist_ = r.AddColumn("vx_cmd");
  r.AddColumn("vy_cmd");
  r.AddColumn("omega_cmd");
  c_wcmd_ = r.AddColumn(std::string("w_cmd_") + kWheel[0]);
  for (int i = 1; i < kMecanumWheels; ++i) r.AddColumn(std::string("w_cmd_") + kWheel[i]);
  c_w_ = r.AddColumn(std::string("w_") + kWheel[0]);
  for (int i = 1; i < kMecanumWheels; ++i) r.AddColumn(std::string("w_") + kWheel[i]);
  c_slip_ = r.AddColumn(std::string("slip_") + kWheel[0]);
  for (int i = 1; i < kMecanumWheels; ++i) r.AddColumn(std::string("slip_") + kWheel[i]);
  c_slipping_ = r.AddColumn("slipping");
  c_mu_ = r.AddColumn("mu");
  c_mode_ = r.AddColumn("mode");
  c_progress_ = r.AddColumn("progress");
}

void AgvExperiment::Record(Recorder& r) {
  const Pose2 truth = robot_->pose();
  auto set_pose = [&r](int c, const Pose2& p) {
    r.Set(c, p.x);
    r.Set(c + 1, p.y);
    r.Set(c + 2, p.theta);
  };
  r.Set(c_t_, time());
  set_pose(c_true_, truth);
  set_pose(c_odo_, odometry_.pose());
  set_pose(c_beacon_, beacon_pose_);
  set_pose(c_fused_, filter_.pose());
  const Eigen::Matrix3d& P = filter_.covariance();
  for (int k = 0; k < 3; ++k) r.Set(c_sd_ + k, std::sqrt(std::max(0.0, P(k, k))));
  r.Set(c_cross_, true_cross_);
  r.Set(c_cross_mm_, true_cross_ * 1000.0);
  const control::TrackingErrors& e = tracker_.errors();
  r.Set(c_est_cross_, e.cross_track);
  r.Set(c_track_err_, e.es);
  r.Set(c_track_err_ + 1, e.ed);
  r.Set(c_track_err_ + 2, e.etheta);
  const Pose2 est[3] = {odometry_.pose(), beacon_pose_, filter_.pose()};
  for (int k = 0; k < 3; ++k) {
    r.Set(c_err_ + k, (est[k].p() - truth.p()).Norm() * 1000.0);
    r.Set(c_herr_ + k, control::AngleDiff(est[k].theta, truth.theta) * kRadToDeg);
  }
  r.Set(c_nis_, last_nis_);
  r.Set(c_acc_, static_cast<double>(counts_.accepted));
  r.Set(c_rej_, static_cast<double>(counts_.rejected));
  r.Set(c_twist_, cmd_twist_.vx);
  r.Set(c_twist_ + 1, cmd_twist_.vy);
  r.Set(c_twist_ + 2, cmd_twist_.omega);
  for (int i = 0; i < kMecanumWheels; ++i) {
    r.Set(c_wcmd_ + i, drive_->command()[i]);
    r.Set(c_w_ + i, drive_->wheel_speeds()[i]);
    r.Set(c_slip_ + i, drive_->slip()[i] * 1000.0);
  }
  r.Set(c_slipping_, drive_->slipping() ? 1.0 : 0.0);
  r.Set(c_mu_, world_.FrictionAt(truth.p()));
  r.Set(c_mode_, static_cast<double>(cfg_.mode));
  r.Set(c_progress_, true_s_);
}

void AgvExperiment::DrawScene(DrawSink& draw) const {
  const Color path_color = PaletteColor(kPathColor);
  draw.Polyline(path_samples_, path_color.WithAlpha(0.8f), 2.0f, false);
  const control::PathPoint start = cfg_.path.At(0.0);
  draw.Segment(start.p, start.p + Vec2{std::cos(start.heading), std::sin(start.heading)} * 0.25,
               path_color, 2.0f);

  // Trails: truth (fading), fused and odometry estimates.
  auto trail = [&draw](const std::deque<Vec2>& d, Color c, float w, bool fade) {
    if (d.size() > 1) draw.Polyline(std::vector<Vec2>(d.begin(), d.end()), c, w, fade);
  };
  trail(trail_odo_, PaletteColor(kOdoColor).WithAlpha(0.8f), 1.5f, false);
  trail(trail_fused_, PaletteColor(kFusedColor).WithAlpha(0.9f), 1.5f, false);
  trail(trail_true_, PaletteColor(kTruthColor), 2.5f, true);

  // Recent beacon fixes: accepted as dots, rejected by the gate as crosses.
  const std::size_t n_show = 60;
  const std::size_t first = fixes_.size() > n_show ? fixes_.size() - n_show : 0;
  for (std::size_t i = first; i < fixes_.size(); ++i) {
    const FixRecord& f = fixes_[i];
    const float age = static_cast<float>(fixes_.size() - i) / n_show;
    if (f.rejected) {
      draw.Cross(f.pose.p(), 0.08, PaletteColor(kRejectedColor).WithAlpha(1.0f - 0.6f * age));
    } else {
      const Color c = PaletteColor(kBeaconColor).WithAlpha(1.0f - 0.7f * age);
      draw.Circle(f.pose.p(), 0.015, c, c);
    }
  }

  // Estimates: odometry and fused ghosts, fused 2σ covariance ellipse, beacon ghost.
  const std::vector<Vec2> outline = robot_->outline();
  DrawRobotBody(draw, odometry_.pose(), outline, PaletteColor(kOdoColor), "", true);
  DrawRobotBody(draw, beacon_pose_, outline, PaletteColor(kBeaconColor), "", true);
  DrawRobotBody(draw, filter_.pose(), outline, PaletteColor(kFusedColor), "", true);
  const Eigen::Matrix3d& P = filter_.covariance();
  draw.CovarianceEllipse(filter_.pose().p(), P(0, 0), P(0, 1), P(1, 1), 2.0,
                         PaletteColor(kFusedColor));

  // The true robot with its four wheels; a wheel at its friction limit turns red.
  const Pose2 truth = robot_->pose();
  DrawRobotBody(draw, truth, outline, PaletteColor(kTruthColor),
                cfg_.body.name + " [" + LocalisationModeNames()[static_cast<int>(cfg_.mode)] + "]");
  const double r = cfg_.drive.geometry.wheel_radius, hw = 0.035;
  for (int i = 0; i < kMecanumWheels; ++i) {
    const Vec2 c = cfg_.drive.geometry.WheelPosition(i);
    const std::vector<Vec2> wheel = {
        truth.ToWorld(c + Vec2{r, hw}), truth.ToWorld(c + Vec2{-r, hw}),
        truth.ToWorld(c + Vec2{-r, -hw}), truth.ToWorld(c + Vec2{r, -hw})};
    const bool slip = drive_->wheel_slipping(i);
    draw.Polygon(wheel, slip ? Color{0.85f, 0.1f, 0.1f, 1} : Color{0.15f, 0.15f, 0.15f, 1},
                 Color{0, 0, 0, 1});
    // The contact roller's axis at 45°.
    const Vec2 a = control::MecanumGeometry::RollerAxis(i) * (0.7 * hw * std::sqrt(2.0));
    draw.Segment(truth.ToWorld(c - a), truth.ToWorld(c + a), Color{0.9f, 0.9f, 0.9f, 1}, 1.5f);
  }

  // The reference point the tracker aims at.
  const control::TrackingErrors& e = tracker_.errors();
  draw.Segment(ControlPose().p(), e.ref.p, Color{0.2f, 0.2f, 0.2f, 0.7f}, 1.0f);
  draw.Circle(e.ref.p, 0.02, Color{1, 1, 1, 1}, Color{0.1f, 0.1f, 0.1f, 1});
}

void AgvExperiment::Bounds(Vec2& lo, Vec2& hi) const {
  Experiment::Bounds(lo, hi);
  for (const Vec2& p : path_samples_) {
    lo.x = std::min(lo.x, p.x - 0.5);
    lo.y = std::min(lo.y, p.y - 0.5);
    hi.x = std::max(hi.x, p.x + 0.5);
    hi.y = std::max(hi.y, p.y + 0.5);
  }
}

std::vector<FigureSpec> AgvExperiment::Figures() const {
  std::vector<FigureSpec> figs;
  const std::string mode = LocalisationModeNames()[static_cast<int>(cfg_.mode)];

  // Fig. 6 style: desired path, beacon readings, true track, fused and odometry estimates.
  FigureSpec traj;
  traj.id = "trajectory";
  traj.title = "Path tracking with " + mode + " localisation (cf. paper Fig. 6)";
  traj.x_label = "x [m]";
  traj.y_label = "y [m]";
  traj.equal_aspect = true;
  SeriesSpec path;
  path.label = "desired path";
  path.color_index = kPathColor;
  path.dashed = true;
  for (const Vec2& p : path_samples_) {
    path.x.push_back(p.x);
    path.y.push_back(p.y);
  }
  traj.series.push_back(path);
  SeriesSpec acc, rej;
  acc.label = "beacon readings";
  acc.color_index = kBeaconColor;
  acc.markers_only = true;
  rej.label = "rejected by gate";
  rej.color_index = kRejectedColor;
  rej.markers_only = true;
  for (const FixRecord& f : fixes_) {
    SeriesSpec& s = f.rejected ? rej : acc;
    s.x.push_back(f.pose.x);
    s.y.push_back(f.pose.y);
  }
  traj.series.push_back(acc);
  if (!rej.x.empty()) traj.series.push_back(rej);
  traj.series.push_back({"odometry estimate", "odo_y", "odo_x", {}, {}, kOdoColor, false, false});
  traj.series.push_back({"true track", "y", "x", {}, {}, kTruthColor, false, false});
  traj.series.push_back(
      {"fused estimate", "fused_y", "fused_x", {}, {}, kFusedColor, false, false});
  figs.push_back(traj);

  FigureSpec cross;
  cross.id = "cross_track";
  cross.title = "True cross-track error (" + mode + " localisation)";
  cross.y_label = "e_d [mm]";
  cross.series.push_back(
      {"cross-track error", "cross_track_mm", "", {}, {}, kTruthColor, false, false});
  cross.reference_lines = {-10.0, 10.0};  // the paper's ±10 mm
  figs.push_back(cross);

  FigureSpec loc;
  loc.id = "localisation_error";
  loc.title = "Localisation error against the truth";
  loc.y_label = "position error [mm]";
  loc.series.push_back({"odometry", "err_odo", "", {}, {}, kOdoColor, false, false});
  loc.series.push_back(
      {"beacon (raw, held)", "err_beacon", "", {}, {}, kBeaconColor, false, false});
  loc.series.push_back({"fused (KF)", "err_fused", "", {}, {}, kFusedColor, false, false});
  figs.push_back(loc);

  FigureSpec head;
  head.id = "heading_error";
  head.title = "Heading error against the truth";
  head.y_label = "heading error [deg]";
  head.series.push_back({"odometry", "herr_odo", "", {}, {}, kOdoColor, false, false});
  head.series.push_back({"beacon", "herr_beacon", "", {}, {}, kBeaconColor, false, false});
  head.series.push_back({"fused", "herr_fused", "", {}, {}, kFusedColor, false, false});
  figs.push_back(head);

  // Outliers reach NIS in the thousands; cap the axis so the accepted cloud stays readable.
  const double nis_cap = 3.0 * filter_.gate_threshold();
  FigureSpec nis;
  nis.id = "innovation";
  nis.title = "Normalised innovation squared of each beacon sample";
  nis.y_label = "NIS (χ², 3 dof), capped at " + Fmt("%.0f", nis_cap);
  SeriesSpec na, nr;
  na.label = "accepted";
  na.color_index = kBeaconColor;
  na.markers_only = true;
  nr.label = "rejected by the gate";
  nr.color_index = kRejectedColor;
  nr.markers_only = true;
  for (const FixRecord& f : fixes_) {
    SeriesSpec& s = f.rejected ? nr : na;
    s.x.push_back(f.t);
    s.y.push_back(std::min(f.nis, nis_cap));
  }
  nis.series.push_back(na);
  if (!nr.x.empty()) nis.series.push_back(nr);
  if (cfg_.filter.gate) nis.reference_lines = {filter_.gate_threshold()};
  figs.push_back(nis);

  FigureSpec wheels;
  wheels.id = "wheel_slip";
  wheels.title = "Wheel slip along the roller axes";
  wheels.y_label = "slip [mm/s]";
  for (int i = 0; i < kMecanumWheels; ++i)
    wheels.series.push_back(
        {kWheel[i], std::string("slip_") + kWheel[i], "", {}, {}, i, false, false});
  figs.push_back(wheels);
  return figs;
}

std::vector<TableSpec> AgvExperiment::Tables() const {
  TableSpec t;
  t.title = "Localisation against the truth";
  t.header = {"estimate", "RMS [mm]", "max [mm]", "heading RMS [deg]", "jumps"};
  auto row = [&t](const char* name, const EstimateStats& s) {
    t.rows.push_back({name, Fmt("%.1f", s.position.rms() * 1000),
                      Fmt("%.1f", s.position.max_abs * 1000),
                      Fmt("%.2f", s.heading.rms() * kRadToDeg), std::to_string(s.jumps)});
  };
  row("odometry", stats_odo_);
  row("beacon", stats_beacon_);
  row("fused", stats_fused_);
  TableSpec b;
  b.title = "Beacon samples and the gate";
  b.header = {"samples", "dropouts", "outliers", "accepted", "rejected", "outliers rejected"};
  b.rows.push_back({std::to_string(counts_.samples), std::to_string(counts_.dropouts),
                    std::to_string(counts_.outliers), std::to_string(counts_.accepted),
                    std::to_string(counts_.rejected), std::to_string(counts_.rejected_outliers)});
  return {t, b};
}

Json AgvExperiment::Summary() const {
  Json j = Json::Object();
  j["localisation_mode"] = LocalisationModeNames()[static_cast<int>(cfg_.mode)];
  j["path_length_m"] = cfg_.path.length();
  j["tracking_finished"] = tracking_done_;
  j["tracking_time_s"] = done_time_;
  j["loop_completed"] = completed();
  j["completion_tolerance_m"] = cfg_.completion_tolerance;
  Json ct = Json::Object();
  ct["rms_m"] = cross_track_.rms();
  ct["max_m"] = cross_track_.max_abs;
  ct["final_m"] = true_cross_;
  j["cross_track"] = ct;
  const control::PathPoint end = cfg_.path.At(tracker_.goal_s());
  j["final_distance_to_goal_m"] = (robot_->pose().p() - end.p).Norm();
  Json loc = Json::Object();
  loc["odometry"] = StatsJson(stats_odo_);
  loc["beacon"] = StatsJson(stats_beacon_);
  loc["fused"] = StatsJson(stats_fused_);
  j["localisation"] = loc;
  Json b = Json::Object();
  b["samples"] = counts_.samples;
  b["dropouts"] = counts_.dropouts;
  b["outliers"] = counts_.outliers;
  b["accepted"] = counts_.accepted;
  b["rejected"] = counts_.rejected;
  b["rejected_outliers"] = counts_.rejected_outliers;
  b["accepted_outliers"] = counts_.accepted_outliers;
  b["rejected_good"] = counts_.rejected - counts_.rejected_outliers;
  b["reinitialisations"] = counts_.reinitialisations;
  b["faults"] = counts_.faults;
  b["nis_mean"] = counts_.accepted ? counts_.nis_sum / counts_.accepted : 0.0;
  b["suppressed_events"] = suppressed_events_;
  j["beacon"] = b;
  Json f = Json::Object();
  f["gate"] = cfg_.filter.gate;
  f["adaptive_r"] = cfg_.filter.adaptive_r;
  f["r_xy_in_use_m"] = std::sqrt(filter_.measurement_cov()(0, 0));
  f["r_theta_in_use_rad"] = std::sqrt(filter_.measurement_cov()(2, 2));
  j["filter"] = f;
  return j;
}

std::string AgvExperiment::SummaryTable() const {
  std::string s;
  char line[200];
  std::snprintf(line, sizeof line, "Mecanum AGV, %s localisation, path %.2f m: %s\n",
                LocalisationModeNames()[static_cast<int>(cfg_.mode)].c_str(), cfg_.path.length(),
                !tracking_done_ ? "did not finish (duration too short?)"
                : completed()   ? "completed"
                                : "finished in its own belief, but off the path");
  s += line;
  std::snprintf(
      line, sizeof line, "  true cross-track error: RMS %.1f mm, max %.1f mm (tolerance %.0f mm)\n",
      cross_track_.rms() * 1000, cross_track_.max_abs * 1000, cfg_.completion_tolerance * 1000);
  s += line;
  s += "  localisation      RMS [mm]   max [mm]  final [mm]  heading RMS [deg]  jumps\n";
  auto row = [&](const char* name, const EstimateStats& e) {
    std::snprintf(line, sizeof line, "  %-16s %9.1f %10.1f %11.1f %18.2f %6ld\n", name,
                  e.position.rms() * 1000, e.position.max_abs * 1000, e.final_position_error * 1000,
                  e.heading.rms() * kRadToDeg, e.jumps);
    s += line;
  };
  row("odometry", stats_odo_);
  row("beacon (raw)", stats_beacon_);
  row("fused (KF)", stats_fused_);
  std::snprintf(line, sizeof line,
                "  beacon: %ld samples, %ld dropouts, %ld outliers; gate %s: %ld rejected "
                "(%ld outliers), %ld outliers accepted, %ld re-inits, %ld faults\n",
                counts_.samples, counts_.dropouts, counts_.outliers,
                cfg_.filter.gate ? "on" : "off", counts_.rejected, counts_.rejected_outliers,
                counts_.accepted_outliers, counts_.reinitialisations, counts_.faults);
  s += line;
  return s;
}

}  // namespace formsim::sim
