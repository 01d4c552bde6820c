// Figures, tables and the scene drawing of the formation experiment.
#include <algorithm>
#include <cmath>

#include "sim/core/number_format.hpp"
#include "sim/formation/formation_experiment.hpp"

namespace formsim::sim::formation {
namespace {

using cf::FormationLaw;
using cf::Twist;

// Plots stay readable: at most this many series of one kind per figure.
constexpr std::size_t kMaxSeries = FormationExperiment::kManyLinks;
// Seconds an event flash stays visible.
constexpr double kFlashSeconds = 1.0;
// The view (Bounds) covers the robots plus this margin, m.
constexpr double kBoundsMargin = 0.6;
// Level of detail: above kManyRobots robots, trails are drawn without fading for at most about
// kMaxTrails of them, and ellipses only when they span a few pixels; a link is labelled only
// when it spans kLinkLabelPx pixels.
constexpr std::size_t kManyRobots = 100;
constexpr std::size_t kMaxTrails = 50;
constexpr double kLinkLabelPx = 90.0;
// What lies this far outside the view is still drawn (links and labels reach in), m.
constexpr double kViewMargin = 1.0;


}  // namespace

std::vector<FigureSpec> FormationExperiment::Figures() const {
  std::vector<FigureSpec> figs;
  const std::size_t n_robots = std::min(agents_.size(), kMaxSeries);
  const std::size_t n_links = std::min(links_.size(), kMaxSeries);

  FigureSpec traj = PlaneFigure("trajectories", "(a) Robot trajectories", {});
  for (std::size_t i = 0; i < n_robots; ++i) {
    const std::string& n = agents_[i].robot->name();
    traj.series.push_back(Path(n, n + ".x", n + ".y", cfg_.robots[i].body.color_index));
  }
  figs.push_back(traj);

  FigureSpec phi =
      TimeFigure("phi_error", "(b) Bearing error e_{φ} = φ_{des} − φ", "e_{φ} [rad]", {});
  FigureSpec dist =
      TimeFigure("distance_error", "(c) Distance errors e_{l} = l_{des} − l", "e_{l} [m]", {});
  FigureSpec alpha =
      TimeFigure("alpha_error", "(d) Heading differences e_{α} = θ_{i} − θ_{j}", "e_{α} [rad]", {});
  FigureSpec est = TimeFigure("estimation_error", "(f) Estimation error φ_{est} − φ with ±2σ (UKF)",
                              "φ_{est} − φ [rad]", {});
  for (FigureSpec* f : {&phi, &dist, &alpha, &est}) f->reference_lines = {0.0};
  int color = 0;
  for (std::size_t k = 0; k < n_links; ++k) {
    const Link& l = links_[k];
    const std::string& n = l.name;
    if (cfg_.robots[l.follower].node.law == FormationLaw::kLPhi)
      phi.series.push_back(Line("e_{φ} " + n, n + ".e_phi", color));
    dist.series.push_back(Line("e_{l} " + n, n + ".e_l", color));
    alpha.series.push_back(Line("α " + n, n + ".alpha", color));
    // The estimation figure shows every link whose UKF ran at some time of the run (the
    // estimator can be switched live).
    if (l.ever_ukf && recorder_.rows() > 0) AddEstimationSeries(est, n, color);
    ++color;
  }
  if (!phi.series.empty()) figs.push_back(phi);
  figs.push_back(dist);
  if (links_.size() > kManyLinks) {
    // Every link at once: the largest and the median distance error, and the l-φ bearing's.
    FigureSpec all =
        TimeFigure("distance_error_all",
                   Sprintf("(c) Distance errors over all %zu links: largest and median |e_{l}|",
                           links_.size()),
                   "|e| [m], [rad]", {});
    all.series.push_back(Line("max |e_{l}|", "links.max_abs_e_l", 0));
    all.series.push_back(Line("median |e_{l}|", "links.median_abs_e_l", 2));
    all.series.push_back(Line("max |e_{φ}| (l-φ links) [rad]", "links.max_abs_e_phi", 1, true));
    all.reference_lines = {0.0};
    figs.push_back(all);
  }
  figs.push_back(alpha);

  FigureSpec v = TimeFigure("follower_v", "(e) Follower speeds v", "v [m/s]", {});
  FigureSpec w = TimeFigure("follower_w", "(e) Follower turn rates ω", "ω [rad/s]", {});
  for (std::size_t i = 0; i < n_robots; ++i) {
    const std::string& n = agents_[i].robot->name();
    // The root leader is drawn dashed, as the reference the followers are compared with.
    const bool root = cfg_.robots[i].node.law == FormationLaw::kRoot;
    const int c = cfg_.robots[i].body.color_index;
    v.series.push_back(Line("v " + n, n + ".v_cmd", c, root));
    w.series.push_back(Line("ω " + n, n + ".w_cmd", c, root));
  }
  figs.push_back(v);
  figs.push_back(w);
  AddSwitchingFigures(figs, n_robots);
  if (!est.series.empty()) figs.push_back(est);
  return figs;
}

void FormationExperiment::AddEstimationSeries(FigureSpec& est, const std::string& n,
                                              int color) const {
  est.series.push_back(Line("φ_{est} − φ " + n, n + ".phi_est_err", color));
  // ±2σ bands as inline data from the recorded standard deviations.
  SeriesSpec hi = Line("±2σ " + n, "", color, true);
  SeriesSpec lo = Line("", "", color, true);
  const int c_t = recorder_.Column("t");
  const int c_sd = recorder_.Column(n + ".phi_sd");
  for (std::size_t r = 0; r < recorder_.rows(); ++r) {
    const double t = recorder_.At(r, c_t), s2 = 2.0 * recorder_.At(r, c_sd);
    hi.x.push_back(t);
    hi.y.push_back(s2);
    lo.x.push_back(t);
    lo.y.push_back(-s2);
  }
  est.series.push_back(std::move(hi));
  est.series.push_back(std::move(lo));
}

void FormationExperiment::AddSwitchingFigures(std::vector<FigureSpec>& figs,
                                              std::size_t n_robots) const {
  if (cfg_.switching.enabled() || cfg_.avoidance.present) {
    // Switching and avoidance: the formation error against the 1e-2 tolerance, and each
    // follower's distance to the nearest obstacle against the safety distance.
    FigureSpec fe =
        TimeFigure("formation_error",
                   "Formation error: largest |e_{l}| [m], |e_{φ}| [rad] (followers not avoiding)",
                   "error", {});
    fe.series.push_back(Line("formation error", "formation.error", 0));
    fe.reference_lines = {0.0, kRecoveredError};
    figs.push_back(fe);
  }
  if (cfg_.avoidance.present) {
    FigureSpec od = TimeFigure(
        "obstacle_distance",
        Sprintf("Control point to nearest obstacle (capped at %g m); safety distance %g m",
                AvoidanceReach(), cfg_.avoidance.def.safety_distance),
        "d [m]", {});
    for (std::size_t i = 0; i < n_robots; ++i) {
      if (cfg_.robots[i].node.law == FormationLaw::kRoot) continue;
      const std::string& n = agents_[i].robot->name();
      od.series.push_back(Line("d " + n, n + ".obstacle_d", cfg_.robots[i].body.color_index));
    }
    od.reference_lines = {cfg_.avoidance.def.safety_distance};
    figs.push_back(od);
  }
}

Pose2 FormationExperiment::DesiredPose(int j) const {
  const FormationRobotDef& r = cfg_.robots[j];
  const Agent& a = agents_[j];
  const Pose2 p1 = agents_[links_[a.links[0]].leader].robot->pose();
  const double L = cfg_.L;
  const cf::SlotValues& s = slots_[static_cast<std::size_t>(j)];
  Vec2 m;
  if (r.node.law == FormationLaw::kLPhi) {
    const double b = p1.theta + s.phi_des;
    m = p1.p() + Vec2{std::cos(b), std::sin(b)} * s.l_des;
  } else {
    // The apex on the side the control point is on now (the law keeps it there).
    const Pose2 p2 = agents_[links_[a.links[1]].leader].robot->pose();
    const Vec2 mj = cf::ControlPoint(a.robot->pose(), L);
    const int side = (p2.p() - p1.p()).Cross(mj - p1.p()) >= 0.0 ? 1 : -1;
    if (!cf::TriangleApex(p1.p(), p2.p(), s.l_des, s.l2_des, side, m))
      return {std::nan(""), std::nan(""), 0.0};
  }
  // The ghost keeps the follower's current heading, so it coincides with the robot exactly when
  // the controlled outputs are at their desired values (α is not controlled).
  const double th = a.robot->pose().theta;
  return {m.x - L * std::cos(th), m.y - L * std::sin(th), th};
}

void FormationExperiment::DrawScene(DrawSink& draw) const {
  // Level of detail (a thousand robots stay interactive): how large things are on screen.
  double extent = 0.0;
  if (!agents_.empty())
    for (const Vec2& v : agents_[0].robot->outline()) extent = std::max(extent, v.Norm());
  const double body_px = PixelsOf(draw, 2.0 * extent);
  // Only what is in view (with a margin for links and labels) is drawn.
  Vec2 lo, hi;
  draw.ViewBox(lo, hi);
  const std::function<bool(Vec2)> in_view = [&](Vec2 p) {
    return p.x >= lo.x - kViewMargin && p.x <= hi.x + kViewMargin && p.y >= lo.y - kViewMargin &&
           p.y <= hi.y + kViewMargin;
  };
  DrawTrails(draw, body_px);
  DrawSlotsAndLinks(draw, body_px, in_view);
  // Robots, then their control points and the link labels (l, and φ for l-φ links) on top.
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    const Agent& a = agents_[i];
    if (!in_view(a.robot->pose().p())) continue;
    DrawRobotBody(draw, a.robot->pose(), a.robot->outline(),
                  PaletteColor(cfg_.robots[i].body.color_index), a.robot->name());
    draw.Legend(LegendMark::kBody, PaletteColor(cfg_.robots[i].body.color_index),
                "robot (arrow: heading)");
  }
  DrawControlPointsAndLinkLabels(draw, body_px, in_view);
  DrawLawTags(draw, body_px, in_view);
  DrawEstimatedPoses(draw, body_px, in_view);
  DrawEventFlashes(draw);
  DrawLawOverlays(draw, body_px, in_view);
}

void FormationExperiment::DrawTrails(DrawSink& draw, double body_px) const {
  // Trails, oldest faded. Many robots: plain lines, and only every k-th robot's (the roots'
  // always), so that the paths stay readable and the view cheap; robots that are dots: only
  // the roots'.
  const bool many = agents_.size() > kManyRobots;
  std::size_t trail_every = many ? (agents_.size() + kMaxTrails - 1) / kMaxTrails : 1;
  // Coprime with the palette's ten colours, so the trails drawn do not all share one.
  while (trail_every > 1 && (trail_every % 2 == 0 || trail_every % 5 == 0)) ++trail_every;
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    const Agent& a = agents_[i];
    if (a.trail.size() < 2) continue;
    const bool root = a.links.empty();
    if (!root && (body_px < 2.0 || i % trail_every != 0)) continue;
    std::vector<Vec2> pts;
    pts.reserve(a.trail.size() + 1);
    a.trail.AppendTo(pts);
    pts.push_back(a.robot->pose().p());
    draw.Polyline(pts, PaletteColor(cfg_.robots[i].body.color_index).WithAlpha(0.8f), 2.0f, !many);
    draw.Legend(LegendMark::kTrail, PaletteColor(cfg_.robots[i].body.color_index),
                "trail (path so far)");
  }
}

void FormationExperiment::DrawSlotsAndLinks(DrawSink& draw, double body_px,
                                            const std::function<bool(Vec2)>& in_view) const {
  // Desired slots (ghosts, once they can be told from the robots) and leader → control point
  // links, once the robots are bodies.
  const bool show_slots = draw.Shows("slots"), show_links = draw.Shows("links");
  const Color link_ink{0.35f, 0.35f, 0.35f, 0.7f};
  if (!(body_px >= 4.0 && (show_slots || show_links))) return;
  for (std::size_t j = 0; j < agents_.size(); ++j) {
    const Agent& a = agents_[j];
    if (a.links.empty() || !in_view(a.robot->pose().p())) continue;
    const Color c = PaletteColor(cfg_.robots[j].body.color_index);
    const Pose2 g =
        show_slots && body_px >= 8.0 ? DesiredPose(static_cast<int>(j)) : Pose2{std::nan(""), 0, 0};
    if (std::isfinite(g.x)) {
      DrawRobotBody(draw, g, a.robot->outline(), c, "", true);
      draw.Legend(LegendMark::kGhost, c, "desired slot (ghost)");
    }
    if (!show_links) continue;
    const Vec2 m = cf::ControlPoint(a.robot->pose(), cfg_.L);
    for (int li : a.links)
      draw.Segment(agents_[links_[li].leader].robot->pose().p(), m, link_ink, 1.0f);
    draw.Legend(LegendMark::kLine, link_ink, "link: leader -> control point M");
  }
}

void FormationExperiment::DrawControlPointsAndLinkLabels(
    DrawSink& draw, double body_px, const std::function<bool(Vec2)>& in_view) const {
  const bool show_m = draw.Shows("control_points"), show_links = draw.Shows("links");
  if (!(body_px >= 6.0 && (show_m || show_links))) return;
  for (std::size_t j = 0; j < agents_.size(); ++j) {
    const Agent& a = agents_[j];
    if (a.links.empty() || !in_view(a.robot->pose().p())) continue;
    const Vec2 m = cf::ControlPoint(a.robot->pose(), cfg_.L);
    if (show_m) {
      draw.Circle(m, 0.012, PaletteColor(cfg_.robots[j].body.color_index),
                  Color{0.1f, 0.1f, 0.1f, 1.0f});
      draw.Legend(LegendMark::kDot, PaletteColor(cfg_.robots[j].body.color_index),
                  "control point M (L ahead of the axle)");
    }
    if (!show_links) continue;
    for (int li : a.links) {
      const Link& l = links_[li];
      // A label needs about 90 px of link to sit on without covering its neighbours.
      if (PixelsOf(draw, l.truth.l) < kLinkLabelPx) continue;
      const Vec2 mid = (agents_[l.leader].robot->pose().p() + m) * 0.5;
      std::string label = Sprintf("%.3f m", l.truth.l);
      if (cfg_.robots[l.follower].node.law == FormationLaw::kLPhi)
        label += ", " + AngleLabel(draw, control::WrapTo2Pi(l.truth.phi));
      draw.Label(mid, label, Color{0.25f, 0.25f, 0.25f, 0.9f}, LabelRole::kLink, 4.0f, 4.0f);
    }
  }
}

void FormationExperiment::DrawLawTags(DrawSink& draw, double body_px,
                                      const std::function<bool(Vec2)>& in_view) const {
  // Avoidance and switching: each follower's active law under its name and, while it avoids,
  // its virtual leader (the obstacle's nearest point) joined to its control point.
  if (!((cfg_.avoidance.present || cfg_.switching.enabled()) && body_px >= 8.0)) return;
  const Color avoid_c{0.9f, 0.45f, 0.0f, 1.0f};
  // The law's tag sits just below the body (the name is above it).
  const float tag_dy = static_cast<float>(0.5 * body_px + 4.0);
  for (std::size_t j = 0; j < agents_.size(); ++j) {
    const Agent& a = agents_[j];
    const FormationRobotDef& r = cfg_.robots[j];
    if (a.links.empty() || !in_view(a.robot->pose().p())) continue;
    const std::string& leader = agents_[links_[a.links[0]].leader].robot->name();
    if (a.avoiding) {
      const Vec2 m = cf::ControlPoint(a.robot->pose(), cfg_.L);
      draw.Segment(m, a.near.point, avoid_c, 2.0f);
      draw.Circle(a.near.point, 0.03, avoid_c, Color{0.2f, 0.1f, 0.0f, 1.0f});
      // The law's tag before the leader's label (a label overlapping an earlier one is left
      // out, and the tag matters more).
      draw.Text(a.robot->pose().p(), "l-l: " + leader + " + obstacle", avoid_c, -8.0f, tag_dy);
      draw.Text(a.near.point, "virtual leader", avoid_c, 6.0f, 6.0f);
    } else {
      draw.Text(a.robot->pose().p(), r.node.law == FormationLaw::kLPhi ? "l-φ" : "l-l",
                Color{0.3f, 0.3f, 0.3f, 0.9f}, -8.0f, tag_dy);
    }
  }
}

void FormationExperiment::DrawEstimatedPoses(DrawSink& draw, double body_px,
                                             const std::function<bool(Vec2)>& in_view) const {
  // Estimated poses with 2σ position ellipses. The link covariance P (over l, φ, α) is mapped
  // to the follower's position through the Jacobian J of p_j(l, φ, α) at the leader's true
  // pose: Σ = J P Jᵀ (first-order propagation; the leader's own uncertainty is not included).
  // Crosses and ellipses smaller than a few pixels are left out.
  const bool many = agents_.size() > kManyRobots;
  for (std::size_t j = 0; j < agents_.size() && body_px >= 4.0 && draw.Shows("covariance"); ++j) {
    const Agent& a = agents_[j];
    if (a.links.empty() || Mode(static_cast<int>(j)) == EstimatorMode::kTruth) continue;
    if (!in_view(a.robot->pose().p())) continue;
    const Link& l = links_[a.links[0]];
    const Color c = PaletteColor(cfg_.robots[j].body.color_index);
    const Pose2 e = EstimatedPose(a);
    if (PixelsOf(draw, 0.03) >= 4.0) {
      draw.Cross(e.p(), 0.03, c);
      draw.Legend(LegendMark::kCross, c, "estimated position (from the link estimate)");
    }
    if (Mode(static_cast<int>(j)) == EstimatorMode::kUkf && l.filter_ready) {
      const Eigen::Matrix<double, 2, 3> J =
          cf::FollowerPositionJacobian(agents_[l.leader].robot->pose(), l.used, cfg_.L);
      const Eigen::Matrix2d S = J * l.filter->cov() * J.transpose();
      // The ellipse's long axis, 2 × 2σ: sqrt of the largest eigenvalue of S.
      const double tr = 0.5 * (S(0, 0) + S(1, 1)), det = S.determinant();
      const double major =
          4.0 * std::sqrt(std::max(0.0, tr + std::sqrt(std::max(0.0, tr * tr - det))));
      if (!many || PixelsOf(draw, major) >= 3.0) {
        draw.CovarianceEllipse(e.p(), S(0, 0), S(0, 1), S(1, 1), 2.0, c);
        draw.Legend(LegendMark::kEllipse, c, "UKF 2σ position ellipse");
      }
    }
  }
}

void FormationExperiment::DrawEventFlashes(DrawSink& draw) const {
  // Flashes for recent saturations, collisions, singularities and filter faults.
  const double now = time();
  const auto& events = events_.recent();
  for (std::size_t k = events.size(); k-- > 0;) {
    const Event* it = &events[k];
    const double age = (now - it->time) / kFlashSeconds;
    if (age > 1.0) break;
    if (age < 0.0) continue;
    const Color c = it->kind == "collision"  ? Color{0.85f, 0.1f, 0.1f, 1}
                    : it->kind == "singular" ? Color{0.6f, 0.1f, 0.7f, 1}
                                             : Color{0.95f, 0.55f, 0.0f, 1};
    // The event's last robot is the one it concerns (follower of a singular triangle).
    std::string name = it->robots.substr(it->robots.rfind(',') + 1);
    for (const Agent& a : agents_)
      if (a.robot->name() == name) {
        // A ring just around the body, so it marks the robot without hiding its neighbours.
        double extent = 0.0;
        for (const Vec2& v : a.robot->outline()) extent = std::max(extent, v.Norm());
        draw.Flash(a.robot->pose().p(), extent + 0.02, c, static_cast<float>(age));
        draw.Legend(LegendMark::kRing, c, "event: " + it->kind);
      }
  }
}

namespace {

// An arc of radius r about c from angle a0 to a1 (rad, counter-clockwise by the shorter way).
std::vector<Vec2> Arc(Vec2 c, double r, double a0, double a1) {
  const double sweep = control::WrapToPi(a1 - a0);
  const int n = std::max(4, static_cast<int>(std::abs(sweep) / 0.08));
  std::vector<Vec2> pts;
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + sweep * k / n;
    pts.push_back(c + Vec2{std::cos(a), std::sin(a)} * r);
  }
  return pts;
}

// An arrow from a to b with a head of `head` metres.
void Arrow(DrawSink& draw, Vec2 a, Vec2 b, Color c, float px, double head) {
  const Vec2 d = b - a;
  const double n = d.Norm();
  if (!(n > 1e-9)) return;
  draw.Segment(a, b, c, px);
  const Vec2 u = d * (1.0 / n), v{-u.y, u.x};
  const double h = std::min(head, 0.5 * n);
  draw.Segment(b, b - u * h + v * (0.5 * h), c, px);
  draw.Segment(b, b - u * h - v * (0.5 * h), c, px);
}

// Green when the l-l determinant is comfortable, through orange to red at the singular line.
Color SingularInk(double abs_sin, double threshold) {
  const double t = std::clamp((abs_sin - threshold) / std::max(0.5 - threshold, 1e-6), 0.0, 1.0);
  return t > 0.5 ? Color{static_cast<float>(0.9 * (1 - t) * 2), 0.6f, 0.2f, 1}
                 : Color{0.9f, static_cast<float>(0.1 + t), 0.1f, 1};
}


}  // namespace

void FormationExperiment::DrawLawOverlays(DrawSink& draw, double body_px,
                                          const std::function<bool(Vec2)>& in_view) const {
  if (body_px < 6.0) return;
  if (draw.Shows("graph")) DrawFormationGraph(draw, in_view);
  // Which overlays, asked once for every robot (a thousand a frame).
  const bool measured = draw.Shows("measured"), errors = draw.Shows("errors"),
             triangles = draw.Shows("triangles"), velocity = draw.Shows("velocity");
  if (!measured && !errors && !triangles && !velocity) return;
  for (std::size_t j = 0; j < agents_.size(); ++j) {
    const Agent& a = agents_[j];
    if (a.links.empty() || !in_view(a.robot->pose().p())) continue;
    const Vec2 m = cf::ControlPoint(a.robot->pose(), cfg_.L);
    if (measured) DrawMeasuredLinks(draw, j, m);
    if (errors) DrawErrorVector(draw, j, m);
    if (triangles && cfg_.robots[j].node.law == FormationLaw::kLL) DrawSingularTriangle(draw, a, m);
    if (velocity) DrawCommandSplit(draw, j, m);
  }
}

void FormationExperiment::DrawFormationGraph(DrawSink& draw,
                                             const std::function<bool(Vec2)>& in_view) const {
  // Formation graph: an arrow from each leader to each follower, with the law on the edge.
  const Color g{0.35f, 0.2f, 0.6f, 0.9f};
  for (const Link& l : links_) {
    const Vec2 a = agents_[l.leader].robot->pose().p(), b = agents_[l.follower].robot->pose().p();
    if (!in_view(a) && !in_view(b)) continue;
    const Vec2 d = b - a;
    const double n = d.Norm();
    if (!(n > 0.1)) continue;
    const Vec2 u = d * (1.0 / n);
    Arrow(draw, a + u * 0.1, b - u * 0.1, g, 2.0f, 0.06);
    const bool lphi = cfg_.robots[l.follower].node.law == FormationLaw::kLPhi;
    draw.Label((a + b) * 0.5, lphi ? "l-φ" : "l-l", g, LabelRole::kLink, -14.0f, -16.0f);
  }
  if (!links_.empty()) draw.Legend(LegendMark::kArrow, g, "graph: leader -> follower (law)");
}

void FormationExperiment::DrawMeasuredLinks(DrawSink& draw, std::size_t j, Vec2 m) const {
  // Measured l and φ as the law sees them: an arc from the leader's heading to the bearing
  // of M (l-φ), labelled; the estimate's arc dashed-looking (faint) when an estimator runs.
  const Agent& a = agents_[j];
  const FormationRobotDef& r = cfg_.robots[j];
  const Color c = PaletteColor(r.body.color_index);
  const Color ink{0.2f, 0.2f, 0.2f, 0.95f};
  for (int li : a.links) {
    const Link& l = links_[li];
    const Pose2 pi = agents_[l.leader].robot->pose();
    const double rad = std::min(0.35 * l.truth.l, 0.25);
    draw.Segment(pi.p(), pi.p() + Vec2{std::cos(pi.theta), std::sin(pi.theta)} * (rad * 1.3), ink,
                 1.0f);
    if (r.node.law == FormationLaw::kLPhi) {
      const double half = pi.theta + 0.5 * l.truth.phi;
      draw.Polyline(Arc(pi.p(), rad, pi.theta, pi.theta + l.truth.phi), ink, 1.5f, false);
      draw.Text(pi.p() + Vec2{std::cos(half), std::sin(half)} * rad,
                "φ " + AngleLabel(draw, control::WrapTo2Pi(l.truth.phi)), ink, 4.0f, -6.0f);
    }
    // l as an arc of radius l about the leader through M.
    const double b = std::atan2(m.y - pi.y, m.x - pi.x);
    draw.Polyline(Arc(pi.p(), l.truth.l, b - 0.12, b + 0.12), ink, 1.5f, false);
    draw.Text(m, Sprintf("l %.3f m", l.truth.l), ink, 8.0f, 6.0f);
    if (Mode(static_cast<int>(j)) != EstimatorMode::kTruth) {
      const Color e = c.WithAlpha(0.6f);
      const double phi_est = cfg_.bearing == cf::BearingConvention::kDas ? l.used.phi : l.truth.phi;
      if (r.node.law == FormationLaw::kLPhi)
        draw.Polyline(Arc(pi.p(), rad * 0.8, pi.theta, pi.theta + phi_est), e, 1.5f, false);
      draw.Polyline(Arc(pi.p(), l.used.l, b - 0.08, b + 0.08), e, 3.0f, false);
      draw.Text(m, Sprintf("l est %.3f m", l.used.l), e, 8.0f, 22.0f);
      draw.Legend(LegendMark::kArc, e, "estimated l (and φ) used by the law");
    }
  }
  draw.Legend(LegendMark::kArc, ink, "measured φ (from leader heading) and l");
}

void FormationExperiment::DrawErrorVector(DrawSink& draw, std::size_t j, Vec2 m) const {
  // Error vector: from M to where M should be.
  const Pose2 g = DesiredPose(static_cast<int>(j));
  if (!std::isfinite(g.x)) return;
  const Vec2 md = cf::ControlPoint(g, cfg_.L);
  const Color e{0.85f, 0.3f, 0.0f, 1.0f};
  Arrow(draw, m, md, e, 2.0f, 0.03);
  const double err = (md - m).Norm();
  if (err > 1e-4)
    draw.Text(md, err >= 0.01 ? Sprintf("%.1f cm", err * 100) : Sprintf("%.1f mm", err * 1000), e,
              6.0f, -8.0f);
  draw.Legend(LegendMark::kArrow, e, "error vector M -> desired M");
}

void FormationExperiment::DrawSingularTriangle(DrawSink& draw, const Agent& a, Vec2 m) const {
  // l-l: the triangle of the two leaders and M, and the singular line through the leaders in a
  // colour from green (|sin| comfortable) to red (at the threshold and below).
  const Vec2 p1 = agents_[links_[a.links[0]].leader].robot->pose().p();
  const Vec2 p2 = agents_[links_[a.links[1]].leader].robot->pose().p();
  const double s = std::abs(a.sin_ll);
  const Color col = SingularInk(s, cfg_.singular_threshold);
  draw.Polygon({p1, p2, m}, col.WithAlpha(0.08f), col.WithAlpha(0.8f));
  const Vec2 d = p2 - p1;
  const double n = d.Norm();
  if (n > 1e-6) {
    const Vec2 u = d * (1.0 / n);
    draw.Segment(p1 - u * 0.3, p2 + u * 0.3, col.WithAlpha(0.9f), 2.5f);
  }
  draw.Text(m, Sprintf("|sin| %.2f", s), col, 8.0f, -22.0f);
  draw.Legend(LegendMark::kLine, col, "l-l triangle, singular line (red: |sin| -> 0)");
}

void FormationExperiment::DrawCommandSplit(DrawSink& draw, std::size_t j, Vec2 m) const {
  // The command split: the control point's velocity from the leaders' motion alone
  // (feed-forward, errors zero) and what the error terms add (feedback), as far as M goes in 0.1 s.
  const Agent& a = agents_[j];
  const double L = cfg_.L;
  const Pose2 pj = a.robot->pose();
  Twist ff;
  if (cfg_.robots[j].node.law == FormationLaw::kLPhi) {
    cf::LPhiPrepared p = a.lphi;
    p.e1 = p.e2 = 0;
    ff = cf::FinishLPhi(p, agents_[links_[a.links[0]].leader].cmd, L);
  } else {
    cf::LLPrepared p = a.ll;
    p.e1 = p.e2 = 0;
    ff = cf::FinishLL(p, agents_[links_[a.links[0]].leader].cmd,
                      agents_[links_[a.links[1]].leader].cmd, L)
             .cmd;
  }
  auto mdot = [&](const Twist& t) {
    return Vec2{t.v * std::cos(pj.theta) - L * t.w * std::sin(pj.theta),
                t.v * std::sin(pj.theta) + L * t.w * std::cos(pj.theta)};
  };
  constexpr double kSeconds = 0.1;
  const Vec2 vff = mdot(ff) * kSeconds, vfb = (mdot(a.cmd) - mdot(ff)) * kSeconds;
  const Color cf_ink{0.1f, 0.45f, 0.85f, 1}, cb_ink{0.85f, 0.1f, 0.45f, 1};
  Arrow(draw, m, m + vff, cf_ink, 2.0f, 0.03);
  Arrow(draw, m + vff, m + vff + vfb, cb_ink, 2.0f, 0.03);
  draw.Legend(LegendMark::kArrow, cf_ink, "velocity of M: feed-forward (x 0.1 s)");
  draw.Legend(LegendMark::kArrow, cb_ink, "velocity of M: feedback (x 0.1 s)");
}

void FormationExperiment::Bounds(Vec2& lo, Vec2& hi) const {
  // A camera on the formation: the robots with a margin, centred on them (not on their trails),
  // so a video follows the robots at a scale where they, their ghosts and ellipses are readable;
  // figure (a) shows the whole trajectories.
  lo = {1e300, 1e300};
  hi = {-1e300, -1e300};
  for (const Agent& a : agents_) {
    const Vec2 p = a.robot->pose().p();
    lo = {std::min(lo.x, p.x - kBoundsMargin), std::min(lo.y, p.y - kBoundsMargin)};
    hi = {std::max(hi.x, p.x + kBoundsMargin), std::max(hi.y, p.y + kBoundsMargin)};
  }
}

void FormationExperiment::FocusPoints(std::vector<Vec2>& bodies, std::vector<double>& radii,
                                      std::vector<Vec2>& trails, double seconds) const {
  Experiment::FocusPoints(bodies, radii, trails, seconds);
  // A trail point is pushed every trail_every steps: the last `seconds` are its last n points.
  const double per_point = dt() * cfg_.trail_every;
  const std::size_t n = per_point > 0 ? static_cast<std::size_t>(seconds / per_point) : 0;
  // Reserved at once: a thousand robots' trails are tens of thousands of points.
  std::size_t count = trails.size();
  for (const Agent& a : agents_) count += std::min(n, a.trail.size());
  trails.reserve(count);
  for (const Agent& a : agents_)
    a.trail.AppendTo(trails, a.trail.size() > n ? a.trail.size() - n : 0);
}

bool FormationExperiment::TrailBox(double seconds, Vec2& lo, Vec2& hi) const {
  const double per_point = dt() * cfg_.trail_every;
  const std::size_t n = per_point > 0 ? static_cast<std::size_t>(seconds / per_point) : 0;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Agent& a : agents_)
    a.trail.ForEachRun(a.trail.size() > n ? a.trail.size() - n : 0,
                       [&](const Vec2* p, std::size_t count) {
                         for (std::size_t k = 0; k < count; ++k) {
                           if (!std::isfinite(p[k].x) || !std::isfinite(p[k].y)) continue;
                           x0 = std::min(x0, p[k].x), y0 = std::min(y0, p[k].y);
                           x1 = std::max(x1, p[k].x), y1 = std::max(y1, p[k].y);
                         }
                       });
  if (!(x0 <= x1)) return false;
  lo = {x0, y0}, hi = {x1, y1};
  return true;
}

}  // namespace formsim::sim::formation
