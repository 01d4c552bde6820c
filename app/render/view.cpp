#include "app/render/view.hpp"

#include <algorithm>
#include <cmath>

namespace formsim::app {

void View::Fit(Vec2 lo, Vec2 hi, float margin_px) {
  const double w = std::max(1e-3, hi.x - lo.x), h = std::max(1e-3, hi.y - lo.y);
  const double avail_w = std::max(10.0, static_cast<double>(width()) - 2 * margin_px);
  const double avail_h = std::max(10.0, static_cast<double>(height()) - 2 * margin_px);
  scale = std::clamp(std::min(avail_w / w, avail_h / h), 1e-2, 1e5);
  center = {0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)};
}

void View::ZoomAt(ImVec2 screen, double factor) {
  const Vec2 before = ToWorld(screen);
  scale = std::clamp(scale * factor, 1e-2, 1e5);
  const Vec2 after = ToWorld(screen);
  center = center + (before - after);
}

void View::Pan(ImVec2 delta_px) {
  center.x -= delta_px.x / scale;
  center.y += delta_px.y / scale;
}

void AutoFit::Include(Vec2 lo, Vec2 hi) {
  if (!valid_) {
    lo_ = lo, hi_ = hi, valid_ = true;
    return;
  }
  lo_ = {std::min(lo_.x, lo.x), std::min(lo_.y, lo.y)};
  hi_ = {std::max(hi_.x, hi.x), std::max(hi_.y, hi.y)};
}

void AutoFit::Update(View& view, Vec2 lo, Vec2 hi, double smoothing) {
  if (!valid_) {
    lo_ = lo, hi_ = hi, valid_ = true;
    view.Fit(lo_, hi_);
    return;
  }
  if (mode_ == Mode::kGrow) {
    lo_ = {std::min(lo_.x, lo.x), std::min(lo_.y, lo.y)};
    hi_ = {std::max(hi_.x, hi.x), std::max(hi_.y, hi.y)};
  } else {
    lo_ = lo, hi_ = hi;
  }
  View target = view;
  target.Fit(lo_, hi_);
  const double a = std::clamp(smoothing, 0.0, 1.0);
  // Tracking moving robots: the centre follows closely (no lag at 2.5 m/s), the zoom smoothly.
  const double ac = mode_ == Mode::kTrack ? std::max(a, 0.6) : a;
  view.center = view.center + (target.center - view.center) * ac;
  view.scale = std::exp(std::log(view.scale) + a * (std::log(target.scale) - std::log(view.scale)));
}

}  // namespace formsim::app
