// The generic UKF (control/common/ukf.hpp) and the link filter built on it.
#include "control/common/ukf.hpp"

#include <gtest/gtest.h>

#include "control/common/linear_kf.hpp"
#include "control/formation/link_filter.hpp"
#include "sim/core/rng.hpp"

namespace formsim::control::formation {
namespace {

TEST(Ukf, EqualsTheKalmanFilterOnALinearModel) {
  // On a linear model the unscented transform is exact: the UKF must match the KF.
  LinearKalmanFilter<2, 1, 1> kf;
  kf.A << 1, 0.1, 0, 1;
  kf.B << 0.005, 0.1;
  kf.H << 1, 0;
  kf.Q = Eigen::Matrix2d::Identity() * 1e-3;
  kf.R << 0.04;
  Ukf<2, 1> ukf;
  const Eigen::Vector2d x0(0.5, -0.2);
  const Eigen::Matrix2d P0 = Eigen::Matrix2d::Identity() * 0.3;
  kf.Reset(x0, P0);
  ukf.Reset(x0, P0);
  sim::Rng rng(5);
  for (int k = 0; k < 50; ++k) {
    const Eigen::Matrix<double, 1, 1> u(rng.Uniform(-1, 1)), z(rng.Normal(0, 1));
    kf.Predict(u);
    ASSERT_EQ(ukf.Predict([&](const Eigen::Vector2d& s) { return kf.A * s + kf.B * u; }, kf.Q),
              UkfStatus::kOk);
    kf.Update(z);
    ASSERT_EQ(ukf.Update(
                  z, [&](const Eigen::Vector2d& s) { return kf.H * s; }, kf.R),
              UkfStatus::kOk);
    EXPECT_LT((ukf.x() - kf.x()).norm(), 1e-9);
    EXPECT_LT((ukf.P() - kf.P()).norm(), 1e-9);
  }
}

TEST(Ukf, WeightsFollowTheScaling) {
  Ukf<3, 2> ukf;  // default: a = 1, b = 2, κ = 0 for n = 3, so λ = 0
  EXPECT_DOUBLE_EQ(ukf.lambda(), 0.0);
  double sum = 0.0;
  for (int i = 0; i < 7; ++i) sum += ukf.weight_mean(i);
  EXPECT_NEAR(sum, 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(ukf.weight_cov(0), 2.0);
}

TEST(Ukf, AveragesAnglesAcrossTheWrap) {
  // State near ±π: a plain mean of sigma points on both sides of the cut would give ~0.
  Ukf<1, 1> ukf;
  ukf.SetAngleStates({0});
  ukf.SetAngleMeas({0});
  ukf.Reset(Eigen::Matrix<double, 1, 1>(kPi - 0.01), Eigen::Matrix<double, 1, 1>(0.04));
  ASSERT_EQ(ukf.Predict([](const Eigen::Matrix<double, 1, 1>& s) { return s; },
                        Eigen::Matrix<double, 1, 1>(1e-4)),
            UkfStatus::kOk);
  EXPECT_NEAR(std::abs(ukf.x()(0)), kPi - 0.01, 1e-3);
  // A measurement just across the cut pulls the estimate the short way.
  ASSERT_EQ(ukf.Update(
                Eigen::Matrix<double, 1, 1>(-kPi + 0.01),
                [](const Eigen::Matrix<double, 1, 1>& s) { return s; },
                Eigen::Matrix<double, 1, 1>(0.04)),
            UkfStatus::kOk);
  EXPECT_GT(std::abs(ukf.x()(0)), kPi - 0.02);
}

TEST(Ukf, ReportsFaultsWithoutTouchingTheState) {
  Ukf<2, 1> ukf;
  Eigen::Matrix2d bad;
  bad << 1, 2, 2, 1;  // indefinite
  ukf.Reset(Eigen::Vector2d(1, 2), bad);
  auto f = [](const Eigen::Vector2d& s) { return s; };
  EXPECT_EQ(ukf.Predict(f, Eigen::Matrix2d::Identity()), UkfStatus::kNotPositiveDefinite);
  EXPECT_EQ(ukf.x(), Eigen::Vector2d(1, 2));

  ukf.Reset(Eigen::Vector2d(1, 2), Eigen::Matrix2d::Identity());
  auto blow = [](const Eigen::Vector2d& s) {
    return Eigen::Vector2d(s(0) / 0.0, s(1));  // inf
  };
  EXPECT_EQ(ukf.Predict(blow, Eigen::Matrix2d::Identity()), UkfStatus::kNonFinite);
  EXPECT_EQ(ukf.x(), Eigen::Vector2d(1, 2));
  EXPECT_EQ(ukf.P(), Eigen::Matrix2d::Identity());

  // A negative measurement variance larger than the predicted spread makes Pyy indefinite.
  EXPECT_EQ(ukf.Update(
                Eigen::Matrix<double, 1, 1>(0.0),
                [](const Eigen::Vector2d& s) { return Eigen::Matrix<double, 1, 1>(s(0)); },
                Eigen::Matrix<double, 1, 1>(-5.0)),
            UkfStatus::kNotPositiveDefinite);
  EXPECT_EQ(ukf.x(), Eigen::Vector2d(1, 2));
}

// Simulates the link's own discrete model with the noise the filter assumes and checks that
// the filter is consistent: the normalised estimation error squared (NEES, 3 dof) averages
// about 3 and lies inside the 95 % chi-square bound most of the time.
TEST(LinkFilter, ConsistentOnItsOwnModel) {
  for (MeasurementSet m : {MeasurementSet::kPhiAlpha, MeasurementSet::kLPhiAlpha}) {
    LinkFilterDef def;
    def.measure = m;
    def.q = {1e-7, 1e-6, 1e-6};
    def.r = {1e-4, 0.9186e-4, 0.9186e-4};
    def.p0 = {1e-4, 1e-3, 1e-3};
    auto filter = LinkFilter::Make(def);
    sim::Rng rng(99);
    LinkState truth{0.3, 5 * kPi / 4 - 2 * kPi, 0.0};
    filter->Reset({truth.l + 0.01, truth.phi + 0.03, truth.alpha - 0.03},
                  Eigen::Matrix3d(def.p0.asDiagonal()));
    double nees_sum = 0.0;
    int inside = 0, n = 0;
    const int steps = 3000;
    for (int k = 0; k < steps; ++k) {
      const double t = k * def.Tc;
      // Inputs that excite the link: a turning leader and a follower keeping roughly in place.
      const Twist leader{2.5, 1.0 * std::sin(0.7 * t)};
      const Twist follower{2.5 + 0.3 * std::sin(1.3 * t), 1.0 * std::sin(0.7 * t - 0.1)};
      const LinkRates r = LinkDerivative(truth, leader, follower, def.L);
      truth.l += def.Tc * r.l_dot + std::sqrt(def.q(0)) * rng.Normal();
      truth.phi = WrapToPi(truth.phi + def.Tc * r.phi_dot + std::sqrt(def.q(1)) * rng.Normal());
      truth.alpha =
          WrapToPi(truth.alpha + def.Tc * r.alpha_dot + std::sqrt(def.q(2)) * rng.Normal());
      const LinkState z{truth.l + std::sqrt(def.r(0)) * rng.Normal(),
                        WrapToPi(truth.phi + std::sqrt(def.r(1)) * rng.Normal()),
                        WrapToPi(truth.alpha + std::sqrt(def.r(2)) * rng.Normal())};
      ASSERT_EQ(filter->Predict(leader, follower), UkfStatus::kOk);
      ASSERT_EQ(filter->Update(z), UkfStatus::kOk);
      if (k < 200) continue;  // initial transient
      const LinkState e = filter->state();
      const Eigen::Vector3d err(e.l - truth.l, WrapToPi(e.phi - truth.phi),
                                WrapToPi(e.alpha - truth.alpha));
      const double nees = err.dot(filter->cov().ldlt().solve(err));
      nees_sum += nees;
      inside += nees < 7.815;  // chi-square(3) 95 %
      ++n;
    }
    const double mean = nees_sum / n;
    EXPECT_GT(mean, 2.0) << MeasurementSetName(m);
    EXPECT_LT(mean, 4.2) << MeasurementSetName(m);
    EXPECT_GT(static_cast<double>(inside) / n, 0.88) << MeasurementSetName(m);
  }
}

TEST(LinkFilter, AlphaOnlyLeavesLUnobservable) {
  LinkFilterDef def;
  def.measure = MeasurementSet::kAlpha;
  auto filter = LinkFilter::Make(def);
  filter->Reset({0.3, 1.0, 0.0}, Eigen::Matrix3d(def.p0.asDiagonal()));
  for (int k = 0; k < 500; ++k) {
    ASSERT_EQ(filter->Predict({2.5, 0.5}, {2.5, 0.5}), UkfStatus::kOk);
    ASSERT_EQ(filter->Update({0.3, 1.0, 0.0}), UkfStatus::kOk);
  }
  // The l variance only grows (by Q each step); α's settles.
  EXPECT_GT(filter->cov()(0, 0), def.p0(0));
  EXPECT_LT(filter->cov()(2, 2), def.p0(2));
}

// ukf.substeps: 1 is the paper's single Euler step (the same numbers as before the option);
// more substeps bring the predicted mean closer to the exact flow of the link kinematics.
TEST(LinkFilter, SubstepsIntegrateTheKinematicsCloser) {
  const Twist leader{2.5, 1.0}, follower{2.0, -0.5};
  const LinkState x0{0.3, 3.9, 0.2};
  auto predicted = [&](int substeps) {
    LinkFilterDef def;
    def.Tc = 0.05;  // a long period, so the Euler error shows
    def.substeps = substeps;
    auto f = LinkFilter::Make(def);
    f->Reset(x0, Eigen::Matrix3d(def.p0.asDiagonal()));
    EXPECT_EQ(f->Predict(leader, follower), UkfStatus::kOk);
    return f->state().vec();
  };
  // The exact flow, by 10^5 Euler steps.
  Eigen::Vector3d x = x0.vec();
  for (int i = 0; i < 100000; ++i) {
    const LinkRates r = LinkDerivative(LinkState::FromVec(x), leader, follower, 0.15);
    x += 0.05 / 100000 * Eigen::Vector3d(r.l_dot, r.phi_dot, r.alpha_dot);
  }
  // Distance between link states, angles wrapped (the filter keeps φ and α in (−π, π]).
  auto dist = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return Eigen::Vector3d(a(0) - b(0), WrapToPi(a(1) - b(1)), WrapToPi(a(2) - b(2))).norm();
  };
  const double e1 = dist(predicted(1), x), e20 = dist(predicted(20), x);
  EXPECT_LT(e20, e1 / 10) << e1 << " " << e20;
  // One substep is the single step: the state is x0 + Tc f(x0) (the UKF's mean of the
  // propagated sigma points differs from it only by their spread).
  const LinkRates r0 = LinkDerivative(x0, leader, follower, 0.15);
  const Eigen::Vector3d euler = x0.vec() + 0.05 * Eigen::Vector3d(r0.l_dot, r0.phi_dot, r0.alpha_dot);
  EXPECT_LT(dist(predicted(1), euler), dist(predicted(20), euler));
}

}  // namespace
}  // namespace formsim::control::formation
