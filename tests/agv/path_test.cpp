// Paths of lines and arcs: construction, projection, windowed projection with laps.
#include "control/agv/path.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::control::agv {
namespace {

TEST(Path, RoundedRectangleLengthAndClosure) {
  const double r = 0.5;
  const Path p = Path::RoundedRectangle({0, 0}, 6.0, 4.0, r);
  EXPECT_TRUE(p.closed());
  EXPECT_NEAR(p.length(), 2 * (6.0 + 4.0) - 8 * r + 2 * kPi * r, 1e-9);
  // Start: middle of the bottom side, heading +x.
  const PathPoint s = p.At(0.0);
  EXPECT_NEAR(s.p.x, 0.0, 1e-12);
  EXPECT_NEAR(s.p.y, -2.0, 1e-12);
  EXPECT_NEAR(s.heading, 0.0, 1e-12);
  // The top side is travelled at heading π: half way round the loop.
  const PathPoint top = p.At(0.5 * p.length());
  EXPECT_NEAR(top.p.x, 0.0, 1e-9);
  EXPECT_NEAR(top.p.y, 2.0, 1e-9);
  EXPECT_NEAR(std::abs(top.heading), kPi, 1e-9);
  // Wrapping s on a closed path.
  EXPECT_NEAR(p.At(p.length() + 1.0).p.x, p.At(1.0).p.x, 1e-9);
}

TEST(Path, RoundedRectangleRejectsTooLargeRadius) {
  EXPECT_THROW(Path::RoundedRectangle({0, 0}, 6.0, 4.0, 2.5), PathError);
  EXPECT_THROW(Path::RoundedRectangle({0, 0}, 6.0, 4.0, 0.0), PathError);
  EXPECT_NO_THROW(Path::RoundedRectangle({0, 0}, 6.0, 4.0, 2.0));  // stadium
}

TEST(Path, ClockwiseRectangleTurnsRight) {
  const Path p = Path::RoundedRectangle({1, 1}, 6.0, 4.0, 0.5, false);
  EXPECT_NEAR(std::abs(p.At(0).heading), kPi, 1e-12);
  for (const PathSegment& s : p.segments()) EXPECT_LE(s.curvature, 0.0);
}

TEST(Path, ProjectionOnLineAndArc) {
  Path p({0, 0, 0});
  p.AddLine(2.0);
  p.AddArc(1.0, 0.5 * kPi);  // centre (2, 1)
  PathProjection pr = p.Project({1.0, 0.1});
  EXPECT_NEAR(pr.s, 1.0, 1e-12);
  EXPECT_NEAR(pr.cross_track, 0.1, 1e-12);
  pr = p.Project({1.0, -0.2});
  EXPECT_NEAR(pr.cross_track, -0.2, 1e-12);
  // A point 0.2 m outside the arc at 45°: cross-track -0.2 (right of a left turn).
  const Vec2 q{2.0 + 1.2 * std::sin(kPi / 4), 1.0 - 1.2 * std::cos(kPi / 4)};
  pr = p.Project(q);
  EXPECT_NEAR(pr.s, 2.0 + kPi / 4, 1e-9);
  EXPECT_NEAR(pr.cross_track, -0.2, 1e-9);
  EXPECT_NEAR(pr.ref.heading, kPi / 4, 1e-9);
  EXPECT_NEAR(pr.ref.curvature, 1.0, 1e-12);
}

TEST(Path, ProjectNearCountsLapsAndIgnoresFarStretches) {
  const Path p = Path::RoundedRectangle({0, 0}, 6.0, 4.0, 0.5);
  const double L = p.length();
  // Just after the start on the second lap: s keeps growing past L.
  PathProjection pr = p.ProjectNear({0.1, -2.0}, L - 0.05, 0.5);
  EXPECT_NEAR(pr.s, L + 0.1, 1e-9);
  // A U-shaped path whose legs are 0.4 m apart: the window keeps the tracker on its own leg.
  Path u({0, 0, 0});
  u.AddLine(3.0);
  u.AddArc(0.2, kPi);
  u.AddLine(3.0);
  const Vec2 q{1.0, 0.25};  // 0.15 m from the return leg (y = 0.4), 0.25 m from the outbound
  EXPECT_NEAR(u.Project(q).s, 3.0 + 0.2 * kPi + 2.0, 1e-9);  // globally: the return leg
  pr = u.ProjectNear(q, 1.0, 0.5);
  EXPECT_NEAR(pr.s, 1.0, 1e-9);  // within the window: the outbound leg
  EXPECT_NEAR(pr.cross_track, 0.25, 1e-9);
}

TEST(Path, PolylineWithFilletsIsTangentContinuous) {
  const Path p = Path::Polyline({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, 0.5, true);
  EXPECT_TRUE(p.closed());
  // Perimeter 14, four quarter fillets each save (2 - π/2) r.
  EXPECT_NEAR(p.length(), 14.0 - 4 * (2.0 - 0.5 * kPi) * 0.5, 1e-9);
  for (size_t i = 1; i < p.segments().size(); ++i) {
    const PathSegment& a = p.segments()[i - 1];
    const PathPoint end = a.At(a.length);
    EXPECT_NEAR((end.p - p.segments()[i].start).Norm(), 0.0, 1e-9);
    EXPECT_NEAR(AngleDiff(end.heading, p.segments()[i].heading0), 0.0, 1e-9);
  }
  const Path open = Path::Polyline({{0, 0}, {2, 0}, {2, 2}}, 0.3, false);
  EXPECT_FALSE(open.closed());
  EXPECT_NEAR(open.At(open.length()).p.y, 2.0, 1e-9);
  EXPECT_THROW(Path::Polyline({{0, 0}, {0.2, 0}, {0.2, 2}}, 0.5, false), PathError);
  EXPECT_THROW(Path::Polyline({{0, 0}, {1, 0}, {0, 0}}, 0.1, false), PathError);
}

TEST(Path, CloseRejectsOpenLoop) {
  Path p({0, 0, 0});
  p.AddLine(1.0);
  p.AddArc(0.5, kPi);
  EXPECT_THROW(p.Close(), PathError);
}

}  // namespace
}  // namespace formsim::control::agv
