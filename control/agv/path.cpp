#include "control/agv/path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "control/common/angle.hpp"

namespace formsim::control::agv {
namespace {

Vec2 Dir(double heading) {
  return {std::cos(heading), std::sin(heading)};
}
Vec2 LeftNormal(double heading) {
  return {-std::sin(heading), std::cos(heading)};
}

}  // namespace

PathPoint PathSegment::At(double ds) const {
  if (!is_arc()) return {start + Dir(heading0) * ds, heading0, 0.0};
  // Arc: centre at start + n0 / κ; the point at heading h is centre + (sin h, -cos h) / κ.
  const Vec2 center = start + LeftNormal(heading0) * (1.0 / curvature);
  const double h = heading0 + curvature * ds;
  return {center + Vec2{std::sin(h), -std::cos(h)} * (1.0 / curvature), WrapToPi(h), curvature};
}

double PathSegment::Nearest(Vec2 q, double a, double b) const {
  a = std::clamp(a, 0.0, length);
  b = std::clamp(b, a, length);
  double ds;
  if (!is_arc()) {
    ds = (q - start).Dot(Dir(heading0));
  } else {
    const Vec2 center = start + LeftNormal(heading0) * (1.0 / curvature);
    const Vec2 d = q - center;
    if (d.Norm() < 1e-12) return a;  // the centre: every point is nearest, take the first
    // The radial direction of the point at heading h is h - π/2 (left turn) or h + π/2 (right).
    const double h_q = std::atan2(d.y, d.x) + (curvature > 0.0 ? 0.5 * kPi : -0.5 * kPi);
    const double h_mid = heading0 + curvature * 0.5 * length;
    ds = 0.5 * length + AngleDiff(h_q, h_mid) / curvature;
  }
  // Distance along a line or circle grows monotonically away from the free optimum, so the
  // restricted optimum is the clamped one; compare with both ends anyway for arcs over π.
  double best = std::clamp(ds, a, b), best_d = (At(best).p - q).Norm();
  for (double c : {a, b}) {
    const double d = (At(c).p - q).Norm();
    if (d < best_d) best = c, best_d = d;
  }
  return best;
}

PathPoint Path::EndPoint() const {
  if (segments_.empty()) return {start_.p(), start_.theta, 0.0};
  const PathSegment& last = segments_.back();
  return last.At(last.length);
}

void Path::AddLine(double length) {
  if (closed_) throw PathError("cannot extend a closed path");
  if (!(length > 0.0) || !std::isfinite(length))
    throw PathError("line length must be > 0 (got " + std::to_string(length) + ")");
  const PathPoint e = EndPoint();
  segments_.push_back({e.p, e.heading, length, 0.0, length_});
  length_ += length;
}

void Path::AddArc(double radius, double angle) {
  if (closed_) throw PathError("cannot extend a closed path");
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw PathError("arc radius must be > 0 (got " + std::to_string(radius) + ")");
  if (angle == 0.0 || !std::isfinite(angle))
    throw PathError("arc angle must be non-zero (got " + std::to_string(angle) + ")");
  const PathPoint e = EndPoint();
  const double len = radius * std::abs(angle);
  segments_.push_back({e.p, e.heading, len, (angle > 0.0 ? 1.0 : -1.0) / radius, length_});
  length_ += len;
}

void Path::Close() {
  if (segments_.empty()) throw PathError("an empty path cannot be closed");
  const PathPoint e = EndPoint();
  const double gap = (e.p - start_.p()).Norm();
  const double turn = std::abs(AngleDiff(e.heading, start_.theta));
  if (gap > 1e-3 || turn > 1e-3) {
    std::ostringstream msg;
    msg << "path declared closed but its end (" << e.p.x << ", " << e.p.y << ") is " << gap
        << " m from its start and its tangent differs by " << turn << " rad";
    throw PathError(msg.str());
  }
  closed_ = true;
}

Path Path::RoundedRectangle(Vec2 c, double length, double width, double r, bool ccw) {
  if (!(length > 0.0) || !(width > 0.0))
    throw PathError("rounded rectangle needs length > 0 and width > 0");
  if (!(r > 0.0) || r > 0.5 * std::min(length, width))
    throw PathError("corner radius must be in (0, min(length, width)/2] (got " + std::to_string(r) +
                    ")");
  const double turn = ccw ? 0.5 * kPi : -0.5 * kPi;
  Path p({c.x, c.y - 0.5 * width, ccw ? 0.0 : kPi});
  // Half bottom side, then three full sides and the other half, a quarter arc at each corner;
  // straight pieces of zero length (r at its maximum) are skipped.
  const double half_x = 0.5 * length - r, side_y = width - 2.0 * r, side_x = length - 2.0 * r;
  const double sides[] = {half_x, side_y, side_x, side_y};
  for (double side : sides) {
    if (side > 1e-12) p.AddLine(side);
    p.AddArc(r, turn);
  }
  if (half_x > 1e-12) p.AddLine(half_x);
  p.Close();
  return p;
}

Path Path::Polyline(const std::vector<Vec2>& pts, double r, bool closed) {
  const int n = static_cast<int>(pts.size());
  if (n < 2 || (closed && n < 3))
    throw PathError(closed ? "a closed polyline needs at least 3 points"
                           : "a polyline needs at least 2 points");
  const int edges = closed ? n : n - 1;
  std::vector<double> heading(edges), len(edges);
  for (int i = 0; i < edges; ++i) {
    const Vec2 d = pts[(i + 1) % n] - pts[i];
    len[i] = d.Norm();
    if (len[i] < 1e-9)
      throw PathError("polyline points " + std::to_string(i) + " and " +
                      std::to_string((i + 1) % n) + " coincide");
    heading[i] = std::atan2(d.y, d.x);
  }
  // Corner k joins edge k-1 to edge k (corner 0 only on closed polylines). Its fillet takes
  // r·tan(|turn|/2) from each of the two edges.
  std::vector<double> turn(edges, 0.0), cut(edges, 0.0);
  for (int k = closed ? 0 : 1; k < edges; ++k) {
    turn[k] = AngleDiff(heading[k], heading[(k - 1 + edges) % edges]);
    if (std::abs(turn[k]) < 1e-9) continue;
    if (std::abs(turn[k]) > kPi - 1e-6)
      throw PathError("polyline reverses direction at point " + std::to_string(k));
    if (!(r > 0.0)) throw PathError("corner_radius must be > 0 for a polyline with corners");
    cut[k] = r * std::tan(0.5 * std::abs(turn[k]));
  }
  std::vector<double> straight(edges);
  for (int i = 0; i < edges; ++i) {
    const double in = cut[i], out = (closed || i + 1 < edges) ? cut[(i + 1) % edges] : 0.0;
    straight[i] = len[i] - in - out;
    if (straight[i] < -1e-9) {
      std::ostringstream msg;
      msg << "corner_radius " << r << " does not fit edge " << i << " (length " << len[i]
          << " m needs " << in + out << " m for its fillets)";
      throw PathError(msg.str());
    }
  }
  // Closed: start at the middle of edge 0's straight part; walk edges 1..n-1, then edge 0.
  const double start_along = closed ? cut[0] + 0.5 * straight[0] : 0.0;
  Path p({pts[0].x + std::cos(heading[0]) * start_along,
          pts[0].y + std::sin(heading[0]) * start_along, heading[0]});
  auto add_line = [&p](double l) {
    if (l > 1e-9) p.AddLine(l);
  };
  add_line(closed ? 0.5 * straight[0] : straight[0]);
  for (int i = 1; i < edges; ++i) {
    if (cut[i] > 0.0) p.AddArc(r, turn[i]);
    add_line(straight[i]);
  }
  if (closed) {
    if (cut[0] > 0.0) p.AddArc(r, turn[0]);
    add_line(0.5 * straight[0]);
    p.Close();
  }
  return p;
}

PathPoint Path::At(double s) const {
  if (segments_.empty()) return {start_.p(), start_.theta, 0.0};
  if (closed_) {
    s = std::fmod(s, length_);
    if (s < 0.0) s += length_;
  } else {
    s = std::clamp(s, 0.0, length_);
  }
  // Segments are few (a rectangle has 9), a linear scan is fine.
  for (const PathSegment& seg : segments_)
    if (s <= seg.s0 + seg.length) return seg.At(s - seg.s0);
  return segments_.back().At(segments_.back().length);
}

PathProjection Path::Project(Vec2 q) const {
  PathProjection best;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(segments_.size()); ++i) {
    const PathSegment& seg = segments_[i];
    const double ds = seg.Nearest(q, 0.0, seg.length);
    const PathPoint pt = seg.At(ds);
    const double d = (pt.p - q).Norm();
    if (d < best_d) {
      best_d = d;
      best.s = seg.s0 + ds;
      best.ref = pt;
      best.segment = i;
    }
  }
  if (closed_ && best.s >= length_) best.s -= length_;
  best.cross_track = (q - best.ref.p).Dot(LeftNormal(best.ref.heading));
  return best;
}

PathProjection Path::ProjectNear(Vec2 q, double s_hint, double window) const {
  if (segments_.empty()) return Project(q);
  const double lo = s_hint - window, hi = s_hint + window;
  // Copies of the loop at offsets k·length that overlap [lo, hi] (one copy for open paths).
  int k_min = 0, k_max = 0;
  if (closed_) {
    k_min = static_cast<int>(std::floor(lo / length_));
    k_max = static_cast<int>(std::floor(hi / length_));
  }
  PathProjection best;
  double best_d = std::numeric_limits<double>::infinity();
  for (int k = k_min; k <= k_max; ++k) {
    const double offset = k * length_;
    for (int i = 0; i < static_cast<int>(segments_.size()); ++i) {
      const PathSegment& seg = segments_[i];
      const double a = std::max(0.0, lo - offset - seg.s0);
      const double b = std::min(seg.length, hi - offset - seg.s0);
      if (a > b) continue;
      const double ds = seg.Nearest(q, a, b);
      const PathPoint pt = seg.At(ds);
      const double d = (pt.p - q).Norm();
      if (d < best_d) {
        best_d = d;
        best.s = offset + seg.s0 + ds;
        best.ref = pt;
        best.segment = i;
      }
    }
  }
  if (best.segment < 0) return Project(q);  // window entirely off an open path
  best.cross_track = (q - best.ref.p).Dot(LeftNormal(best.ref.heading));
  return best;
}

std::vector<Vec2> Path::Sample(double step) const {
  std::vector<Vec2> out;
  if (segments_.empty()) return out;
  step = std::max(step, 1e-3);
  out.push_back(segments_.front().At(0.0).p);
  for (const PathSegment& seg : segments_) {
    const int n = seg.is_arc() ? std::max(2, static_cast<int>(std::ceil(seg.length / step))) : 1;
    for (int j = 1; j <= n; ++j) out.push_back(seg.At(seg.length * j / n).p);
  }
  return out;
}

}  // namespace formsim::control::agv
