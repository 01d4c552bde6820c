#pragma once
/// \file Plain 2-D geometry types shared by control, sim and app (no Box2D, no Eigen).

#include <cmath>

namespace formsim {

/// A point or vector in metres, world frame unless said otherwise.
struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  Vec2 operator+(const Vec2& o) const { return {x + o.x, y + o.y}; }
  Vec2 operator-(const Vec2& o) const { return {x - o.x, y - o.y}; }
  Vec2 operator*(double s) const { return {x * s, y * s}; }
  double Dot(const Vec2& o) const { return x * o.x + y * o.y; }
  double Cross(const Vec2& o) const { return x * o.y - y * o.x; }
  double Norm() const { return std::hypot(x, y); }
};

/// A planar pose: position in metres, heading theta in radians from the world x axis (CCW).
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  Vec2 p() const { return {x, y}; }
  /// Maps a point from this pose's body frame to the world frame.
  Vec2 ToWorld(const Vec2& b) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * b.x - s * b.y, y + s * b.x + c * b.y};
  }
  /// Maps a world point into this pose's body frame.
  Vec2 ToBody(const Vec2& w) const {
    const double c = std::cos(theta), s = std::sin(theta), dx = w.x - x, dy = w.y - y;
    return {c * dx + s * dy, -s * dx + c * dy};
  }
};

}  // namespace formsim
