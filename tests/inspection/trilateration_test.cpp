// Eq. 2-4 of the inspection paper on exact (noise-free) measurements, and the "no fix" cases.
#include "control/inspection/trilateration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/inspection/paper_frame.hpp"
#include "control/inspection/route.hpp"

namespace ins = formsim::control::inspection;
using formsim::Vec2;
using formsim::control::AngleDiff;

namespace {

// What a perfect scanner at (position, heading) reports for a post.
ins::PostSighting See(const Vec2& position, double heading, const Vec2& post, int id = 0) {
  ins::PostSighting s;
  s.post = id;
  s.position = post;
  s.range = (post - position).Norm();
  s.bearing = formsim::control::WrapToPi(ins::Azimuth(post - position) - heading);
  return s;
}

}  // namespace

TEST(Trilateration, CirclesIntersectAndMiss) {
  const auto two = ins::IntersectCircles({0, 0}, 5.0, {8, 0}, 5.0, 0.0);
  ASSERT_EQ(two.count, 2);
  EXPECT_NEAR(two.a.x, 4.0, 1e-12);
  EXPECT_NEAR(std::abs(two.a.y), 3.0, 1e-12);
  EXPECT_NEAR(two.a.y, -two.b.y, 1e-12);
  EXPECT_EQ(ins::IntersectCircles({0, 0}, 1.0, {8, 0}, 1.0, 0.5).count, 0);
  // A small miss (noise) resolves to the closest point between the circles.
  const auto near = ins::IntersectCircles({0, 0}, 3.95, {8, 0}, 3.95, 0.2);
  ASSERT_EQ(near.count, 1);
  EXPECT_NEAR(near.a.x, 4.0, 1e-12);
  EXPECT_NEAR(near.a.y, 0.0, 1e-12);
}

// Exact ranges and scan angles give the exact position (eq. 2) and heading (eq. 3) for every
// pose, both sides of the post line and both orders of the posts.
TEST(Trilateration, ExactOnNoiseFreeRanges) {
  const std::vector<Vec2> posts = {{2.1, 4.0}, {4.5, 6.5}, {2.1, 9.0}, {4.5, 12.0}, {-1.0, 3.0}};
  int fixes = 0;
  for (double x = -0.5; x <= 6.0; x += 0.7) {
    for (double y = 1.0; y <= 13.0; y += 1.3) {
      for (double heading = -3.0; heading <= 3.1; heading += 0.9) {
        const Vec2 p{x, y};
        for (std::size_t i = 0; i < posts.size(); ++i) {
          for (std::size_t j = 0; j < posts.size(); ++j) {
            if (i == j || (posts[i] - p).Norm() < 0.3 || (posts[j] - p).Norm() < 0.3) continue;
            const auto s1 = See(p, heading, posts[i]), s2 = See(p, heading, posts[j]);
            const ins::Fix fix = ins::TrilaterateTwoPosts(s1, s2);
            if (std::sin(fix.subtended) < std::sin(ins::Rad(20.0))) {
              EXPECT_EQ(fix.status, ins::FixStatus::kPoorGeometry);
              continue;
            }
            ASSERT_TRUE(fix.ok()) << ins::ToString(fix.status) << " at " << x << "," << y;
            EXPECT_NEAR(fix.position.x, x, 1e-9);
            EXPECT_NEAR(fix.position.y, y, 1e-9);
            EXPECT_NEAR(AngleDiff(fix.heading, heading), 0.0, 1e-9);
            EXPECT_NEAR(AngleDiff(ins::HeadingFromScanAngles(s1, s2), heading), 0.0, 1e-9);
            ++fixes;
          }
        }
      }
    }
  }
  EXPECT_GT(fixes, 1000);
}

TEST(Trilateration, NoFixWithFewerThanTwoPosts) {
  const Vec2 p{3.3, 5.0};
  EXPECT_EQ(ins::Localise({}).status, ins::FixStatus::kTooFewPosts);
  EXPECT_EQ(ins::Localise({See(p, 0.0, {2.0, 7.0})}).status, ins::FixStatus::kTooFewPosts);
  // Two sightings, but one beyond the usable range, is still fewer than two posts.
  ins::TrilaterationDef def;
  def.max_range = 5.0;
  EXPECT_EQ(ins::Localise({See(p, 0.0, {2.0, 7.0}), See(p, 0.0, {4.5, 14.0})}, def).status,
            ins::FixStatus::kTooFewPosts);
}

TEST(Trilateration, NoFixWhenPostsInLineWithTheRobot) {
  const Vec2 p{3.3, 5.0};
  // Both posts straight ahead: the circles touch, the side is unknown.
  const auto fix = ins::TrilaterateTwoPosts(See(p, 0.0, {3.3, 8.0}), See(p, 0.0, {3.3, 11.0}));
  EXPECT_EQ(fix.status, ins::FixStatus::kPoorGeometry);
  // Robot between two posts across the road.
  const auto across = ins::TrilaterateTwoPosts(See(p, 0.0, {2.1, 5.0}), See(p, 0.0, {4.5, 5.0}));
  EXPECT_EQ(across.status, ins::FixStatus::kPoorGeometry);
}

TEST(Trilateration, NoFixWhenMeasurementsDisagreeWithTheMap) {
  const Vec2 p{3.3, 5.0};
  auto s1 = See(p, 0.2, {2.1, 7.0}), s2 = See(p, 0.2, {4.5, 8.0});
  // Misidentified post: the ranges belong to another pair of posts.
  auto wrong = s2;
  wrong.position = {4.5, 11.0};
  EXPECT_FALSE(ins::TrilaterateTwoPosts(s1, wrong).ok());
  // Ranges so short the circles cannot meet.
  auto short1 = s1, short2 = s2;
  short1.range *= 0.4;
  short2.range *= 0.4;
  EXPECT_EQ(ins::TrilaterateTwoPosts(short1, short2).status, ins::FixStatus::kNoIntersection);
  // The right ranges but an angle between the rays that no point of the map can produce.
  auto a1 = s1, a2 = s2;
  a2.bearing += ins::Rad(10.0);
  EXPECT_EQ(ins::TrilaterateTwoPosts(a1, a2).status, ins::FixStatus::kInconsistent);
}

TEST(Trilateration, LocalisePicksTheBestGeometry) {
  const Vec2 p{3.3, 5.0};
  const double heading = 0.1;
  std::vector<ins::PostSighting> s = {See(p, heading, {3.3, 9.0}, 0),
                                      See(p, heading, {3.4, 12.0}, 1),
                                      See(p, heading, {1.3, 5.5}, 2)};
  const ins::Fix fix = ins::Localise(s);
  ASSERT_TRUE(fix.ok());
  EXPECT_NE(fix.sighting_a, fix.sighting_b);
  EXPECT_TRUE(fix.sighting_a == 2 || fix.sighting_b == 2);  // the post on the side
  EXPECT_NEAR(fix.position.x, p.x, 1e-9);
  EXPECT_NEAR(fix.position.y, p.y, 1e-9);
}

// The nearest pair is tried first when asked, even where a farther pair crosses at 90°; a
// nearest pair in line with the robot gives way to the next one.
TEST(Trilateration, LocaliseCanPreferTheNearestPair) {
  const Vec2 p{3.3, 5.0};
  const double heading = 0.1;
  // 0 and 1 are the nearest (1.6 and 2.2 m, 139° apart); 0 and 2 cross at 90°, 2 is 4 m off.
  std::vector<ins::PostSighting> s = {See(p, heading, {2.0, 4.0}, 0),
                                      See(p, heading, {5.496, 4.87}, 1),
                                      See(p, heading, {0.86, 8.17}, 2)};
  ins::TrilaterationDef def;
  def.pair = ins::PairChoice::kNearest;
  const ins::Fix nearest = ins::Localise(s, def);
  ASSERT_TRUE(nearest.ok());
  EXPECT_EQ(nearest.sighting_a, 0);
  EXPECT_EQ(nearest.sighting_b, 1);
  EXPECT_NEAR(nearest.position.x, p.x, 1e-9);
  EXPECT_NEAR(nearest.position.y, p.y, 1e-9);
  const ins::Fix best = ins::Localise(s);
  ASSERT_TRUE(best.ok());
  EXPECT_TRUE(best.sighting_a == 2 || best.sighting_b == 2);
  // Posts left and right of the robot at the same distance: 180° apart, poor geometry; the
  // next nearest pair is used.
  s = {See(p, heading, {2.0, 5.0}, 0), See(p, heading, {4.6, 5.0}, 1),
       See(p, heading, {4.6, 8.0}, 2)};
  const ins::Fix abeam = ins::Localise(s, def);
  ASSERT_TRUE(abeam.ok());
  EXPECT_EQ(abeam.sighting_b, 2);
}

// Eq. 4 on a turn agrees with the route geometry: radius offset, heading error, heading.
TEST(Trilateration, TurnGeometryMatchesTheRoute) {
  const ins::Route route = ins::Route::UShape({3.3, 2.0}, 18.0, 2.5, true);
  const Vec2 centre{5.8, 20.0};
  const std::vector<Vec2> inner = {{5.8, 20.0}, {5.0, 21.0}, {6.6, 21.0}};
  for (double phi = -1.4; phi <= 1.4; phi += 0.2) {
    for (double dr : {-0.4, 0.0, 0.3}) {
      for (double dh : {-0.2, 0.0, 0.15}) {
        const Vec2 p = centre + ins::AzimuthDirection(phi) * (2.5 + dr);
        const ins::RouteProjection pr = route.Project(p, 1);
        ASSERT_TRUE(pr.on_arc);
        const double heading = pr.tangent + dh;
        for (const Vec2& post : inner) {
          if ((post - p).Norm() < 0.3) continue;
          const auto m = ins::TurnGeometry(p, centre, 2.5, true, See(p, heading, post));
          ASSERT_TRUE(m.ok);
          EXPECT_NEAR(m.delta_r, dr, 1e-9);
          EXPECT_NEAR(m.lateral_offset, pr.lateral, 1e-9);
          EXPECT_NEAR(AngleDiff(m.heading_error, dh), 0.0, 1e-9);
          EXPECT_NEAR(AngleDiff(m.heading, heading), 0.0, 1e-9);
        }
      }
    }
  }
}
