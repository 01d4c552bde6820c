// Finding and naming the reference posts in a scan, on synthetic scans (exact ray casts
// against circles and segments, no Box2D).
#include "control/inspection/post_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "control/inspection/paper_frame.hpp"

namespace ins = formsim::control::inspection;
using formsim::Vec2;

namespace {

struct Segment {
  Vec2 a, b;
};

// A perfect 360° scan from `pose` against circles of `radius` and wall segments.
ins::Scan MakeScan(const ins::PaperPose& pose, const std::vector<Vec2>& circles, double radius,
                   const std::vector<Segment>& walls = {}, double resolution_deg = 0.5) {
  ins::Scan scan;
  scan.angle_increment = ins::Rad(resolution_deg);
  scan.angle_min = -M_PI;
  scan.range_max = 20.0;
  const int n = static_cast<int>(std::lround(360.0 / resolution_deg));
  for (int k = 0; k < n; ++k) {
    const Vec2 d = ins::AzimuthDirection(pose.theta + scan.Bearing(k));
    double best = std::numeric_limits<double>::quiet_NaN();
    auto take = [&](double t) {
      if (t > 0.0 && t <= scan.range_max && !(t >= best)) best = t;
    };
    for (const Vec2& c : circles) {
      const Vec2 m = pose.p() - c;
      const double b = m.Dot(d), cc = m.Dot(m) - radius * radius, disc = b * b - cc;
      if (disc >= 0.0) take(-b - std::sqrt(disc));
    }
    for (const auto& w : walls) {
      const Vec2 e = w.b - w.a, f = w.a - pose.p();
      const double den = d.Cross(e);
      if (std::abs(den) < 1e-12) continue;
      const double t = f.Cross(e) / den, u = f.Cross(d) / den;
      if (u >= 0.0 && u <= 1.0) take(t);
    }
    scan.ranges.push_back(best);
  }
  return scan;
}

}  // namespace

TEST(PostDetector, FitsAKnownCircleExactly) {
  const Vec2 c{0.4, 5.0};
  std::vector<Vec2> pts;
  for (double a = -0.6; a <= 0.6; a += 0.3)  // points on the near side of the circle
    pts.push_back(c + Vec2{0.1 * std::sin(M_PI + a), 0.1 * std::cos(M_PI + a)});
  Vec2 fit;
  double rms = 1.0;
  ASSERT_TRUE(ins::FitKnownCircle(pts, 0.1, &fit, &rms));
  EXPECT_NEAR(fit.x, c.x, 1e-9);
  EXPECT_NEAR(fit.y, c.y, 1e-9);
  EXPECT_LT(rms, 1e-9);
}

TEST(PostDetector, IdentifiesEveryVisiblePostWithExactRanges) {
  const ins::PaperPose pose{3.3, 6.0, 0.3};
  ins::PostMap map;
  map.radius = 0.1;
  map.posts = {{2.1, 4.0}, {4.5, 7.0}, {2.1, 10.0}, {4.5, 13.0}, {2.1, 16.0}};
  const auto scan = MakeScan(pose, map.posts, map.radius);
  const auto det = ins::DetectPosts(scan, pose, map);
  ASSERT_EQ(det.sightings.size(), map.posts.size());
  for (const auto& s : det.sightings) {
    const Vec2 rel = map.posts[s.post] - pose.p();
    EXPECT_NEAR(s.range, rel.Norm(), 1e-6);
    EXPECT_NEAR(formsim::control::AngleDiff(s.bearing, ins::Azimuth(rel) - pose.theta), 0.0, 1e-6);
  }
  // And the fix from them is the pose.
  const auto fix = ins::Localise(det.sightings);
  ASSERT_TRUE(fix.ok());
  EXPECT_NEAR(fix.position.x, pose.x, 1e-5);
  EXPECT_NEAR(fix.position.y, pose.y, 1e-5);
  EXPECT_NEAR(fix.heading, pose.theta, 1e-5);
}

TEST(PostDetector, WallsAndBoxesAreNotPosts) {
  const ins::PaperPose pose{3.3, 6.0, 0.0};
  ins::PostMap map;
  map.posts = {{2.1, 8.0}};
  // A cabinet right where the map has no post, and a wall far away.
  const auto scan =
      MakeScan(pose, map.posts, 0.1,
               {{{5.0, 5.0}, {5.0, 6.0}}, {{5.0, 6.0}, {5.6, 6.0}}, {{-2, 30}, {9, 30}}});
  const auto det = ins::DetectPosts(scan, pose, map);
  ASSERT_EQ(det.sightings.size(), 1u);
  EXPECT_EQ(det.sightings[0].post, 0);
  int not_posts = 0;
  for (const auto& c : det.clusters)
    if (c.outcome == ins::ScanCluster::Outcome::kNotPostShaped) ++not_posts;
  EXPECT_GE(not_posts, 1);
  // A single post is not enough for a fix.
  EXPECT_EQ(ins::Localise(det.sightings).status, ins::FixStatus::kTooFewPosts);
}

TEST(PostDetector, UnknownAndAmbiguousPostsAreDropped) {
  const ins::PaperPose pose{3.3, 6.0, 0.0};
  ins::PostMap map;
  map.posts = {{2.1, 8.0}, {4.5, 8.0}, {4.8, 8.2}};  // the last two are 0.36 m apart
  // The world has an extra, unsurveyed post at (1.0, 4.0) and one of the close pair.
  const auto scan = MakeScan(pose, {{2.1, 8.0}, {4.6, 8.1}, {1.0, 4.0}}, 0.1);
  const auto det = ins::DetectPosts(scan, pose, map);
  ASSERT_EQ(det.sightings.size(), 1u);
  EXPECT_EQ(det.sightings[0].post, 0);
  int ambiguous = 0, unmatched = 0;
  for (const auto& c : det.clusters) {
    if (c.outcome == ins::ScanCluster::Outcome::kAmbiguous) ++ambiguous;
    if (c.outcome == ins::ScanCluster::Outcome::kUnmatched) ++unmatched;
  }
  EXPECT_EQ(ambiguous, 1);
  EXPECT_EQ(unmatched, 1);
  EXPECT_FALSE(ins::Localise(det.sightings).ok());
}

TEST(PostDetector, APoorPredictionFindsNothingRatherThanWrongPosts) {
  const ins::PaperPose truth{3.3, 6.0, 0.0};
  ins::PostMap map;
  for (int k = 0; k < 6; ++k) map.posts.push_back({k % 2 ? 4.5 : 2.1, 3.0 + 3.0 * k});
  const auto scan = MakeScan(truth, map.posts, 0.1);
  // The prediction is 1.5 m off along the road: half-way between posts 3 m apart.
  const ins::PaperPose wrong{3.3, 7.5, 0.0};
  const auto det = ins::DetectPosts(scan, wrong, map);
  EXPECT_TRUE(det.sightings.empty());
}
