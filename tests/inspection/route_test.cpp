#include "control/inspection/route.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/inspection/paper_frame.hpp"

namespace ins = formsim::control::inspection;
using formsim::Vec2;

TEST(Route, UShapeGeometry) {
  const auto r = ins::Route::UShape({3.3, 2.0}, 18.0, 2.5, true);
  ASSERT_EQ(r.segments().size(), 3u);
  EXPECT_NEAR(r.length(), 36.0 + M_PI * 2.5, 1e-12);
  const auto& arc = r.segments()[1];
  EXPECT_NEAR(arc.a.x, 3.3, 1e-12);
  EXPECT_NEAR(arc.a.y, 20.0, 1e-12);
  EXPECT_NEAR(arc.b.x, 8.3, 1e-12);
  EXPECT_NEAR(arc.b.y, 20.0, 1e-12);
  EXPECT_NEAR(r.segments()[2].a.x, 8.3, 1e-12);
}

TEST(Route, LateralOffsetSignAndTangent) {
  const auto r = ins::Route::UShape({3.3, 2.0}, 18.0, 2.5, true);
  // First straight goes up (+Y, azimuth 0): right of it is larger X.
  auto p = r.Project({3.5, 10.0}, 0);
  EXPECT_NEAR(p.lateral, 0.2, 1e-12);
  EXPECT_NEAR(p.tangent, 0.0, 1e-12);
  EXPECT_NEAR(p.progress, 8.0, 1e-12);
  // Second straight comes down: right of it is smaller X.
  p = r.Project({8.0, 10.0}, 2);
  EXPECT_NEAR(p.lateral, 0.3, 1e-12);
  EXPECT_NEAR(std::abs(p.tangent), M_PI, 1e-12);
  // On the right turn, outside the arc is left of the path.
  p = r.Project({5.8, 20.0 + 2.8}, 1);
  EXPECT_TRUE(p.on_arc);
  EXPECT_NEAR(p.lateral, -0.3, 1e-12);
  EXPECT_NEAR(p.tangent, M_PI / 2.0, 1e-12);  // heading +X at the top of the turn
  EXPECT_GT(p.curvature, 0.0);
}

TEST(Route, ProgressIsMonotonicAndFinishes) {
  const auto r = ins::Route::UShape({3.3, 2.0}, 18.0, 2.5, true);
  int hint = 0;
  double last = -1.0;
  for (const Vec2& q : r.Polyline(0.05)) {
    const auto p = r.Project(q + Vec2{0.01, 0.0}, hint);
    hint = p.segment;
    EXPECT_GE(p.progress, last - 1e-9);
    last = p.progress;
  }
  EXPECT_EQ(hint, 2);
  EXPECT_TRUE(r.Project({8.3, 1.0}, 2).finished);
  EXPECT_FALSE(r.Project({8.3, 3.0}, 2).finished);
}
