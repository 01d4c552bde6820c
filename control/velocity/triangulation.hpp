#pragma once
/// \file Linear triangulation of a point landmark from bearing rays in the plane: the point
/// minimising the squared perpendicular distances to every ray. Used to initialise a landmark
/// once its rays are far enough apart (parallax) to fix its depth.

#include <vector>

#include "control/velocity/planar.hpp"

namespace formsim::control::velocity {

/// A bearing ray in the world frame: origin (camera centre) and direction angle.
struct BearingRay {
  Vec2d origin = Vec2d::Zero();
  double angle = 0.0;  ///< world direction, rad
};

struct TriangulationResult {
  bool ok = false;
  Vec2d point = Vec2d::Zero();
  double parallax = 0.0;    ///< largest angle between two rays, rad
  const char* reason = "";  ///< why it failed
};

/// Intersects the rays. Fails with fewer than two rays, a parallax below `min_parallax`, a point
/// behind any ray origin (depth < `min_depth`) or farther than `max_range` from the last origin.
TriangulationResult Triangulate(const std::vector<BearingRay>& rays, double min_parallax,
                                double min_depth, double max_range);

}  // namespace formsim::control::velocity
