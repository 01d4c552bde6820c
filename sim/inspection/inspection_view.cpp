// Drawing, figures and tables of the inspection experiment.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "control/inspection/paper_frame.hpp"
#include "sim/inspection/inspection_experiment.hpp"

namespace formsim::sim {

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

std::string Fmt(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
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
    draw.Polyline(trail_true_, Color{0.1f, 0.1f, 0.1f, 0.8f}, 1.5f, true);
  if (trail_kf_.size() >= 2) draw.Polyline(trail_kf_, kKalmanColor.WithAlpha(0.8f), 1.2f, true);

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
  std::vector<FigureSpec> figs;
  auto series = [](const std::string& label, const std::string& column, int color,
                   bool markers = false, bool dashed = false) {
    SeriesSpec s;
    s.label = label;
    s.column = column;
    s.color_index = color;
    s.markers_only = markers;
    s.dashed = dashed;
    return s;
  };
  {
    FigureSpec f;
    f.id = "fig8_x";
    f.title =
        "Fig. 8: X on the first straight (centre line X = " + Fmt("%.1f", cfg_.route_start.x) +
        " m): raw / limit+mean / Kalman / ideal";
    f.y_label = "X [m]";
    f.series = {series("raw fix", "s1_raw_x", 5, true), series("limit + mean", "s1_classic_x", 6),
                series("Kalman", "s1_kf_x", 4),
                series("ideal (true)", "s1_true_x", 0, false, true)};
    f.reference_lines = {cfg_.route_start.x};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "fig9_y";
    f.title = "Fig. 9: Y on the first straight: raw / limit+mean / Kalman / ideal";
    f.y_label = "Y [m]";
    f.series = {series("raw fix", "s1_raw_y", 5, true), series("limit + mean", "s1_classic_y", 6),
                series("Kalman", "s1_kf_y", 4),
                series("ideal (true)", "s1_true_y", 0, false, true)};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "x_error";
    f.title = "X error (estimate − truth), whole route";
    f.y_label = "ΔX [m]";
    f.series = {series("raw fix", "raw_ex", 5, true), series("limit + mean", "classic_ex", 6),
                series("Kalman", "kf_ex", 4)};
    f.reference_lines = {0.0};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "y_error";
    f.title = "Y error (estimate − truth), whole route";
    f.y_label = "ΔY [m]";
    f.series = {series("raw fix", "raw_ey", 5, true), series("limit + mean", "classic_ey", 6),
                series("Kalman", "kf_ey", 4)};
    f.reference_lines = {0.0};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "localisation_error";
    f.title = "Position error of each estimate";
    f.y_label = "error [m]";
    f.series = {series("raw fix", "err_raw", 5, true), series("limit + mean", "err_classic", 6),
                series("Kalman", "err_kf", 4)};
    f.reference_lines = {0.1};  // the paper's ~10 cm
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "dead_reckoning_error";
    f.title = "Dead reckoning alone (eq. 1, encoders only) drifts";
    f.y_label = "error [m]";
    f.series = {series("dead reckoning", "err_dr", 7), series("Kalman", "err_kf", 4)};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "lateral_offset";
    f.title = "Lateral offset s from the route (true, and as the controller saw it)";
    f.y_label = "s [m]";
    f.series = {series("true", "s_true", 0), series("controller input", "s_ctrl", 4, false, true)};
    f.reference_lines = {0.0};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "heading_error";
    f.title = "Heading error Δφ (true, and as the controller saw it)";
    f.y_label = "Δφ [deg]";
    f.series = {series("true", "dphi_true_deg", 0),
                series("controller input", "dphi_ctrl_deg", 4, false, true)};
    f.reference_lines = {0.0};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "fuzzy_speed_levels";
    f.title = "Drive motor levels u1 (left), u2 (right)";
    f.y_label = "level";
    f.series = {series("u1 left", "u1", 1), series("u2 right", "u2", 2),
                series("u1 fuzzy", "fz_u1", 1, false, true),
                series("u2 fuzzy", "fz_u2", 2, false, true)};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "fuzzy_steering";
    f.title = "Steering servo command u3 (360 = straight, > 360 right)";
    f.y_label = "u3";
    f.series = {series("u3 sent", "u3", 3), series("u3 fuzzy", "fz_u3", 4, false, true)};
    f.reference_lines = {cfg_.drive.servo_center};
    figs.push_back(f);
  }
  {
    FigureSpec f;
    f.id = "trajectory";
    f.title = "Route and trajectories";
    f.x_label = "X [m]";
    f.y_label = "Y [m]";
    f.equal_aspect = true;
    SeriesSpec route;
    route.label = "route";
    route.color_index = 7;
    route.dashed = true;
    for (const Vec2& p : route_.Polyline(0.2)) {
      route.x.push_back(p.x);
      route.y.push_back(p.y);
    }
    SeriesSpec posts;
    posts.label = "posts";
    posts.color_index = 6;
    posts.markers_only = true;
    for (const auto& p : cfg_.posts) {
      posts.x.push_back(p.position.x);
      posts.y.push_back(p.position.y);
    }
    SeriesSpec truth = series("true", "true_y", 0);
    truth.x_column = "true_x";
    SeriesSpec kf = series("Kalman", "kf_y", 4);
    kf.x_column = "kf_x";
    SeriesSpec raw = series("raw fix", "raw_y", 5, true);
    raw.x_column = "raw_x";
    f.series = {route, posts, raw, truth, kf};
    figs.push_back(f);
  }
  // Membership functions with the current value marked.
  const char* const titles[] = {"s: lateral offset [m]", "Δφ: heading error [deg]",
                                "u1: left drive level", "u2: right drive level",
                                "u3: steering servo command"};
  int vi = 0;
  for (const auto& v : fuzzy_.variables()) {
    FigureSpec f;
    f.id = "mf_" + v.name;
    f.title = std::string("Membership functions, ") + titles[std::min(vi++, 4)];
    f.x_label = v.name == "dphi" ? "Δφ [deg]" : v.name == "s" ? "s [m]" : v.name;
    f.y_label = "membership";
    int color = 0;
    for (const auto& term : v.terms) {
      SeriesSpec s;
      s.label = v.input ? term.name : term.name + " (" + Fmt("%.4g", term.centroid) + ")";
      s.x = term.x;
      s.y = term.y;
      s.color_index = color++;
      f.series.push_back(s);
    }
    f.marker_x = v.value;
    figs.push_back(f);
  }
  return figs;
}

std::vector<TableSpec> InspectionExperiment::Tables() const {
  std::vector<TableSpec> tables;
  TableSpec rules;
  rules.title = "Fuzzy rules (firing strength of the last control step)";
  rules.header = {"#", "s", "Δφ", "u1", "u2", "u3", "strength"};
  int k = 1;
  for (const auto& r : fuzzy_.rules()) {
    if (r.s.empty() && r.dphi.empty()) {
      rules.rows.push_back({std::to_string(k++), r.text, "", "", "", "", Fmt("%.3f", r.strength)});
    } else {
      rules.rows.push_back(
          {std::to_string(k++), r.s, r.dphi, r.u1, r.u2, r.u3, Fmt("%.3f", r.strength)});
    }
    rules.row_strength.push_back(std::clamp(r.strength, 0.0, 1.0));
  }
  tables.push_back(rules);

  TableSpec loc;
  loc.title = "Localisation";
  loc.header = {"item", "value"};
  loc.rows.push_back({"scans", std::to_string(scans_)});
  loc.rows.push_back({"fixes", std::to_string(fixes_)});
  for (int s = 1; s < 5; ++s)
    loc.rows.push_back({std::string("no fix: ") + ins::ToString(static_cast<ins::FixStatus>(s)),
                        std::to_string(status_counts_[s])});
  loc.rows.push_back({"posts identified now", std::to_string(detection_.sightings.size())});
  loc.rows.push_back({"Kalman fixes gated", std::to_string(kf_gated_)});
  loc.rows.push_back({"limit filter rejections", std::to_string(classic_.rejected())});
  loc.rows.push_back({"heading rejections", std::to_string(heading_.rejected())});
  loc.rows.push_back({"RMS error raw / classical / Kalman [m]",
                      Fmt("%.3f", err_raw_.rms()) + " / " + Fmt("%.3f", err_classic_.rms()) +
                          " / " + Fmt("%.3f", err_kf_.rms())});
  tables.push_back(loc);
  return tables;
}

}  // namespace formsim::sim
