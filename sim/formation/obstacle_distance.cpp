#include "sim/formation/obstacle_distance.hpp"

#include <box2d/b2_distance.h>

#include <algorithm>

namespace formsim::sim::formation {
namespace {

// Distance from p to one child of a fixture's shape, with b2Distance against a one-vertex proxy.
double ChildDistance(const b2Fixture& f, int child, const b2Transform& xf, const b2Vec2& p, b2Vec2& nearest) {
  b2DistanceInput in;
  in.proxyA.Set(f.GetShape(), child);
  in.proxyB.Set(&p, 1, 0.0f);
  in.transformA = xf;
  in.transformB.SetIdentity();
  in.useRadii = true;
  b2SimplexCache cache;
  cache.count = 0;
  b2DistanceOutput out;
  b2Distance(&out, &cache, &in);
  nearest = out.pointA;
  return out.distance;
}

// Distance from p to one obstacle body (its nearest fixture child); `reach` < ∞ skips children
// whose boxes are farther.
double BodyDistance(const b2Body& body, const b2Vec2& p, double reach, b2Vec2& nearest) {
  double best = std::numeric_limits<double>::infinity();
  const b2Transform& xf = body.GetTransform();
  for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
    const b2Shape* shape = f->GetShape();
    for (int c = 0; c < shape->GetChildCount(); ++c) {
      b2AABB box;
      shape->ComputeAABB(&box, xf, c);
      const double dx = std::max({0.0, double(box.lowerBound.x - p.x), double(p.x - box.upperBound.x)});
      const double dy = std::max({0.0, double(box.lowerBound.y - p.y), double(p.y - box.upperBound.y)});
      if (dx * dx + dy * dy > reach * reach) continue;
      b2Vec2 q;
      const double d = ChildDistance(*f, c, xf, p, q);
      if (d < best) best = d, nearest = q;
    }
  }
  return best;
}

}  // namespace

ObstacleDistance NearestObstacle(const World& world, Vec2 p, double reach) {
  ObstacleDistance r;
  const b2Vec2 q(static_cast<float>(p.x), static_cast<float>(p.y));
  const auto& bodies = world.obstacle_bodies();
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    b2Vec2 nearest(0.0f, 0.0f);
    const double d = BodyDistance(*bodies[k], q, reach, nearest);
    if (d < r.distance) r = {d, {nearest.x, nearest.y}, static_cast<int>(k)};
  }
  return r;
}

double DistanceToObstacle(const World& world, int index, Vec2 p, Vec2* point) {
  const b2Vec2 q(static_cast<float>(p.x), static_cast<float>(p.y));
  b2Vec2 nearest(0, 0);
  const double d = BodyDistance(*world.obstacle_bodies()[static_cast<std::size_t>(index)], q,
                                std::numeric_limits<double>::infinity(), nearest);
  if (point != nullptr) *point = {nearest.x, nearest.y};
  return d;
}

}  // namespace formsim::sim::formation
