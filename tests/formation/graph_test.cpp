// Formation graphs and leader schedules.
#include <gtest/gtest.h>

#include "control/formation/formation_graph.hpp"
#include "control/formation/leader_schedule.hpp"

namespace formsim::control::formation {
namespace {

FormationNodeDef Root(const std::string& n) {
  FormationNodeDef d;
  d.name = n;
  return d;
}
FormationNodeDef LPhi(const std::string& n, const std::string& leader, double phi = 5 * kPi / 4) {
  FormationNodeDef d;
  d.name = n;
  d.law = FormationLaw::kLPhi;
  d.leaders = {leader};
  d.phi_des = phi;
  return d;
}
FormationNodeDef LL(const std::string& n, const std::string& a, const std::string& b,
                    double l1 = 0.3, double l2 = 0.3) {
  FormationNodeDef d;
  d.name = n;
  d.law = FormationLaw::kLL;
  d.leaders = {a, b};
  d.l_des = l1;
  d.l2_des = l2;
  d.initial_pose = {-0.3, 0.1, 0};
  return d;
}

std::string ErrorOf(const std::vector<FormationNodeDef>& nodes, int* robot = nullptr,
                    std::string* key = nullptr) {
  try {
    BuildFormationGraph(nodes, 0.1);
  } catch (const FormationGraphError& e) {
    if (robot) *robot = e.robot();
    if (key) *key = e.key();
    return e.what();
  }
  return "";
}

TEST(FormationGraph, OrdersLeadersBeforeFollowers) {
  // Declared out of order on purpose.
  const FormationGraph g = BuildFormationGraph(
      {LL("R3", "R1", "R2"), LPhi("R2", "R1"), Root("R1"), LPhi("R4", "R3")}, 0.1);
  ASSERT_EQ(g.order, (std::vector<int>{2, 1, 0, 3}));
  EXPECT_EQ(g.depth, (std::vector<int>{2, 1, 0, 3}));
  // R2 sits at l = 0.3, φ = 5π/4 from R1, its centre L behind the control point.
  EXPECT_NEAR(g.shape[1].x, 0.3 * std::cos(5 * kPi / 4) - 0.15, 1e-12);
  EXPECT_NEAR(g.shape[1].y, 0.3 * std::sin(5 * kPi / 4), 1e-12);
  // R3's control point is 0.3 from both leaders.
  const Vec2 m3 = g.shape[0] + Vec2{0.15, 0};
  EXPECT_NEAR((m3 - g.shape[2]).Norm(), 0.3, 1e-12);
  EXPECT_NEAR((m3 - g.shape[1]).Norm(), 0.3, 1e-12);
}

TEST(FormationGraph, RejectsACycle) {
  int robot = -1;
  std::string key;
  const std::string e =
      ErrorOf({Root("R1"), LPhi("R2", "R3"), LPhi("R3", "R4"), LPhi("R4", "R2")}, &robot, &key);
  EXPECT_NE(e.find("cycle"), std::string::npos) << e;
  EXPECT_NE(e.find("R2 -> R3 -> R4 -> R2"), std::string::npos) << e;
  EXPECT_EQ(key, "leaders");
  EXPECT_EQ(robot, 1);
}

TEST(FormationGraph, RejectsBadLeaders) {
  EXPECT_NE(ErrorOf({Root("R1"), LPhi("R2", "R9")}).find("leader 'R9' is not a robot"),
            std::string::npos);
  EXPECT_NE(ErrorOf({Root("R1"), LPhi("R2", "R2")}).find("cannot follow itself"),
            std::string::npos);
  EXPECT_NE(ErrorOf({Root("R1"), LPhi("R2", "R1"), LL("R3", "R1", "R1")}).find("listed twice"),
            std::string::npos);
  FormationNodeDef two = LPhi("R2", "R1");
  two.leaders.push_back("R1");
  EXPECT_NE(ErrorOf({Root("R1"), two}).find("law l_phi needs exactly 1 leader"), std::string::npos);
}

TEST(FormationGraph, RejectsNonPositiveDistances) {
  FormationNodeDef f = LPhi("R2", "R1");
  f.l_des = 0.0;
  std::string key;
  EXPECT_NE(ErrorOf({Root("R1"), f}, nullptr, &key).find("must be > 0"), std::string::npos);
  EXPECT_EQ(key, "l_des");
  f.l_des = 0.3;
  f.L = -0.1;
  EXPECT_NE(ErrorOf({Root("R1"), f}, nullptr, &key).find("L must be > 0"), std::string::npos);
  EXPECT_EQ(key, "L");
}

TEST(FormationGraph, RejectsAnImpossibleTriangle) {
  // R1 and R2 are 0.42 m apart in the desired shape; 0.1 + 0.2 cannot reach.
  std::string key;
  const std::string e =
      ErrorOf({Root("R1"), LPhi("R2", "R1"), LL("R3", "R1", "R2", 0.1, 0.2)}, nullptr, &key);
  EXPECT_NE(e.find("cannot form a triangle"), std::string::npos) << e;
  EXPECT_EQ(key, "l_des");
  // Nearly flat: the apex sits almost on the line through the leaders.
  const double sep = std::hypot(0.3 * std::cos(5 * kPi / 4) - 0.15, 0.3 * std::sin(5 * kPi / 4));
  const std::string flat =
      ErrorOf({Root("R1"), LPhi("R2", "R1"), LL("R3", "R1", "R2", sep / 2 + 1e-4, sep / 2 + 1e-4)});
  EXPECT_NE(flat.find("nearly flat"), std::string::npos) << flat;
}

TEST(FormationGraph, TriangleApexSide) {
  Vec2 apex;
  ASSERT_TRUE(TriangleApex({0, 0}, {1, 0}, 1.0, 1.0, +1, apex));
  EXPECT_NEAR(apex.x, 0.5, 1e-12);
  EXPECT_NEAR(apex.y, std::sqrt(0.75), 1e-12);
  ASSERT_TRUE(TriangleApex({0, 0}, {1, 0}, 1.0, 1.0, -1, apex));
  EXPECT_LT(apex.y, 0.0);
  EXPECT_FALSE(TriangleApex({0, 0}, {1, 0}, 0.3, 0.3, +1, apex));
}

TEST(LeaderSchedule, SegmentsWithARampChangeLinearly) {
  LeaderScheduleDef d;
  d.kind = LeaderScheduleDef::Kind::kSegments;
  d.segments = {{2.0, 2.5, 0.0}, {6.0, 2.5, 0.2}, {10.0, 1.5, -0.2}};
  EXPECT_EQ(ScheduleAt(d, 2.5).w, 0.2);  // no ramp: steps
  d.ramp = 1.0;
  EXPECT_EQ(ScheduleAt(d, 1.0).w, 0.0);
  EXPECT_EQ(ScheduleAt(d, 2.0).w, 0.0);
  EXPECT_DOUBLE_EQ(ScheduleAt(d, 2.5).w, 0.1);
  EXPECT_DOUBLE_EQ(ScheduleAt(d, 3.0).w, 0.2);
  EXPECT_DOUBLE_EQ(ScheduleAt(d, 6.25).w, 0.1);
  EXPECT_DOUBLE_EQ(ScheduleAt(d, 6.25).v, 2.25);
  EXPECT_DOUBLE_EQ(ScheduleAt(d, 7.0).w, -0.2);
  EXPECT_DOUBLE_EQ(ScheduleAt(d, 50.0).v, 1.5);  // the last segment holds
}

TEST(LeaderSchedule, PaperTrajectories) {
  LeaderScheduleDef t1;
  t1.kind = LeaderScheduleDef::Kind::kLineCurve;
  EXPECT_EQ(ScheduleAt(t1, 1.99).w, 0.0);
  EXPECT_DOUBLE_EQ(ScheduleAt(t1, 2.0).w, -kPi / 5);
  EXPECT_DOUBLE_EQ(ScheduleAt(t1, 6.0).w, -kPi / 5);
  EXPECT_EQ(ScheduleAt(t1, 7.0).w, 0.0);
  EXPECT_EQ(ScheduleAt(t1, 8.0).w, 0.0);
  EXPECT_DOUBLE_EQ(ScheduleAt(t1, 8.01).w, kPi / 5);
  EXPECT_DOUBLE_EQ(ScheduleAt(t1, 16.0).v, 2.5);

  LeaderScheduleDef t2;
  t2.kind = LeaderScheduleDef::Kind::kFigureEight;
  t2.omega = kPi / 3;
  EXPECT_DOUBLE_EQ(ScheduleAt(t2, 0.0).w, -kPi / 3);
  EXPECT_DOUBLE_EQ(ScheduleAt(t2, 5.5).w, -kPi / 3);
  EXPECT_DOUBLE_EQ(ScheduleAt(t2, 5.51).w, kPi / 3);
  EXPECT_DOUBLE_EQ(ScheduleAt(t2, 11.0).w, kPi / 3);

  LeaderScheduleDef t3;
  t3.kind = LeaderScheduleDef::Kind::kSpiral;
  EXPECT_DOUBLE_EQ(ScheduleAt(t3, 0.0).v, 2.5);
  EXPECT_DOUBLE_EQ(ScheduleAt(t3, 0.0).w, 2.5 / 2.0);
  EXPECT_NEAR(ScheduleAt(t3, 15.0).w, 3.25 / 5.0, 1e-12);

  LeaderScheduleDef seg;
  seg.kind = LeaderScheduleDef::Kind::kSegments;
  seg.segments = {{1.0, 1.0, 0.0}, {2.0, 0.5, 0.3}};
  EXPECT_EQ(ScheduleAt(seg, 0.5).v, 1.0);
  EXPECT_EQ(ScheduleAt(seg, 1.5).w, 0.3);
  EXPECT_EQ(ScheduleAt(seg, 9.0).v, 0.5);  // the last segment holds
}

}  // namespace
}  // namespace formsim::control::formation
