// PID path tracking on the rounded rectangle with ideal (kinematic) motion.
#include "control/agv/path_tracker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"
#include "control/agv/dead_reckoning.hpp"

namespace formsim::control::agv {
namespace {

struct LapResult {
  double max_cross = 0.0;
  double max_etheta_after_start = 0.0;
  bool finished = false;
  double time = 0.0;
  bool crossed_pi = false;
};

LapResult RunLap(PathTrackerDef def, Pose2 start) {
  const Path path = Path::RoundedRectangle({0, 0}, 6.0, 4.0, 0.5);
  PathTracker tr(def);
  tr.SetPath(path);
  tr.Reset(start);
  Pose2 pose = start;
  LapResult r;
  const double T = 1.0 / 15.0;
  for (int k = 0; k < 15 * 120 && !tr.finished(); ++k) {
    const BodyTwist tw = tr.Step(pose, T);
    for (int j = 0; j < 10; ++j) pose = IntegrateTwist(pose, tw, T / 10);
    r.max_cross =
        std::max(r.max_cross, std::abs(path.ProjectNear(pose.p(), tr.errors().s, 0.5).cross_track));
    if (k > 30)
      r.max_etheta_after_start = std::max(r.max_etheta_after_start, std::abs(tr.errors().etheta));
    if (std::abs(pose.theta) > kPi - 0.05) r.crossed_pi = true;
    r.time = (k + 1) * T;
  }
  r.finished = tr.finished();
  return r;
}

TEST(PathTracker, FollowsRoundedRectangleWithTangentHeading) {
  const LapResult r = RunLap(DefaultPathTrackerDef(), {0.0, -2.0, 0.0});
  EXPECT_TRUE(r.finished);
  EXPECT_TRUE(r.crossed_pi);  // the top side is driven at θ = ±π
  EXPECT_LT(r.max_cross, 0.01);
  EXPECT_LT(r.max_etheta_after_start, 0.05);
  const double L = Path::RoundedRectangle({0, 0}, 6.0, 4.0, 0.5).length();
  EXPECT_NEAR(r.time, L / 0.3, 5.0);  // about one lap at 0.3 m/s plus the ramps
}

TEST(PathTracker, FixedHeadingDrivesSidewaysAndConvergesFromOffset) {
  PathTrackerDef def;
  def.heading_mode = PathTrackerDef::HeadingMode::kFixed;
  def.fixed_heading = 0.3;
  const LapResult r = RunLap(def, {0.1, -2.15, 0.0});  // 15 cm off, wrong heading
  EXPECT_TRUE(r.finished);
  EXPECT_LT(r.max_cross, 0.16);
  EXPECT_FALSE(r.crossed_pi);
}

TEST(PathTracker, ErrorsAreInTheBodyFrame) {
  PathTracker tr;
  tr.SetPath(Path::RoundedRectangle({0, 0}, 6.0, 4.0, 0.5));
  // Robot 0.1 m below the bottom side, facing +y: the path is 0.1 m ahead of it.
  tr.Reset({0.0, -2.1, 0.5 * kPi});
  tr.Step({0.0, -2.1, 0.5 * kPi}, 1.0 / 15);
  EXPECT_NEAR(tr.errors().es, 0.1, 1e-12);
  EXPECT_NEAR(tr.errors().ed, 0.0, 1e-12);
  EXPECT_NEAR(tr.errors().etheta, -0.5 * kPi, 1e-12);
  EXPECT_NEAR(tr.errors().cross_track, -0.1, 1e-12);
}

TEST(PathTracker, StopsAtTheEndOfAnOpenPath) {
  Path p({0, 0, 0});
  p.AddLine(1.0);
  PathTracker tr;
  tr.SetPath(p);
  Pose2 pose{0, 0, 0};
  tr.Reset(pose);
  for (int k = 0; k < 15 * 20; ++k) pose = IntegrateTwist(pose, tr.Step(pose, 1.0 / 15), 1.0 / 15);
  EXPECT_TRUE(tr.finished());
  EXPECT_NEAR(pose.x, 1.0, 0.02);
}

}  // namespace
}  // namespace formsim::control::agv
