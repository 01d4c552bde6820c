#include "control/inspection/route.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"
#include "control/inspection/paper_frame.hpp"

namespace formsim::control::inspection {

void Route::AddLine(const Vec2& a, const Vec2& b) {
  RouteSegment s;
  s.kind = RouteSegment::Kind::kLine;
  s.a = a;
  s.b = b;
  s.length = (b - a).Norm();
  s.start_progress = length();
  segments_.push_back(s);
}

void Route::AddArc(const Vec2& centre, double radius, double start_az, double sweep) {
  RouteSegment s;
  s.kind = RouteSegment::Kind::kArc;
  s.centre = centre;
  s.radius = radius;
  s.start_az = start_az;
  s.sweep = sweep;
  s.length = std::abs(sweep) * radius;
  s.start_progress = length();
  s.a = centre + AzimuthDirection(start_az) * radius;
  s.b = centre + AzimuthDirection(start_az + sweep) * radius;
  segments_.push_back(s);
}

Route Route::UShape(const Vec2& start, double straight_length, double radius, bool turn_right) {
  Route r;
  const Vec2 top = start + Vec2{0.0, straight_length};
  const double side = turn_right ? 1.0 : -1.0;
  const Vec2 centre = top + Vec2{side * radius, 0.0};
  r.AddLine(start, top);
  // The top of the first straight lies left of a right-turn centre (azimuth −90°).
  r.AddArc(centre, radius, -side * kPi / 2.0, side * kPi);
  r.AddLine(top + Vec2{2.0 * side * radius, 0.0}, start + Vec2{2.0 * side * radius, 0.0});
  return r;
}

double Route::length() const {
  return segments_.empty() ? 0.0 : segments_.back().start_progress + segments_.back().length;
}

RouteProjection Route::ProjectOn(int index, const Vec2& p, double* along) const {
  const RouteSegment& s = segments_[index];
  RouteProjection pr;
  pr.segment = index;
  if (s.kind == RouteSegment::Kind::kLine) {
    const Vec2 d = s.b - s.a;
    const Vec2 e = s.length > 0.0 ? d * (1.0 / s.length) : Vec2{0.0, 1.0};
    const Vec2 right{e.y, -e.x};  // e turned clockwise by 90°
    *along = (p - s.a).Dot(e);
    const double t = std::clamp(*along, 0.0, s.length);
    pr.closest = s.a + e * t;
    pr.lateral = (p - s.a).Dot(right);
    pr.tangent = Azimuth(e);
    pr.curvature = 0.0;
    pr.progress = s.start_progress + t;
    return pr;
  }
  const double dir = s.clockwise() ? 1.0 : -1.0;
  const double phi = Azimuth(p - s.centre);
  // Angle travelled from the start, in [0, 2π); points before the start come out near 2π and
  // are mapped to negative values (the half of the missing circle nearer the start).
  double u = WrapTo2Pi((phi - s.start_az) * dir);
  const double span = std::abs(s.sweep);
  if (u > span + 0.5 * (2.0 * kPi - span)) u -= 2.0 * kPi;
  *along = u * s.radius;
  const double uc = std::clamp(u, 0.0, span);
  const double phic = s.start_az + dir * uc;
  pr.closest = s.centre + AzimuthDirection(phic) * s.radius;
  const double r = (p - s.centre).Norm();
  pr.lateral = dir * (s.radius - r);
  pr.tangent = WrapToPi(phic + dir * kPi / 2.0);
  pr.curvature = dir / s.radius;
  pr.on_arc = true;
  pr.progress = s.start_progress + uc * s.radius;
  return pr;
}

RouteProjection Route::Project(const Vec2& p, int hint) const {
  RouteProjection pr;
  if (segments_.empty()) return pr;
  int i = std::clamp(hint, 0, static_cast<int>(segments_.size()) - 1);
  double along = 0.0;
  pr = ProjectOn(i, p, &along);
  // Move on while p is past the end of the current segment.
  while (along > segments_[i].length) {
    if (i + 1 >= static_cast<int>(segments_.size())) {
      pr.finished = true;
      break;
    }
    ++i;
    pr = ProjectOn(i, p, &along);
  }
  return pr;
}

std::vector<Vec2> Route::Polyline(double step) const {
  std::vector<Vec2> pts;
  if (!(step > 0.0)) step = 0.1;
  for (const RouteSegment& s : segments_) {
    const int n = std::max(1, static_cast<int>(std::ceil(s.length / step)));
    for (int k = pts.empty() ? 0 : 1; k <= n; ++k) {
      const double f = static_cast<double>(k) / n;
      if (s.kind == RouteSegment::Kind::kLine) {
        pts.push_back(s.a + (s.b - s.a) * f);
      } else {
        pts.push_back(s.centre + AzimuthDirection(s.start_az + s.sweep * f) * s.radius);
      }
    }
  }
  return pts;
}

}  // namespace formsim::control::inspection
