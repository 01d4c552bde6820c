#pragma once
/// \file Paths made of straight lines and circular arcs, joined head to tail with a continuous
/// tangent, and the nearest-point projection used by the path tracker (paper 002, Fig. 3).
///
///   Path p({0, 0, 0});  p.AddLine(2.0);  p.AddArc(0.5, kPi / 2);  p.AddLine(1.0);
///   PathProjection pr = p.Project({1.0, 0.1});   // s = 1, cross_track = +0.1 (left of path)

#include <stdexcept>
#include <string>
#include <vector>

#include "control/common/geometry.hpp"

namespace formsim::control::agv {

/// A point on the path with its tangent heading [rad] and signed curvature [1/m] (> 0 turns
/// left, counter-clockwise).
struct PathPoint {
  Vec2 p;
  double heading = 0.0;
  double curvature = 0.0;
};

/// One piece of a path: a straight line (curvature 0) or a circular arc of constant curvature.
struct PathSegment {
  Vec2 start;
  double heading0 = 0.0;   ///< tangent heading at the start
  double length = 0.0;     ///< arc length, m
  double curvature = 0.0;  ///< 0: line; ±1/R: arc turning left (+) or right (-)
  double s0 = 0.0;         ///< arc length of the path at this segment's start

  bool is_arc() const { return curvature != 0.0; }
  /// The point `ds` metres along this segment (ds in [0, length]).
  PathPoint At(double ds) const;
  /// Arc-length parameter in [a, b] of the point nearest to q.
  double Nearest(Vec2 q, double a, double b) const;
};

/// The nearest path point to a query point, and the errors relative to it.
struct PathProjection {
  double s = 0.0;            ///< arc length of the nearest point (unwrapped for ProjectNear)
  PathPoint ref;             ///< the nearest point
  double cross_track = 0.0;  ///< signed distance from the path, > 0 left of the direction of travel
  int segment = -1;
};

/// An invalid path description (too large corner radius, empty path, open loop declared closed).
class PathError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class Path {
 public:
  Path() = default;
  /// An empty path starting at `start` (position and initial tangent heading).
  explicit Path(const Pose2& start) : start_(start) {}

  /// Appends a straight line of `length` metres (> 0).
  void AddLine(double length);
  /// Appends an arc of `radius` metres (> 0) turning by `angle` radians (> 0 left, < 0 right).
  void AddArc(double radius, double angle);
  /// Declares the path a closed loop. Throws PathError when the end does not meet the start
  /// (position within 1 mm, tangent within 1e-3 rad).
  void Close();

  /// The paper's experiment path: a length × width rectangle (axis aligned, centred on `center`)
  /// with rounded corners of `corner_radius`, closed, starting at the middle of the bottom side,
  /// heading +x when counter-clockwise, -x when clockwise.
  static Path RoundedRectangle(Vec2 center, double length, double width, double corner_radius,
                               bool counter_clockwise = true);
  /// A polyline through `points` with each corner replaced by a tangent arc of `corner_radius`
  /// (> 0; collinear points need no arc). Closed polylines also round the corner at the first
  /// point and start at the middle of the first edge. Throws PathError when an arc does not fit.
  static Path Polyline(const std::vector<Vec2>& points, double corner_radius, bool closed);

  bool empty() const { return segments_.empty(); }
  bool closed() const { return closed_; }
  double length() const { return length_; }
  const Pose2& start() const { return start_; }
  const std::vector<PathSegment>& segments() const { return segments_; }

  /// The point at arc length s; closed paths wrap s, open paths clamp it to [0, length].
  PathPoint At(double s) const;
  /// Global nearest point (s in [0, length)).
  PathProjection Project(Vec2 q) const;
  /// Nearest point whose (unwrapped) arc length lies within `window` of `s_hint`: keeps a
  /// tracker on its own stretch where the path passes close to itself, and counts laps on a
  /// closed path (s grows past `length`).
  PathProjection ProjectNear(Vec2 q, double s_hint, double window) const;
  /// Points every `step` metres (and at every segment end), for drawing and figures.
  std::vector<Vec2> Sample(double step) const;

 private:
  PathPoint EndPoint() const;
  Pose2 start_;
  std::vector<PathSegment> segments_;
  double length_ = 0.0;
  bool closed_ = false;
};

}  // namespace formsim::control::agv
