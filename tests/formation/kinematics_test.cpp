// Output kinematics of a link and the two laws, checked against finite differences.
#include <gtest/gtest.h>

#include "control/formation/formation_laws.hpp"
#include "control/formation/link_kinematics.hpp"
#include "sim/core/rng.hpp"

namespace formsim::control::formation {
namespace {

// Exact unicycle motion over h with constant (v, ω) (arc), so the finite difference measures
// only the output map, not an integrator.
Pose2 Move(const Pose2& p, const Twist& u, double h) {
  if (std::abs(u.w) < 1e-12)
    return {p.x + u.v * h * std::cos(p.theta), p.y + u.v * h * std::sin(p.theta), p.theta};
  const double th = p.theta + u.w * h;
  return {p.x + u.v / u.w * (std::sin(th) - std::sin(p.theta)),
          p.y - u.v / u.w * (std::cos(th) - std::cos(p.theta)), th};
}

struct RandomCase {
  Pose2 leader, follower;
  Twist ul, uf;
};

RandomCase Draw(sim::Rng& rng) {
  RandomCase c;
  c.leader = {rng.Uniform(-2, 2), rng.Uniform(-2, 2), rng.Uniform(-kPi, kPi)};
  // Follower 0.2-1.2 m away in a random direction, any heading.
  const double r = rng.Uniform(0.2, 1.2), a = rng.Uniform(-kPi, kPi);
  c.follower = {c.leader.x + r * std::cos(a), c.leader.y + r * std::sin(a), rng.Uniform(-kPi, kPi)};
  c.ul = {rng.Uniform(-1, 3), rng.Uniform(-2, 2)};
  c.uf = {rng.Uniform(-1, 3), rng.Uniform(-2, 2)};
  return c;
}

TEST(LinkKinematics, DerivativesMatchFiniteDifferences) {
  sim::Rng rng(42);
  const double L = 0.15, h = 1e-6;
  int checked = 0;
  for (int k = 0; k < 500; ++k) {
    const RandomCase c = Draw(rng);
    const LinkState s = ComputeLinkState(c.leader, c.follower, L);
    if (s.l < 0.05) continue;  // too close to the leader for a clean difference
    const LinkState sp = ComputeLinkState(Move(c.leader, c.ul, h), Move(c.follower, c.uf, h), L);
    const LinkState sm = ComputeLinkState(Move(c.leader, c.ul, -h), Move(c.follower, c.uf, -h), L);
    const LinkRates r = LinkDerivative(s, c.ul, c.uf, L);
    EXPECT_NEAR(r.l_dot, (sp.l - sm.l) / (2 * h), 1e-6) << "case " << k;
    EXPECT_NEAR(r.phi_dot, WrapToPi(sp.phi - sm.phi) / (2 * h), 1e-5 / s.l) << "case " << k;
    EXPECT_NEAR(r.alpha_dot, WrapToPi(sp.alpha - sm.alpha) / (2 * h), 1e-6) << "case " << k;
    ++checked;
  }
  EXPECT_GT(checked, 450);
}

TEST(LinkKinematics, PrintedBearingIsMirroredAndBreaksTheKinematics) {
  // The printed eq. 4 is wrap(−β − θ_i); its derivative is −φ̇_das − 2ω_i, not φ̇_das.
  sim::Rng rng(7);
  const double L = 0.15, h = 1e-6;
  double max_mismatch = 0.0;
  for (int k = 0; k < 200; ++k) {
    const RandomCase c = Draw(rng);
    const LinkState das = ComputeLinkState(c.leader, c.follower, L, BearingConvention::kDas);
    const LinkState pr = ComputeLinkState(c.leader, c.follower, L, BearingConvention::kPrinted);
    EXPECT_NEAR(WrapToPi(pr.phi - WrapToPi(-(das.phi + c.leader.theta) - c.leader.theta)), 0.0,
                1e-9);
    if (das.l < 0.05) continue;
    const LinkState pp = ComputeLinkState(Move(c.leader, c.ul, h), Move(c.follower, c.uf, h), L,
                                          BearingConvention::kPrinted);
    const LinkState pm = ComputeLinkState(Move(c.leader, c.ul, -h), Move(c.follower, c.uf, -h), L,
                                          BearingConvention::kPrinted);
    const double fd = WrapToPi(pp.phi - pm.phi) / (2 * h);
    const double das_rate = LinkDerivative(das, c.ul, c.uf, L).phi_dot;
    EXPECT_NEAR(fd, -das_rate - 2 * c.ul.w, 1e-4);
    max_mismatch = std::max(max_mismatch, std::abs(fd - das_rate));
  }
  EXPECT_GT(max_mismatch, 1.0);  // the Das kinematics do not describe the printed bearing
}

TEST(LinkKinematics, FollowerPoseInvertsTheLinkStateAndJacobianMatches) {
  sim::Rng rng(3);
  const double L = 0.15;
  for (int k = 0; k < 100; ++k) {
    const RandomCase c = Draw(rng);
    const LinkState s = ComputeLinkState(c.leader, c.follower, L);
    const Pose2 back = FollowerPoseFromLink(c.leader, s, L);
    EXPECT_NEAR(back.x, c.follower.x, 1e-12);
    EXPECT_NEAR(back.y, c.follower.y, 1e-12);
    EXPECT_NEAR(WrapToPi(back.theta - c.follower.theta), 0.0, 1e-12);
    const Eigen::Matrix<double, 2, 3> J = FollowerPositionJacobian(c.leader, s, L);
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d(i) = 1e-6;
      const Pose2 p = FollowerPoseFromLink(c.leader, LinkState::FromVec(s.vec() + d), L);
      const Pose2 m = FollowerPoseFromLink(c.leader, LinkState::FromVec(s.vec() - d), L);
      EXPECT_NEAR(J(0, i), (p.x - m.x) / 2e-6, 1e-6);
      EXPECT_NEAR(J(1, i), (p.y - m.y) / 2e-6, 1e-6);
    }
  }
}

TEST(FormationLaws, LPhiLinearisesTheOutputs) {
  sim::Rng rng(11);
  const double L = 0.15;
  const FormationGains k{1.5, 0.8};
  for (int n = 0; n < 200; ++n) {
    const RandomCase c = Draw(rng);
    const LinkState s = ComputeLinkState(c.leader, c.follower, L);
    const double l_des = 0.3, phi_des = 5 * kPi / 4;
    const Twist u = LPhiControl(s, c.ul, l_des, phi_des, k, L);
    const LinkRates r = LinkDerivative(s, c.ul, u, L);
    EXPECT_NEAR(r.l_dot, -k.k1 * (s.l - l_des), 1e-9);
    EXPECT_NEAR(r.phi_dot, -k.k2 * WrapToPi(s.phi - phi_des), 1e-9);
  }
}

TEST(FormationLaws, LLLinearisesTheDistancesAwayFromTheSingularLine) {
  sim::Rng rng(12);
  const double L = 0.15;
  const FormationGains k{1.5, 1.5};
  int regular = 0;
  for (int n = 0; n < 300; ++n) {
    const RandomCase c = Draw(rng);
    const Pose2 leader2 = {rng.Uniform(-2, 2), rng.Uniform(-2, 2), rng.Uniform(-kPi, kPi)};
    const Twist u2 = {rng.Uniform(0, 2), rng.Uniform(-1, 1)};
    const LinkState s1 = ComputeLinkState(c.leader, c.follower, L);
    const LinkState s2 = ComputeLinkState(leader2, c.follower, L);
    const LLCommand out = LLControl(s1, s2, c.ul, u2, 0.3, 0.4, k, L, 0.1);
    EXPECT_NEAR(out.sin_angle, std::sin(s2.gamma() - s1.gamma()), 1e-12);
    if (out.singular) continue;
    ++regular;
    EXPECT_NEAR(LinkDerivative(s1, c.ul, out.cmd, L).l_dot, -k.k1 * (s1.l - 0.3), 1e-8);
    EXPECT_NEAR(LinkDerivative(s2, u2, out.cmd, L).l_dot, -k.k2 * (s2.l - 0.4), 1e-8);
  }
  EXPECT_GT(regular, 200);
}

TEST(FormationLaws, LLStaysBoundedAndContinuousThroughTheSingularity) {
  // Follower control point sweeps across the line through leaders at (0,0) and (1,0).
  const double L = 0.15, thr = 0.1;
  const Pose2 a{0, 0, 0}, b{1, 0, 0};
  const Twist ua{1, 0}, ub{1, 0};
  const FormationGains k{1.5, 1.5};
  double max_speed = 0.0, prev_v = 0.0;
  bool first = true, saw_singular = false;
  for (double y = -0.05; y <= 0.05; y += 1e-4) {
    const Pose2 f{0.5 - L, y, 0.2};
    const LLCommand c = LLControl(ComputeLinkState(a, f, L), ComputeLinkState(b, f, L), ua, ub, 0.6,
                                  0.6, k, L, thr);
    ASSERT_TRUE(std::isfinite(c.cmd.v) && std::isfinite(c.cmd.w));
    saw_singular |= c.singular;
    max_speed = std::max(max_speed, std::hypot(c.cmd.v, L * c.cmd.w));
    if (!first) {
      EXPECT_LT(std::abs(c.cmd.v - prev_v), 0.5) << "jump at y = " << y;
    }
    prev_v = c.cmd.v;
    first = false;
  }
  EXPECT_TRUE(saw_singular);
  // |u'| <= |c| / (2 μ) near the line, with |c| about 1.5 here; far from it the exact inverse.
  EXPECT_LT(max_speed, 50.0);
}

TEST(FormationLaws, GainReadings) {
  EXPECT_DOUBLE_EQ(EffectiveGain(0.15, GainReading::kPrinted, 0.01), 0.15);
  EXPECT_DOUBLE_EQ(EffectiveGain(0.15, GainReading::kPerSample, 0.01), 15.0);
}

}  // namespace
}  // namespace formsim::control::formation
