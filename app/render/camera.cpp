#include "app/render/camera.hpp"

#include <algorithm>
#include <cmath>

namespace formsim::app {

bool FocusSet::RobotBox(Vec2& lo, Vec2& hi) const {
  if (bodies.empty()) return false;
  lo = {1e300, 1e300};
  hi = {-1e300, -1e300};
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const double r = i < radii.size() ? radii[i] : 0.0;
    lo = {std::min(lo.x, bodies[i].x - r), std::min(lo.y, bodies[i].y - r)};
    hi = {std::max(hi.x, bodies[i].x + r), std::max(hi.y, bodies[i].y + r)};
  }
  return true;
}

FocusSet FocusOf(const sim::Experiment& exp, double trail_seconds) {
  FocusSet f;
  FocusOf(exp, trail_seconds, &f);
  return f;
}

bool FocusSet::TrailBox(Vec2& lo, Vec2& hi) const {
  if (trail_box) {
    lo = trail_lo, hi = trail_hi;
    return true;
  }
  bool any = false;
  for (const Vec2& p : trails) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    lo = any ? Vec2{std::min(lo.x, p.x), std::min(lo.y, p.y)} : p;
    hi = any ? Vec2{std::max(hi.x, p.x), std::max(hi.y, p.y)} : p;
    any = true;
  }
  return any;
}

void FocusOf(const sim::Experiment& exp, double trail_seconds, FocusSet* out, FocusTrails trails) {
  out->bodies.clear();
  out->radii.clear();
  out->trails.clear();
  out->trail_box = false;
  // Zero seconds of trail: the robots alone.
  const bool points = trails == FocusTrails::kPoints;
  exp.FocusPoints(out->bodies, out->radii, out->trails, points ? trail_seconds : 0.0);
  if (trails == FocusTrails::kBox)
    out->trail_box = exp.TrailBox(trail_seconds, out->trail_lo, out->trail_hi);
}

double FormationFraction(const View& view, const FocusSet& focus) {
  Vec2 lo, hi;
  if (!focus.RobotBox(lo, hi)) return 0.0;
  const double shorter = std::max(1.0f, std::min(view.width(), view.height()));
  return std::max(hi.x - lo.x, hi.y - lo.y) * view.scale / shorter;
}

View PresentationCamera::Target(const View& view, const FocusSet& focus, float top_inset) const {
  View t = view;
  Vec2 rlo, rhi;
  if (!focus.RobotBox(rlo, rhi)) return t;
  Vec2 lo = rlo, hi = rhi, tlo, thi;
  if (focus.TrailBox(tlo, thi)) {
    lo = {std::min(lo.x, tlo.x), std::min(lo.y, tlo.y)};
    hi = {std::max(hi.x, thi.x), std::max(hi.y, thi.y)};
  }
  const double shorter = std::max(1.0f, std::min(view.width(), view.height()));
  const double margin = opt_.margin_fraction * shorter;
  const double aw = std::max(10.0, view.width() - 2 * margin);
  const double inset = std::clamp(static_cast<double>(top_inset), 0.0, 0.5 * view.height());
  const double ah = std::max(10.0, view.height() - 2 * margin - inset);
  const double rw = std::max(1e-3, rhi.x - rlo.x), rh = std::max(1e-3, rhi.y - rlo.y);
  // Everything framed; at least the wanted fill of the robots; never more than the robots fit.
  const double all = std::min(aw / std::max(1e-3, hi.x - lo.x), ah / std::max(1e-3, hi.y - lo.y));
  const double fill = opt_.min_fill * shorter / std::max(rw, rh);
  const double robots_fit = std::min(aw / rw, ah / rh);
  t.scale = std::clamp(std::min(std::max(all, fill), robots_fit), 1e-2, 1e5);
  // Centred on the robots, moved towards the centre of everything framed by at most half the
  // room the robots leave: when the trails do not fit, the robots stay well inside the view
  // (not pressed against its edge) and more of their trail shows behind them.
  const double hw = 0.5 * aw / t.scale, hh = 0.5 * ah / t.scale;
  auto place = [](double rlo, double rhi, double alo, double ahi, double half) {
    const double rc = 0.5 * (rlo + rhi), room = std::max(0.0, half - 0.5 * (rhi - rlo));
    const double towards = 0.5 * (alo + ahi) - rc;
    const double limit = (ahi - alo) <= 2 * half ? room : 0.5 * room;
    return rc + std::clamp(towards, -limit, limit);
  };
  // The framed box sits in the middle of the room below the inset: half of it lower on screen.
  t.center = {place(rlo.x, rhi.x, lo.x, hi.x, hw),
              place(rlo.y, rhi.y, lo.y, hi.y, hh) + 0.5 * inset / t.scale};
  return t;
}

void PresentationCamera::Update(View& view, const FocusSet& focus, double smoothing,
                                float top_inset) {
  if (suspended_ || focus.empty()) return;
  const View t = Target(view, focus, top_inset);
  const double a = jump_ ? 1.0 : std::clamp(smoothing, 0.0, 1.0);
  jump_ = false;
  // The centre keeps up with moving robots (no lag at 2.5 m/s); the zoom eases.
  view.center = view.center + (t.center - view.center) * std::max(a, std::min(1.0, 0.5 + a));
  view.scale = std::exp(std::log(view.scale) + a * (std::log(t.scale) - std::log(view.scale)));
}

}  // namespace formsim::app
