#pragma once
/// \file Distances from a point to the world's obstacles, measured against their real Box2D
/// shapes with b2Distance (GJK; polygon skins included), for obstacle avoidance. Read-only:
/// safe to call from several threads at once.

#include <limits>

#include "sim/core/world.hpp"

namespace formsim::sim::formation {

/// The nearest obstacle to a point.
struct ObstacleDistance {
  double distance = std::numeric_limits<double>::infinity();  ///< m (0 inside an obstacle)
  Vec2 point;        ///< nearest point on the obstacle
  int obstacle = -1;  ///< index into World::obstacles(), −1 when none within reach
};

/// The nearest obstacle to p among those whose bounding boxes lie within `reach` of p.
ObstacleDistance NearestObstacle(const World& world, Vec2 p, double reach);

/// Distance from p to obstacle `index` (its nearest point in `point` when not null).
double DistanceToObstacle(const World& world, int index, Vec2 p, Vec2* point = nullptr);

}  // namespace formsim::sim::formation
