#pragma once
/// \file The inspection route: straights and circular turns (paper Fig. 7, a U of two straights
/// joined by a turn around a known centre), and the projection of a position onto it that gives
/// the fuzzy controller's inputs: lateral offset s and the path direction (for Δφ).
/// Paper convention: azimuths from +Y towards +X; s > 0 to the right of the direction of travel;
/// a clockwise turn (centre on the right) has positive curvature.

#include <vector>

#include "control/common/geometry.hpp"

namespace formsim::control::inspection {

struct RouteSegment {
  enum class Kind { kLine, kArc } kind = Kind::kLine;
  Vec2 a, b;                    ///< line: start and end
  Vec2 centre;                  ///< arc: centre
  double radius = 0.0;          ///< arc radius, m
  double start_az = 0.0;        ///< arc: azimuth of the start point seen from the centre
  double sweep = 0.0;           ///< arc: swept angle, > 0 clockwise (|sweep| < 2π)
  double length = 0.0;          ///< m
  double start_progress = 0.0;  ///< arc length from the route start to this segment, m
  bool clockwise() const { return sweep > 0.0; }
};

/// Where a point is relative to the route.
struct RouteProjection {
  int segment = 0;
  double progress = 0.0;   ///< arc length from the route start to the closest point, m
  double lateral = 0.0;    ///< s: signed offset, > 0 right of the direction of travel, m
  double tangent = 0.0;    ///< azimuth of the direction of travel at the closest point, rad
  double curvature = 0.0;  ///< 1/m, > 0 clockwise
  Vec2 closest;
  bool on_arc = false;
  bool finished = false;  ///< beyond the end of the last segment
};

class Route {
 public:
  void AddLine(const Vec2& a, const Vec2& b);
  void AddArc(const Vec2& centre, double radius, double start_az, double sweep);
  /// The U of Fig. 7: a straight from `start` along +Y of `straight_length`, a half turn of
  /// `radius` to the right (centre at start.x + radius) or left, and the straight back.
  static Route UShape(const Vec2& start, double straight_length, double radius, bool turn_right);

  double length() const;
  bool empty() const { return segments_.empty(); }
  const std::vector<RouteSegment>& segments() const { return segments_; }

  /// Projects p onto the route, starting the search at segment `hint` (the segment of the
  /// previous projection), so progress is monotonic along the U even where straights are
  /// parallel: the next segment is taken once p passes the end of the current one.
  RouteProjection Project(const Vec2& p, int hint = 0) const;
  /// Points every `step` metres along the route (for drawing).
  std::vector<Vec2> Polyline(double step) const;

 private:
  RouteProjection ProjectOn(int index, const Vec2& p, double* along) const;
  std::vector<RouteSegment> segments_;
};

}  // namespace formsim::control::inspection
