// Drawing, figures and tables of the inspection experiment.
#include <algorithm>
#include <cmath>

#include "control/inspection/paper_frame.hpp"
#include "sim/core/number_format.hpp"
#include "sim/inspection/inspection_experiment.hpp"

namespace formsim::sim::inspection {

namespace ins = control::inspection;

namespace {

const Color kRouteColor{0.55f, 0.55f, 0.55f, 0.9f};
const Color kRayColor{0.85f, 0.2f, 0.2f, 0.12f};
const Color kUsedColor{0.0f, 0.62f, 0.45f, 1.0f};     // bluish green
const Color kSeenColor{0.9f, 0.6f, 0.0f, 0.9f};       // orange
const Color kRawColor{0.84f, 0.37f, 0.0f, 1.0f};      // vermillion
const Color kClassicColor{0.8f, 0.47f, 0.65f, 1.0f};  // reddish purple
const Color kKalmanColor{0.0f, 0.45f, 0.7f, 1.0f};    // blue
const Color kDrColor{0.5f, 0.5f, 0.5f, 1.0f};

// Colours: 0 truth, 4 Kalman, 5 raw fixes (markers), 6 limit + mean, 7 dead reckoning.
SeriesSpec InspectionMarkers(SeriesSpec s) {
  s.markers_only = true;
  return s;
}

// The three estimates of one quantity: raw fixes (markers), limit + mean, Kalman.
std::vector<SeriesSpec> InspectionEstimates(const std::string& raw_col,
                                            const std::string& classic_col,
                                            const std::string& kf_col) {
  SeriesSpec r = InspectionMarkers(Line("raw fix", "", 5));
  r.column = raw_col;
  return std::vector<SeriesSpec>{r, Line("limit + mean", classic_col, 6),
                                 Line("Kalman", kf_col, 4)};
}

// The figures over time: the paper's Figs. 8 and 9, the estimates' errors, the tracking errors
// and the controller's outputs.
std::vector<FigureSpec> InspectionTimeFigures(double centre_x, double servo_center) {
  std::vector<FigureSpec> figs;
  {
    std::vector<SeriesSpec> s = InspectionEstimates("s1_raw_x", "s1_classic_x", "s1_kf_x");
    s.push_back(Line("ideal (true)", "s1_true_x", 0, true));
    FigureSpec f =
        TimeFigure("fig8_x",
                   "Fig. 8: X on the first straight (centre line X = " + Sprintf("%.1f", centre_x) +
                       " m): raw / limit+mean / Kalman / ideal",
                   "X [m]", std::move(s));
    f.reference_lines = {centre_x};
    figs.push_back(f);
  }
  {
    std::vector<SeriesSpec> s = InspectionEstimates("s1_raw_y", "s1_classic_y", "s1_kf_y");
    s.push_back(Line("ideal (true)", "s1_true_y", 0, true));
    figs.push_back(TimeFigure("fig9_y",
                              "Fig. 9: Y on the first straight: raw / limit+mean / Kalman / ideal",
                              "Y [m]", std::move(s)));
  }
  figs.push_back(TimeFigure("x_error", "X error (estimate − truth), whole route", "ΔX [m]",
                            InspectionEstimates("raw_ex", "classic_ex", "kf_ex")));
  figs.back().reference_lines = {0.0};
  figs.push_back(TimeFigure("y_error", "Y error (estimate − truth), whole route", "ΔY [m]",
                            InspectionEstimates("raw_ey", "classic_ey", "kf_ey")));
  figs.back().reference_lines = {0.0};
  figs.push_back(TimeFigure("localisation_error", "Position error of each estimate", "error [m]",
                            InspectionEstimates("err_raw", "err_classic", "err_kf")));
  figs.back().reference_lines = {0.1};  // the paper's ~10 cm
  figs.push_back(TimeFigure("dead_reckoning_error",
                            "Dead reckoning alone (eq. 1, encoders only) drifts", "error [m]",
                            {Line("dead reckoning", "err_dr", 7), Line("Kalman", "err_kf", 4)}));
  figs.push_back(TimeFigure(
      "lateral_offset", "Lateral offset s from the route (true, and as the controller saw it)",
      "s [m]", {Line("true", "s_true", 0), Line("controller input", "s_ctrl", 4, true)}));
  figs.back().reference_lines = {0.0};
  figs.push_back(TimeFigure(
      "heading_error", "Heading error Δφ (true, and as the controller saw it)", "Δφ [deg]",
      {Line("true", "dphi_true_deg", 0), Line("controller input", "dphi_ctrl_deg", 4, true)}));
  figs.back().reference_lines = {0.0};
  figs.push_back(
      TimeFigure("fuzzy_speed_levels", "Drive motor levels u1 (left), u2 (right)", "level",
                 {Line("u1 left", "u1", 1), Line("u2 right", "u2", 2),
                  Line("u1 fuzzy", "fz_u1", 1, true), Line("u2 fuzzy", "fz_u2", 2, true)}));
  figs.push_back(TimeFigure("fuzzy_steering",
                            "Steering servo command u3 (360 = straight, > 360 right)", "u3",
                            {Line("u3 sent", "u3", 3), Line("u3 fuzzy", "fz_u3", 4, true)}));
  figs.back().reference_lines = {servo_center};
  return figs;
}

// The plane: the route, the posts, the raw fixes and the true and Kalman paths.
FigureSpec InspectionTrajectoryFigure(const ins::Route& route_line,
                                      const std::vector<InspectionPost>& post_list) {
  SeriesSpec route = Line("route", "", 7, true);
  for (const Vec2& p : route_line.Polyline(0.2)) {
    route.x.push_back(p.x);
    route.y.push_back(p.y);
  }
  SeriesSpec posts = InspectionMarkers(Line("posts", "", 6));
  for (const auto& p : post_list) {
    posts.x.push_back(p.position.x);
    posts.y.push_back(p.position.y);
  }
  SeriesSpec raw_path = InspectionMarkers(Path("raw fix", "raw_x", "raw_y", 5));
  FigureSpec f = PlaneFigure("trajectory", "Route and trajectories",
                             {route, posts, raw_path, Path("true", "true_x", "true_y", 0),
                              Path("Kalman", "kf_x", "kf_y", 4)});
  f.x_label = "X [m]";
  f.y_label = "Y [m]";
  return f;
}

// The terms near the path are centimetres wide: the same functions within ±0.35 m.
FigureSpec InspectionNearPathZoom(const FigureSpec& f) {
  FigureSpec zoom = f;
  zoom.id = "mf_s_near";
  zoom.title = "Membership functions, s within 0.35 m of the path";
  for (SeriesSpec& series : zoom.series) {
    SeriesSpec kept = series;
    kept.x.clear();
    kept.y.clear();
    for (std::size_t i = 0; i < series.x.size(); ++i)
      if (std::abs(series.x[i]) <= 0.35) {
        kept.x.push_back(series.x[i]);
        kept.y.push_back(series.y[i]);
      }
    series = std::move(kept);
  }
  if (std::abs(zoom.marker_x) > 0.35) zoom.marker_x = std::nan("");
  return zoom;
}

// Membership functions with the current value marked, one figure per variable (and a zoom of s
// near the path).
void AddInspectionMembershipFigures(const std::vector<ins::FuzzyVariableInfo>& variables,
                                    std::vector<FigureSpec>& figs) {
  const char* const titles[] = {"s: lateral offset [m]", "Δφ: heading error [deg]",
                                "u1: left drive level", "u2: right drive level",
                                "u3: steering servo command"};
  int vi = 0;
  for (const auto& v : variables) {
    FigureSpec f = TimeFigure("mf_" + v.name,
                              std::string("Membership functions, ") + titles[std::min(vi++, 4)],
                              "membership", {});
    f.x_label = v.name == "dphi" ? "Δφ [deg]" : v.name == "s" ? "s [m]" : v.name;
    int color = 0;
    for (const auto& term : v.terms) {
      SeriesSpec s = Line(term.name, "", color++);
      s.x = term.x;
      s.y = term.y;
      f.series.push_back(std::move(s));
    }
    if (!v.input) {
      // What the last decision defuzzified: the rules' clipped terms joined, and (the marker)
      // its weighted average over the universe.
      SeriesSpec set = Line("fired set", "", 9, true);
      set.x = v.output_set.x;
      set.y = v.output_set.y;
      f.series.push_back(std::move(set));
      f.title =
          "Membership functions, " + v.name + "; dashed: fired set, marker: its weighted average";
    }
    f.marker_x = v.value;
    figs.push_back(f);
    if (v.name == "s") figs.push_back(InspectionNearPathZoom(f));
  }
}

}  // namespace

void InspectionExperiment::DrawScene(DrawSink& draw) const {
  // Route centre line and the turn centre.
  draw.Polyline(route_.Polyline(0.2), kRouteColor, 1.5f, false);
  for (const auto& seg : route_.segments())
    if (seg.kind == ins::RouteSegment::Kind::kArc) draw.Cross(seg.centre, 0.2, kRouteColor);

  // Laser rays of the last scan (every third beam with a return), from where it was taken.
  const Vec2 origin = scan_pose_.p();
  for (std::size_t k = 0; k < scan_endpoints_.size(); k += 3) {
    if ((scan_endpoints_[k] - origin).Norm() < cfg_.laser.range_max - 1e-6)
      draw.Segment(origin, scan_endpoints_[k], kRayColor, 1.0f);
  }
  // Identified posts: rays to them; the two used for the fix highlighted.
  const double heading = ins::PaperFromMath(scan_pose_.theta);
  for (const auto& s : detection_.sightings) {
    const bool used =
        std::find(used_posts_.begin(), used_posts_.end(), s.post) != used_posts_.end();
    const Vec2 hit = origin + ins::AzimuthDirection(heading + s.bearing) * s.range;
    draw.Segment(origin, hit, used ? kUsedColor : kSeenColor, used ? 2.5f : 1.2f);
    const Vec2 post = cfg_.posts[s.post].position;
    draw.Circle(post, cfg_.post_radius + (used ? 0.12 : 0.07), Color{0, 0, 0, 0},
                used ? kUsedColor : kSeenColor);
    if (used) draw.Text(post, cfg_.posts[s.post].name, kUsedColor, 8.0f, -8.0f);
  }

  // Trails: truth and Kalman estimate.
  if (trail_true_.size() >= 2)
    draw.Polyline(trail_true_.items(), Color{0.1f, 0.1f, 0.1f, 0.8f}, 1.5f, true);
  if (trail_kf_.size() >= 2)
    draw.Polyline(trail_kf_.items(), kKalmanColor.WithAlpha(0.8f), 1.2f, true);

  // Estimates: dead reckoning, raw fix, classical (limit + mean), Kalman with its 3σ ellipse.
  draw.Circle(dr_.pose().p(), 0.05, kDrColor.WithAlpha(0.5f), kDrColor);
  if (has_raw_) draw.Cross(raw_, 0.15, kRawColor);
  if (classic_.has_value())
    draw.Circle(classic_.value(), 0.05, kClassicColor.WithAlpha(0.6f), kClassicColor);
  draw.CovarianceEllipse(kf_.position(), kf_.axis_x().P(), 0.0, kf_.axis_y().P(), 3.0,
                         kKalmanColor);
  draw.Circle(kf_.position(), 0.06, kKalmanColor.WithAlpha(0.6f), kKalmanColor);

  // The true robot, with its steered front wheel.
  const Pose2 pose = robot_->pose();
  const Color body = PaletteColor(cfg_.body.color_index);
  DrawRobotBody(draw, pose, robot_->outline(), body, robot_->name());
  const Vec2 wheel = pose.ToWorld(drive_->front_wheel());
  const double a = pose.theta - drive_->steer_angle();
  const Vec2 d{0.12 * std::cos(a), 0.12 * std::sin(a)};
  draw.Segment(wheel - d, wheel + d, Color{0.1f, 0.1f, 0.1f, 1.0f}, 4.0f);
}

void InspectionExperiment::Bounds(Vec2& lo, Vec2& hi) const {
  lo = {1e300, 1e300};
  hi = {-1e300, -1e300};
  auto grow = [&](const Vec2& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  };
  for (const Vec2& p : route_.Polyline(0.5)) grow(p);
  for (const auto& p : cfg_.posts) grow(p.position);
  grow(robot_->pose().p());
  lo = lo - Vec2{1.0, 1.0};
  hi = hi + Vec2{1.0, 1.0};
}

std::vector<FigureSpec> InspectionExperiment::Figures() const {
  std::vector<FigureSpec> figs = InspectionTimeFigures(cfg_.route_start.x, cfg_.drive.servo_center);
  figs.push_back(InspectionTrajectoryFigure(route_, cfg_.posts));
  AddInspectionMembershipFigures(fuzzy_.variables(), figs);
  return figs;
}

std::vector<TableSpec> InspectionExperiment::Tables() const {
  TableSpec rules;
  rules.title = "Fuzzy rules (firing strength of the last control step)";
  rules.header = {"#", "s", "Δφ", "u1", "u2", "u3", "strength"};
  int k = 1;
  for (const auto& r : fuzzy_.rules()) {
    if (r.s.empty() && r.dphi.empty()) {
      rules.rows.push_back(
          {std::to_string(k++), r.text, "", "", "", "", Sprintf("%.3f", r.strength)});
    } else {
      rules.rows.push_back(
          {std::to_string(k++), r.s, r.dphi, r.u1, r.u2, r.u3, Sprintf("%.3f", r.strength)});
    }
    rules.row_strength.push_back(std::clamp(r.strength, 0.0, 1.0));
  }
  return {rules};
}

}  // namespace formsim::sim::inspection
