// Named formation shapes: every shape for every size loads as a graph whose desired shape is the
// generated slots, every l-l triangle keeps the triangle condition with margin, and no two slots
// are closer than the spacing.
#include <gtest/gtest.h>

#include <cmath>

#include "control/formation/formation_shapes.hpp"

namespace formsim::control::formation {
namespace {

std::vector<std::string> Names(int n) {
  std::vector<std::string> out;
  for (int i = 0; i < n; ++i) out.push_back("R" + std::to_string(i + 1));
  return out;
}

TEST(FormationShapes, EveryShapeAndSizeIsAValidGraphWithMargin) {
  const double d = 0.5, L = 0.15;
  for (const std::string& name : ShapeNames()) {
    ShapeKind kind;
    ASSERT_TRUE(ShapeFromName(name, &kind));
    for (int n = 1; n <= 25; ++n) {
      SCOPED_TRACE(name + " n=" + std::to_string(n));
      const FormationShape s = MakeFormationShape(kind, Names(n), d, L);
      ASSERT_EQ(static_cast<int>(s.nodes.size()), n);
      ASSERT_EQ(static_cast<int>(s.slots.size()), n);
      EXPECT_EQ(s.slots[0].x, 0.0);
      EXPECT_EQ(s.slots[0].y, 0.0);
      // The loader's own check (cycle, leaders, triangle, singular band) accepts it.
      FormationGraph g;
      ASSERT_NO_THROW(g = BuildFormationGraph(s.nodes, 0.1));
      for (int i = 0; i < n; ++i) {
        EXPECT_EQ(g.root[i], 0);
        EXPECT_NEAR(g.shape[i].x, s.slots[i].x, 1e-9);
        EXPECT_NEAR(g.shape[i].y, s.slots[i].y, 1e-9);
        for (int k = 0; k < i; ++k) EXPECT_GE((s.slots[i] - s.slots[k]).Norm(), d * (1 - 1e-9));
        const FormationNodeDef& nd = s.nodes[i];
        if (nd.law != FormationLaw::kLL) continue;
        const Vec2 m = s.slots[i] + Vec2{L, 0};
        const Vec2 a = s.slots[g.leaders[i][0]], b = s.slots[g.leaders[i][1]];
        const double l1 = (m - a).Norm(), l2 = (m - b).Norm(), sep = (b - a).Norm();
        EXPECT_NEAR(nd.l_des, l1, 1e-12);
        EXPECT_NEAR(nd.l2_des, l2, 1e-12);
        EXPECT_GE(std::abs((a - m).Cross(b - m)) / (l1 * l2), kMinApexSin);
        EXPECT_GE(std::min(l1 + l2 - sep, sep - std::abs(l1 - l2)), kMinTriangleSlack * sep);
      }
    }
  }
}

TEST(FormationShapes, ShapesLookLikeTheirNames) {
  const double d = 0.5;
  const auto column = ShapeSlots(ShapeKind::kColumn, 4, d);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(column[i].y, 0.0);
    EXPECT_DOUBLE_EQ(column[i].x, -i * d);
  }
  const auto line = ShapeSlots(ShapeKind::kLineAbreast, 5, d);
  for (const Vec2& p : line) EXPECT_EQ(p.x, 0.0);
  const auto diamond = ShapeSlots(ShapeKind::kDiamond, 4, d);
  // A front robot, two side by side, one at the back on the centre line.
  EXPECT_NEAR(diamond[1].x, diamond[2].x, 1e-12);
  EXPECT_NEAR(diamond[3].y, 0.0, 1e-12);
  EXPECT_LT(diamond[3].x, diamond[1].x);
  const auto v = ShapeSlots(ShapeKind::kV, 7, d);
  for (std::size_t i = 1; i < v.size(); ++i) EXPECT_NEAR(std::abs(v[i].y), -v[i].x / std::sqrt(3.0), 1e-12);
  const auto grid = ShapeSlots(ShapeKind::kGrid, 9, d);
  for (const Vec2& p : grid) EXPECT_NEAR(std::remainder(p.x, d), 0.0, 1e-12);
  // Deep shapes use l-l links (no long l-φ chains).
  const FormationShape w = MakeFormationShape(ShapeKind::kWedge, Names(10), d, 0.15);
  int ll = 0;
  for (const auto& nd : w.nodes) ll += nd.law == FormationLaw::kLL;
  EXPECT_GE(ll, 7);
}

TEST(FormationShapes, RefusesWhatCannotWork) {
  EXPECT_THROW(MakeFormationShape(ShapeKind::kWedge, {}, 0.5, 0.15), std::invalid_argument);
  EXPECT_THROW(MakeFormationShape(ShapeKind::kWedge, Names(3), 0.3, 0.15), std::invalid_argument);
  ShapeKind k;
  EXPECT_FALSE(ShapeFromName("triangle", &k));
}

}  // namespace
}  // namespace formsim::control::formation
