// Figures, tables and the scene drawing of the formation experiment.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/core/number_format.hpp"
#include "sim/formation/formation_experiment.hpp"

namespace formsim::sim::formation {
namespace {

using cf::FormationLaw;

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

  FigureSpec phi = TimeFigure("phi_error", "(b) Bearing error e_φ = φ_des − φ", "e_φ [rad]", {});
  FigureSpec dist = TimeFigure("distance_error", "(c) Distance errors e_l = l_des − l", "e_l [m]", {});
  FigureSpec alpha =
      TimeFigure("alpha_error", "(d) Heading differences e_α = θ_i − θ_j", "e_α [rad]", {});
  FigureSpec est =
      TimeFigure("estimation_error", "(f) Estimation error φ_est − φ with ±2σ (UKF)", "[rad]", {});
  for (FigureSpec* f : {&phi, &dist, &alpha, &est}) f->reference_lines = {0.0};
  int color = 0;
  const int c_t = recorder_.Column("t");
  for (std::size_t k = 0; k < n_links; ++k) {
    const Link& l = links_[k];
    const std::string& n = l.name;
    if (cfg_.robots[l.follower].node.law == FormationLaw::kLPhi)
      phi.series.push_back(Line("e_φ " + n, n + ".e_phi", color));
    dist.series.push_back(Line("e_l " + n, n + ".e_l", color));
    alpha.series.push_back(Line("α " + n, n + ".alpha", color));
    // The estimation figure shows every link whose UKF ran at some time of the run (the
    // estimator can be switched live).
    if (l.ever_ukf && recorder_.rows() > 0) {
      est.series.push_back(Line("φ_est − φ " + n, n + ".phi_est_err", color));
      // ±2σ bands as inline data from the recorded standard deviations.
      SeriesSpec hi = Line("±2σ " + n, "", color, true);
      SeriesSpec lo = Line("", "", color, true);
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
    ++color;
  }
  if (!phi.series.empty()) figs.push_back(phi);
  figs.push_back(dist);
  if (links_.size() > kManyLinks) {
    // Every link at once: the largest and the median distance error, and the l-φ bearing's.
    FigureSpec all = TimeFigure(
        "distance_error_all",
        Sprintf("(c) Distance errors over all %zu links: largest and median |e_l|", links_.size()),
        "|e| [m], [rad]", {});
    all.series.push_back(Line("max |e_l|", "links.max_abs_e_l", 0));
    all.series.push_back(Line("median |e_l|", "links.median_abs_e_l", 2));
    all.series.push_back(Line("max |e_φ| (l-φ links) [rad]", "links.max_abs_e_phi", 1, true));
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
  if (!est.series.empty()) figs.push_back(est);
  return figs;
}

Pose2 FormationExperiment::DesiredPose(int j) const {
  const FormationRobotDef& r = cfg_.robots[j];
  const Agent& a = agents_[j];
  const Pose2 p1 = agents_[links_[a.links[0]].leader].robot->pose();
  const double L = cfg_.L;
  Vec2 m;
  if (r.node.law == FormationLaw::kLPhi) {
    const double b = p1.theta + r.node.phi_des;
    m = p1.p() + Vec2{std::cos(b), std::sin(b)} * r.node.l_des;
  } else {
    // The apex on the side the control point is on now (the law keeps it there).
    const Pose2 p2 = agents_[links_[a.links[1]].leader].robot->pose();
    const Vec2 mj = cf::ControlPoint(a.robot->pose(), L);
    const int side = (p2.p() - p1.p()).Cross(mj - p1.p()) >= 0.0 ? 1 : -1;
    if (!cf::TriangleApex(p1.p(), p2.p(), r.node.l_des, r.node.l2_des, side, m))
      return {std::nan(""), std::nan(""), 0.0};
  }
  // The ghost keeps the follower's current heading, so it coincides with the robot exactly when
  // the controlled outputs are at their desired values (α is not controlled).
  const double th = a.robot->pose().theta;
  return {m.x - L * std::cos(th), m.y - L * std::sin(th), th};
}

void FormationExperiment::DrawScene(DrawSink& draw) const {
  const double now = time();
  // Level of detail (a thousand robots stay interactive): how large things are on screen.
  double extent = 0.0;
  if (!agents_.empty())
    for (const Vec2& v : agents_[0].robot->outline()) extent = std::max(extent, v.Norm());
  const double body_px = PixelsOf(draw, 2.0 * extent);
  const bool many = agents_.size() > kManyRobots;
  // Only what is in view (with a margin for links and labels) is drawn.
  Vec2 lo, hi;
  draw.ViewBox(lo, hi);
  auto in_view = [&](Vec2 p) {
    return p.x >= lo.x - kViewMargin && p.x <= hi.x + kViewMargin && p.y >= lo.y - kViewMargin &&
           p.y <= hi.y + kViewMargin;
  };
  // Trails, oldest faded. Many robots: plain lines, and only every k-th robot's (the roots'
  // always), so that the paths stay readable and the view cheap; robots that are dots: only
  // the roots'.
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
    for (std::size_t k = 0; k < a.trail.size(); ++k) pts.push_back(a.trail[k]);
    pts.push_back(a.robot->pose().p());
    draw.Polyline(pts, PaletteColor(cfg_.robots[i].body.color_index).WithAlpha(0.8f), 2.0f, !many);
  }
  // Desired slots (ghosts, once they can be told from the robots) and leader → control point
  // links, once the robots are bodies.
  if (body_px >= 4.0) {
    for (std::size_t j = 0; j < agents_.size(); ++j) {
      const Agent& a = agents_[j];
      if (a.links.empty() || !in_view(a.robot->pose().p())) continue;
      const Color c = PaletteColor(cfg_.robots[j].body.color_index);
      const Pose2 g = body_px >= 8.0 ? DesiredPose(static_cast<int>(j)) : Pose2{std::nan(""), 0, 0};
      if (std::isfinite(g.x)) DrawRobotBody(draw, g, a.robot->outline(), c, "", true);
      const Vec2 m = cf::ControlPoint(a.robot->pose(), cfg_.L);
      for (int li : a.links)
        draw.Segment(agents_[links_[li].leader].robot->pose().p(), m,
                     Color{0.35f, 0.35f, 0.35f, 0.7f}, 1.0f);
    }
  }
  // Robots, then their control points and the link labels (l, and φ for l-φ links) on top.
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    const Agent& a = agents_[i];
    if (!in_view(a.robot->pose().p())) continue;
    DrawRobotBody(draw, a.robot->pose(), a.robot->outline(),
                  PaletteColor(cfg_.robots[i].body.color_index), a.robot->name());
  }
  if (body_px >= 6.0) {
    for (std::size_t j = 0; j < agents_.size(); ++j) {
      const Agent& a = agents_[j];
      if (a.links.empty() || !in_view(a.robot->pose().p())) continue;
      const Vec2 m = cf::ControlPoint(a.robot->pose(), cfg_.L);
      draw.Circle(m, 0.012, PaletteColor(cfg_.robots[j].body.color_index),
                  Color{0.1f, 0.1f, 0.1f, 1.0f});
      for (int li : a.links) {
        const Link& l = links_[li];
        // A label needs about 90 px of link to sit on without covering its neighbours.
        if (PixelsOf(draw, l.truth.l) < kLinkLabelPx) continue;
        const Vec2 mid = (agents_[l.leader].robot->pose().p() + m) * 0.5;
        std::string label = Sprintf("%.3f m", l.truth.l);
        if (cfg_.robots[l.follower].node.law == FormationLaw::kLPhi)
          label += Sprintf(", %.1f°", control::WrapTo2Pi(l.truth.phi) * 180 / control::kPi);
        draw.Text(mid, label, Color{0.25f, 0.25f, 0.25f, 0.9f}, 4.0f, 4.0f);
      }
    }
  }
  // Estimated poses with 2σ position ellipses. The link covariance P (over l, φ, α) is mapped
  // to the follower's position through the Jacobian J of p_j(l, φ, α) at the leader's true
  // pose: Σ = J P Jᵀ (first-order propagation; the leader's own uncertainty is not included).
  // Crosses and ellipses smaller than a few pixels are left out.
  for (std::size_t j = 0; j < agents_.size() && body_px >= 4.0; ++j) {
    const Agent& a = agents_[j];
    if (a.links.empty() || Mode(static_cast<int>(j)) == EstimatorMode::kTruth) continue;
    if (!in_view(a.robot->pose().p())) continue;
    const Link& l = links_[a.links[0]];
    const Color c = PaletteColor(cfg_.robots[j].body.color_index);
    const Pose2 e = EstimatedPose(a);
    if (PixelsOf(draw, 0.03) >= 4.0) draw.Cross(e.p(), 0.03, c);
    if (Mode(static_cast<int>(j)) == EstimatorMode::kUkf && l.filter_ready) {
      const Eigen::Matrix<double, 2, 3> J =
          cf::FollowerPositionJacobian(agents_[l.leader].robot->pose(), l.used, cfg_.L);
      const Eigen::Matrix2d S = J * l.filter->cov() * J.transpose();
      // The ellipse's long axis, 2 × 2σ: sqrt of the largest eigenvalue of S.
      const double tr = 0.5 * (S(0, 0) + S(1, 1)), det = S.determinant();
      const double major = 4.0 * std::sqrt(std::max(0.0, tr + std::sqrt(std::max(0.0, tr * tr - det))));
      if (!many || PixelsOf(draw, major) >= 3.0)
        draw.CovarianceEllipse(e.p(), S(0, 0), S(0, 1), S(1, 1), 2.0, c);
    }
  }
  // Flashes for recent saturations, collisions, singularities and filter faults.
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
      }
  }
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

}  // namespace formsim::sim::formation
