// Mecanum kinematics: IK∘FK identity and the characteristic wheel patterns.
#include "control/agv/kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/common/angle.hpp"
#include "control/agv/dead_reckoning.hpp"

namespace formsim::control::agv {
namespace {

MecanumGeometry Geom() {
  MecanumGeometry g;
  g.wheel_radius = 0.076;
  g.half_wheelbase = 0.25;
  g.half_track = 0.22;
  return g;
}

TEST(MecanumKinematics, InverseThenForwardIsIdentity) {
  const MecanumGeometry g = Geom();
  const BodyTwist cases[] = {{0.3, 0.0, 0.0},  {0.0, -0.2, 0.0}, {0.0, 0.0, 1.1},
                             {0.3, 0.1, -0.4}, {-0.5, 0.7, 2.0}, {1e-4, -3e-4, 5e-3}};
  for (const BodyTwist& t : cases) {
    const BodyTwist back = ForwardKinematics(g, InverseKinematics(g, t));
    EXPECT_NEAR(back.vx, t.vx, 1e-12);
    EXPECT_NEAR(back.vy, t.vy, 1e-12);
    EXPECT_NEAR(back.omega, t.omega, 1e-12);
  }
}

TEST(MecanumKinematics, PureForwardTurnsAllWheelsEqually) {
  const MecanumGeometry g = Geom();
  const WheelArray w = InverseKinematics(g, {0.3, 0.0, 0.0});
  for (double wi : w) EXPECT_NEAR(wi, 0.3 / g.wheel_radius, 1e-12);
}

TEST(MecanumKinematics, PureSidewaysGivesMinusPlusPlusMinus) {
  const MecanumGeometry g = Geom();
  const WheelArray w = InverseKinematics(g, {0.0, 0.2, 0.0});  // to the left
  const double m = 0.2 / g.wheel_radius;
  EXPECT_NEAR(w[kFrontLeft], -m, 1e-12);
  EXPECT_NEAR(w[kFrontRight], m, 1e-12);
  EXPECT_NEAR(w[kRearLeft], m, 1e-12);
  EXPECT_NEAR(w[kRearRight], -m, 1e-12);
}

TEST(MecanumKinematics, PureRotationGivesMinusPlusMinusPlus) {
  const MecanumGeometry g = Geom();
  const WheelArray w = InverseKinematics(g, {0.0, 0.0, 1.0});  // counter-clockwise
  const double m = (g.half_wheelbase + g.half_track) / g.wheel_radius;
  EXPECT_NEAR(w[kFrontLeft], -m, 1e-12);
  EXPECT_NEAR(w[kFrontRight], m, 1e-12);
  EXPECT_NEAR(w[kRearLeft], -m, 1e-12);
  EXPECT_NEAR(w[kRearRight], m, 1e-12);
}

TEST(MecanumKinematics, NoSlipConditionHoldsAtEveryContact) {
  // r ω_i equals √2 times the contact velocity along the roller axis (the constrained direction).
  const MecanumGeometry g = Geom();
  const BodyTwist t{0.2, -0.1, 0.7};
  const WheelArray w = InverseKinematics(g, t);
  for (int i = 0; i < kMecanumWheels; ++i) {
    const Vec2 p = g.WheelPosition(i);
    const Vec2 vc{t.vx - t.omega * p.y, t.vy + t.omega * p.x};
    EXPECT_NEAR(g.wheel_radius * w[i], std::sqrt(2.0) * vc.Dot(MecanumGeometry::RollerAxis(i)),
                1e-12);
  }
}

TEST(MecanumKinematics, ForwardKinematicsIsLeastSquaresForInconsistentSpeeds) {
  // The front wheels fighting the rear ones, (+, +, -, -), moves nothing: FK ignores it.
  const MecanumGeometry g = Geom();
  WheelArray w = InverseKinematics(g, {0.1, 0.2, 0.3});
  w[0] += 0.5, w[1] += 0.5, w[2] -= 0.5, w[3] -= 0.5;
  const BodyTwist t = ForwardKinematics(g, w);
  EXPECT_NEAR(t.vx, 0.1, 1e-12);
  EXPECT_NEAR(t.vy, 0.2, 1e-12);
  EXPECT_NEAR(t.omega, 0.3, 1e-12);
}

TEST(MecanumKinematics, ScaleToLimitKeepsDirection) {
  WheelArray w{1.0, -4.0, 2.0, 0.5};
  EXPECT_DOUBLE_EQ(ScaleToLimit(w, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(w[1], -2.0);
  EXPECT_DOUBLE_EQ(w[0], 0.5);
  WheelArray u{1.0, -1.0, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(ScaleToLimit(u, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(u[0], 1.0);
}

TEST(DeadReckoning, StraightAndArcAndWrap) {
  DeadReckoning dr;
  dr.Reset({0, 0, 0});
  for (int i = 0; i < 100; ++i) dr.Step({0.3, 0.0, 0.0}, 0.01);
  EXPECT_NEAR(dr.pose().x, 0.3, 1e-12);
  EXPECT_NEAR(dr.pose().y, 0.0, 1e-12);
  // A quarter circle of radius 1 (v = 1, ω = 1) by small steps ends near (1, 1) from the origin.
  dr.Reset({0, 0, 0});
  const int n = 1000;
  for (int i = 0; i < n; ++i) dr.Step({1.0, 0.0, 1.0}, 0.5 * kPi / n);
  EXPECT_NEAR(dr.pose().x, 1.0, 1e-6);
  EXPECT_NEAR(dr.pose().y, 1.0, 1e-6);
  EXPECT_NEAR(dr.pose().theta, 0.5 * kPi, 1e-9);
  // Turning through ±π keeps θ wrapped.
  dr.Reset({0, 0, kPi - 0.05});
  dr.Step({0.0, 0.0, 1.0}, 0.1);
  EXPECT_NEAR(dr.pose().theta, -kPi + 0.05, 1e-12);
}

}  // namespace
}  // namespace formsim::control::agv
