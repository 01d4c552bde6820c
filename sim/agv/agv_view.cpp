// Figures and the scene drawing of the Mecanum AGV experiment.
#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"
#include "sim/agv/agv_experiment.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::sim::agv {

using ca::kMecanumWheels;

namespace {

// Palette roles, shared by the world view and the figures.
constexpr int kTruthColor = 0, kRejectedColor = 1, kFusedColor = 2, kOdoColor = 3;
constexpr int kBeaconColor = 5, kPathColor = 6;

// A scatter of inline points (the core has builders for lines and paths only).

}  // namespace

void AgvExperiment::DrawScene(DrawSink& draw) const {
  const Color path_color = PaletteColor(kPathColor);
  draw.Polyline(path_samples_, path_color.WithAlpha(0.8f), 2.0f, false);
  const ca::PathPoint start = cfg_.path.At(0.0);
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
                cfg_.body.name + " [" + ModeName(cfg_.mode) + "]", false, robot_->name());
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
    const Vec2 a = ca::MecanumGeometry::RollerAxis(i) * (0.7 * hw * std::sqrt(2.0));
    draw.Segment(truth.ToWorld(c - a), truth.ToWorld(c + a), Color{0.9f, 0.9f, 0.9f, 1}, 1.5f);
  }

  // The reference point the tracker aims at.
  const ca::TrackingErrors& e = tracker_.errors();
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
  const std::string& mode = ModeName(cfg_.mode);

  // Fig. 6 style: desired path, beacon readings, true track, fused and odometry estimates.
  FigureSpec traj = PlaneFigure(
      "trajectory", "Path tracking with " + mode + " localisation (cf. paper Fig. 6)", {});
  SeriesSpec path = Line("desired path", "", kPathColor, true);
  for (const Vec2& p : path_samples_) {
    path.x.push_back(p.x);
    path.y.push_back(p.y);
  }
  traj.series.push_back(path);
  SeriesSpec acc = Markers("beacon readings", kBeaconColor),
             rej = Markers("rejected by gate", kRejectedColor);
  for (const FixRecord& f : fixes_) {
    SeriesSpec& s = f.rejected ? rej : acc;
    s.x.push_back(f.pose.x);
    s.y.push_back(f.pose.y);
  }
  traj.series.push_back(acc);
  if (!rej.x.empty()) traj.series.push_back(rej);
  traj.series.push_back(Path("odometry estimate", "odo_x", "odo_y", kOdoColor));
  traj.series.push_back(Path("true track", "x", "y", kTruthColor));
  traj.series.push_back(Path("fused estimate", "fused_x", "fused_y", kFusedColor));
  figs.push_back(traj);

  // The paper's Fig. 6 as its two point sets on the desired path: (a) what the beacon alone
  // reads (interference outliers and dropouts included), (b) the Kalman-fused estimate at every
  // control period. Run agv_beacon_only for (a) as the paper drove it, agv_fused for (b).
  FigureSpec fig6a = PlaneFigure(
      "fig6a_beacon_points",
      "Fig. 6(a): beacon alone, before filtering (robot driven by the " + mode + " estimate)", {});
  fig6a.series.push_back(path);
  SeriesSpec beacon_points = Markers("beacon readings", kBeaconColor);
  for (const FixRecord& f : fixes_) {
    beacon_points.x.push_back(f.pose.x);
    beacon_points.y.push_back(f.pose.y);
  }
  fig6a.series.push_back(beacon_points);
  figs.push_back(fig6a);
  FigureSpec fig6b =
      PlaneFigure("fig6b_fused_points",
                  std::string("Fig. 6(b): after Kalman fusion, ") +
                      (cfg_.filter.gate ? "with our innovation gate" : "the paper's plain filter") +
                      " (robot driven by the " + mode + " estimate)",
                  {path});
  SeriesSpec fused_points = Path("fused estimate", "fused_x", "fused_y", kFusedColor);
  fused_points.markers_only = true;
  fig6b.series.push_back(fused_points);
  figs.push_back(fig6b);

  FigureSpec cross =
      TimeFigure("cross_track", "True cross-track error (" + mode + " localisation)", "e_{d} [mm]",
                 {Line("cross-track error", "cross_track_mm", kTruthColor)});
  cross.reference_lines = {-10.0, 10.0};  // the paper's ±10 mm
  figs.push_back(cross);

  figs.push_back(TimeFigure("localisation_error", "Localisation error against the truth",
                            "position error [mm]",
                            {Line("odometry", "err_odo", kOdoColor),
                             Line("beacon (raw, held)", "err_beacon", kBeaconColor),
                             Line("fused (KF)", "err_fused", kFusedColor)}));
  figs.push_back(TimeFigure(
      "heading_error", "Heading error against the truth", "heading error [deg]",
      {Line("odometry", "herr_odo", kOdoColor), Line("beacon", "herr_beacon", kBeaconColor),
       Line("fused", "herr_fused", kFusedColor)}));

  // Outliers reach NIS in the thousands; cap the axis so the accepted cloud stays readable.
  const double nis_cap = 3.0 * filter_.gate_threshold();
  FigureSpec nis =
      TimeFigure("innovation", "Normalised innovation squared of each beacon sample",
                 "NIS (χ², 3 dof), capped at " + FormatDouble(std::round(nis_cap)), {});
  SeriesSpec na = Markers("accepted", kBeaconColor),
             nr = Markers("rejected by the gate", kRejectedColor);
  for (const FixRecord& f : fixes_) {
    SeriesSpec& s = f.rejected ? nr : na;
    s.x.push_back(f.t);
    s.y.push_back(std::min(f.nis, nis_cap));
  }
  nis.series.push_back(na);
  if (!nr.x.empty()) nis.series.push_back(nr);
  if (cfg_.filter.gate) nis.reference_lines = {filter_.gate_threshold()};
  figs.push_back(nis);

  FigureSpec wheels =
      TimeFigure("wheel_slip", "Wheel slip along the roller axes", "slip [mm/s]", {});
  for (int i = 0; i < kMecanumWheels; ++i)
    wheels.series.push_back(Line(ca::kWheelNames[i], std::string("slip_") + ca::kWheelNames[i], i));
  figs.push_back(wheels);
  return figs;
}

}  // namespace formsim::sim::agv
