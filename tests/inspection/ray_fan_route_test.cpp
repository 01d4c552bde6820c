// The laser's ray casts (RayFan) hit exactly what World::RayCast hits on the inspection
// scenario's world: 720 beams of 20 m, like a scan, from points on and beside the U-route.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "sim/core/ray_fan.hpp"
#include "sim/core/rng.hpp"
#include "sim/session/session.hpp"

namespace formsim::sim {
namespace {

TEST(RayFan, SameHitsAsRayCastOnTheInspectionRoute) {
  Session s(std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/inspection_u_route.yaml",
            std::vector<Override>{});
  const World& world = s.exp().world();
  const Robot* robot = world.robots().front().get();
  Rng rng(11);
  int hits = 0;
  for (int i = 0; i < 40; ++i) {
    const Vec2 origin{rng.Uniform(-2.0, 14.0), rng.Uniform(-2.0, 20.0)};
    const RayFan fan(world, origin, 20.0, false, robot);
    EXPECT_GT(fan.candidates(), 0u);
    for (int k = 0; k < 720; ++k) {
      const double a = 2.0 * M_PI * (k + rng.Uniform()) / 720.0;
      const Vec2 to = origin + Vec2{std::cos(a), std::sin(a)} * 20.0;
      const RayHit want = world.RayCast(origin, to, false, robot);
      const RayHit got = fan.Cast(to);
      ASSERT_EQ(got.hit, want.hit) << "origin " << i << " beam " << k;
      if (!want.hit) continue;
      ++hits;
      ASSERT_EQ(std::memcmp(&got.distance, &want.distance, sizeof(double)), 0)
          << got.distance << " " << want.distance;
      ASSERT_EQ(got.body_name, want.body_name);
    }
  }
  EXPECT_GT(hits, 3000);  // posts and equipment: most origins see several
}

}  // namespace
}  // namespace formsim::sim
