// The presentation camera: after fitting, the formation fills at least half of the view's
// shorter side, with every robot inside the view; it follows the robots; zooming by hand
// suspends it until fit. View-only: the session's journal does not change.
#include "app/render/camera.hpp"

#include <gtest/gtest.h>

#include "sim/session/session.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

View Screen(float w, float h) {
  View v;
  v.min = ImVec2(0, 0);
  v.max = ImVec2(w, h);
  return v;
}

void ExpectRobotsInside(const View& v, const FocusSet& f) {
  for (std::size_t i = 0; i < f.bodies.size(); ++i) {
    const ImVec2 p = v.ToScreen(f.bodies[i]);
    EXPECT_GE(p.x, v.min.x);
    EXPECT_LE(p.x, v.max.x);
    EXPECT_GE(p.y, v.min.y);
    EXPECT_LE(p.y, v.max.y);
  }
}

TEST(PresentationCamera, FitFillsHalfTheShorterSideWithLongTrails) {
  FocusSet f;
  f.bodies = {{10, 10}, {10.6, 10.3}, {10.2, 9.6}};
  f.radii = {0.1, 0.1, 0.1};
  for (int k = 0; k < 100; ++k)
    f.trails.push_back({10.0 - 0.3 * k, 10.0 - 0.1 * k});  // 30 m behind
  for (auto [w, h] :
       std::vector<std::pair<float, float>>{{1920.f, 1080.f}, {1280.f, 800.f}, {600.f, 900.f}}) {
    View v = Screen(w, h);
    PresentationCamera cam;
    cam.Fit();
    cam.Update(v, f, 0.15);
    EXPECT_GE(FormationFraction(v, f), 0.5) << w << "x" << h;
    ExpectRobotsInside(v, f);
  }
}

TEST(PresentationCamera, ShortTrailsAreFramedWhole) {
  FocusSet f;
  f.bodies = {{0, 0}, {1, 0}};
  f.radii = {0.1, 0.1};
  f.trails = {{-0.5, 0}, {1.5, 0.2}};
  View v = Screen(1920, 1080);
  PresentationCamera cam;
  cam.Update(v, f, 1.0);
  for (const Vec2& p : f.trails) {
    const ImVec2 s = v.ToScreen(p);
    EXPECT_GT(s.x, 0);
    EXPECT_LT(s.x, 1920);
  }
  EXPECT_GE(FormationFraction(v, f), 0.5);
}

// Presentation mode's buttons cover the top of the view: the robots (their bodies, not only
// their centres) are framed below them, still filling half the shorter side.
TEST(PresentationCamera, KeepsTheFormationBelowTheButtons) {
  FocusSet f;
  // A wide wedge, as formation_swarm_100: rows of robots, the leader at the top right.
  for (int row = 0; row < 10; ++row)
    for (int k = 0; k <= row; ++k) {
      f.bodies.push_back({10.0 - 0.5 * row, 4.0 - 0.4 * row + 0.4 * k});
      f.radii.push_back(0.1);
    }
  for (int k = 0; k < 60; ++k) f.trails.push_back({10.0 - 0.3 * k, 4.0 - 0.05 * k});
  for (const float inset : {0.0f, 80.0f, 160.0f}) {
    for (auto [w, h] : std::vector<std::pair<float, float>>{{1920.f, 1080.f}, {960.f, 540.f}}) {
      View v = Screen(w, h);
      PresentationCamera cam;
      cam.Update(v, f, 1.0, inset);
      for (std::size_t i = 0; i < f.bodies.size(); ++i) {
        const ImVec2 p = v.ToScreen(f.bodies[i]);
        EXPECT_GE(p.y - f.radii[i] * v.scale, v.min.y + inset) << "inset " << inset << ", " << w;
        EXPECT_LE(p.y + f.radii[i] * v.scale, v.max.y) << "inset " << inset << ", " << w;
      }
      EXPECT_GE(FormationFraction(v, f), 0.5) << "inset " << inset << ", " << w;
    }
  }
}

TEST(PresentationCamera, ManualZoomSuspendsFollowUntilFit) {
  FocusSet f;
  f.bodies = {{0, 0}, {1, 1}};
  f.radii = {0.1, 0.1};
  View v = Screen(1280, 800);
  PresentationCamera cam;
  cam.Update(v, f, 1.0);
  v.ZoomAt(ImVec2(100, 100), 0.3);  // the user zooms out
  cam.Suspend();
  const View zoomed = v;
  f.bodies = {{5, 5}, {6, 6}};  // the robots move on
  cam.Update(v, f, 0.5);
  EXPECT_EQ(v.scale, zoomed.scale);
  EXPECT_EQ(v.center.x, zoomed.center.x);
  EXPECT_FALSE(cam.following());
  cam.Fit();
  cam.Update(v, f, 0.15);
  EXPECT_TRUE(cam.following());
  EXPECT_GE(FormationFraction(v, f), 0.5);
  ExpectRobotsInside(v, f);
}

TEST(PresentationCamera, FollowsARunningFormationAndEditsNothing) {
  sim::Session s(testing::Scenario("formation_traj2_ukf"), {"duration=4"}, -1);
  View v = Screen(1920, 1080);
  PresentationCamera cam;
  while (!s.exp().finished()) {
    s.Step();
    if (s.exp().steps() % 20 == 0) cam.Update(v, FocusOf(s.exp(), 3.0), 0.15);
  }
  const FocusSet f = FocusOf(s.exp(), 3.0);
  EXPECT_FALSE(f.trails.empty()) << "formation runs frame their recent trails";
  cam.Update(v, f, 0.15);
  EXPECT_GE(FormationFraction(v, f), 0.5);
  ExpectRobotsInside(v, f);
  EXPECT_EQ(s.accepted_edits(), 0) << "the camera is view-only";
  EXPECT_FALSE(s.can_undo());
}

// The window asks for the trails' box alone (the camera) or no trails (most frames): the box is
// the one the points give, and the robots are the same either way.
TEST(PresentationCamera, TrailBoxIsTheBoxOfTheTrailPoints) {
  sim::Session s(testing::Scenario("formation_cascade7"), {"duration=3"}, -1);
  while (!s.exp().finished()) s.Step();
  FocusSet points, box, none;
  FocusOf(s.exp(), 2.0, &points, FocusTrails::kPoints);
  FocusOf(s.exp(), 2.0, &box, FocusTrails::kBox);
  FocusOf(s.exp(), 2.0, &none, FocusTrails::kNone);
  ASSERT_GT(points.trails.size(), 100u);
  EXPECT_TRUE(box.trails.empty());
  EXPECT_TRUE(none.trails.empty());
  EXPECT_FALSE(none.trail_box);
  Vec2 lo, hi, blo, bhi;
  ASSERT_TRUE(points.TrailBox(lo, hi));
  ASSERT_TRUE(box.TrailBox(blo, bhi));
  EXPECT_EQ(lo.x, blo.x);
  EXPECT_EQ(lo.y, blo.y);
  EXPECT_EQ(hi.x, bhi.x);
  EXPECT_EQ(hi.y, bhi.y);
  EXPECT_LT(lo.x, hi.x) << "the trails span some ground";
  EXPECT_EQ(points.bodies.size(), none.bodies.size());
  EXPECT_EQ(points.radii, none.radii);
  // Their last 2 s only: a longer span gives a box at least as large.
  FocusSet longer;
  FocusOf(s.exp(), 3.0, &longer, FocusTrails::kBox);
  EXPECT_LE(longer.trail_lo.x, blo.x);
}

}  // namespace
}  // namespace formsim::app
