// RayFan gives every ray the hit of World::RayCast bit for bit: on a world with every obstacle
// shape and robots (skipped or seen, one ignored), from origins inside and outside bodies (the
// inspection scenario's world: tests/inspection/ray_fan_route_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "sim/core/ray_fan.hpp"
#include "sim/core/rng.hpp"
#include "sim/core/world.hpp"

using namespace formsim;
using namespace formsim::sim;

namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Casts `rays` rays of length `range` in random directions from `origin` both ways; returns the
// number of hits (and fails on the first difference).
int CompareFan(const World& world, Vec2 origin, double range, bool robots, const Robot* ignore,
               Rng& rng, int rays) {
  const RayFan fan(world, origin, range, robots, ignore);
  int hits = 0;
  for (int k = 0; k < rays; ++k) {
    const double a = rng.Uniform(-M_PI, M_PI);
    // Some rays shorter than the range, a few exactly along the axes.
    const double len = k % 5 == 0 ? range * rng.Uniform() : range;
    const double dir = k % 97 == 0 ? M_PI * 0.5 * (k % 4) : a;
    const Vec2 to = origin + Vec2{std::cos(dir), std::sin(dir)} * len;
    const RayHit want = world.RayCast(origin, to, robots, ignore);
    const RayHit got = fan.Cast(to);
    EXPECT_EQ(got.hit, want.hit) << "ray " << k;
    if (got.hit != want.hit) return hits;
    if (!want.hit) continue;
    ++hits;
    EXPECT_TRUE(SameBits(got.distance, want.distance)) << got.distance << " " << want.distance;
    EXPECT_TRUE(SameBits(got.point.x, want.point.x) && SameBits(got.point.y, want.point.y));
    if (!SameBits(got.distance, want.distance)) return hits;
  }
  return hits;
}

TEST(RayFan, SameHitsAsRayCastForEveryShape) {
  World world;
  ObstacleDef box = DefaultObstacleDef();
  box.name = "box";
  box.pose = {3.0, 1.0, 0.4};
  box.half_x = 0.8;
  box.half_y = 0.3;
  world.CreateObstacle(box);
  ObstacleDef post = DefaultObstacleDef();
  post.shape = ObstacleDef::Shape::kCircle;
  for (int i = 0; i < 12; ++i) {
    post.name = "post" + std::to_string(i);
    post.pose = {-6.0 + 1.1 * i, -2.0 + 0.3 * (i % 3), 0.0};
    post.radius = 0.05 + 0.02 * (i % 4);
    world.CreateObstacle(post);
  }
  ObstacleDef poly = DefaultObstacleDef();
  poly.name = "poly";
  poly.shape = ObstacleDef::Shape::kPolygon;
  poly.pose = {-3.0, 3.0, 1.0};
  poly.vertices = {{-0.5, -0.4}, {0.6, -0.3}, {0.7, 0.4}, {0.0, 0.8}, {-0.6, 0.3}};
  world.CreateObstacle(poly);
  ObstacleDef wall = DefaultObstacleDef();
  wall.name = "wall";
  wall.shape = ObstacleDef::Shape::kWall;
  wall.vertices = {{-10.0, -5.0}, {10.0, -5.0}, {10.0, 6.0}, {-4.0, 8.0}};
  world.CreateObstacle(wall);
  RobotDef r = DefaultRobotDef();
  r.name = "R1";
  r.pose = {0.5, 0.2, 0.3};
  Robot& r1 = world.CreateRobot(r);
  r.name = "R2";
  r.shape = RobotDef::Shape::kCircle;
  r.pose = {1.5, -1.0, 0.0};
  world.CreateRobot(r);

  Rng rng(7);
  int hits = 0;
  // From the robot (ignored), from open floor, from inside the box and the polygon, from far out.
  for (const Vec2 origin : {Vec2{0.5, 0.2}, Vec2{-1.0, 1.5}, Vec2{3.0, 1.0}, Vec2{-3.0, 3.2},
                            Vec2{-20.0, 0.5}, Vec2{0.0, -4.9}})
    for (const bool robots : {false, true}) {
      hits += CompareFan(world, origin, 12.0, robots, &r1, rng, 700);
      hits += CompareFan(world, origin, 30.0, robots, nullptr, rng, 300);
    }
  EXPECT_GT(hits, 5000);  // most rays hit something: the comparison is not vacuous
  // A ray longer than the fan's range and a degenerate one go to the world's cast.
  const RayFan fan(world, {-1.0, 1.5}, 1.0);
  EXPECT_TRUE(fan.Cast({8.0, 1.5}).hit);
  EXPECT_FALSE(fan.Cast({-1.0, 1.5}).hit);
}

}  // namespace
