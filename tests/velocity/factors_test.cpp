// Analytic Jacobians of every residual against central finite differences.
#include "control/velocity/factors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "control/common/angle.hpp"

namespace cv = formsim::control::velocity;
using cv::KeyframeState;
using cv::Vec2d;

namespace {

KeyframeState MakeState(double seed) {
  KeyframeState s;
  for (int i = 0; i < KeyframeState::kDim; ++i) s.x(i) = 0.3 * std::sin(seed * (i + 1) + 0.7 * i);
  s.set_p(Vec2d(1.0 + seed, -0.5 * seed));
  s.set_theta(0.4 + 0.3 * seed);
  return s;
}

// d f / d x_k by central differences, f returning a vector.
Eigen::MatrixXd NumericJacobian(const std::function<Eigen::VectorXd(const KeyframeState&)>& f,
                                const KeyframeState& x) {
  const double h = 1e-6;
  Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd J(f0.size(), KeyframeState::kDim);
  for (int i = 0; i < KeyframeState::kDim; ++i) {
    KeyframeState a = x, b = x;
    a.x(i) += h;
    b.x(i) -= h;
    J.col(i) = (f(a) - f(b)) / (2 * h);
  }
  return J;
}

cv::ImuPreintegration SomeImu() {
  cv::ImuNoise n;
  cv::ImuPreintegration pre(0.01, Vec2d(0.03, -0.02), n);
  for (int k = 0; k < 40; ++k)
    pre.Integrate(0.005, 0.3 + 0.2 * std::sin(0.1 * k), Vec2d(0.4 * std::cos(0.2 * k), 0.1));
  return pre;
}

}  // namespace

TEST(Factors, ImuJacobians) {
  const cv::ImuPreintegration pre = SomeImu();
  const KeyframeState i = MakeState(0.3), j = MakeState(0.8);
  const cv::ImuFactor f = cv::EvaluateImuFactor(pre, i, j);
  const auto Ji = NumericJacobian(
      [&](const KeyframeState& x) { return Eigen::VectorXd(cv::EvaluateImuFactor(pre, x, j).r); },
      i);
  const auto Jj = NumericJacobian(
      [&](const KeyframeState& x) { return Eigen::VectorXd(cv::EvaluateImuFactor(pre, i, x).r); },
      j);
  EXPECT_LT((Ji - f.Ji).norm() / f.Ji.norm(), 1e-6);
  EXPECT_LT((Jj - f.Jj).norm() / f.Jj.norm(), 1e-6);
}

TEST(Factors, OdometryJacobians) {
  cv::OdometryPreintegration pre(0.02, -0.01, cv::OdometryNoise{});
  for (int k = 0; k < 12; ++k) pre.Integrate(0.02, 0.5 + 0.01 * k, 0.3 - 0.02 * k);
  const KeyframeState i = MakeState(0.2), j = MakeState(0.6);
  const cv::OdometryFactor f = cv::EvaluateOdometryFactor(pre, i, j);
  const auto Ji = NumericJacobian(
      [&](const KeyframeState& x) {
        return Eigen::VectorXd(cv::EvaluateOdometryFactor(pre, x, j).r);
      },
      i);
  const auto Jj = NumericJacobian(
      [&](const KeyframeState& x) {
        return Eigen::VectorXd(cv::EvaluateOdometryFactor(pre, i, x).r);
      },
      j);
  EXPECT_LT((Ji - f.Ji).norm() / f.Ji.norm(), 1e-6);
  EXPECT_LT((Jj - f.Jj).norm() / f.Jj.norm(), 1e-6);
}

TEST(Factors, OdometryBiasJacobiansMatchReintegration) {
  cv::OdometryPreintegration pre(0.0, 0.0, cv::OdometryNoise{});
  for (int k = 0; k < 25; ++k) pre.Integrate(0.02, 0.45, 0.8);
  const double h = 1e-6;
  cv::OdometryPreintegration p1 = pre;
  p1.Repropagate(h, 0.0);
  EXPECT_LT(((p1.delta_p() - pre.delta_p()) / h - pre.dp_dbv()).norm(), 1e-5);
  p1 = pre;
  p1.Repropagate(0.0, h);
  EXPECT_LT(((p1.delta_p() - pre.delta_p()) / h - pre.dp_dbw()).norm(), 1e-5);
  EXPECT_NEAR((p1.delta_theta() - pre.delta_theta()) / h, pre.dtheta_dbw(), 1e-6);
}

TEST(Factors, BearingAndNonholonomicJacobians) {
  const KeyframeState k = MakeState(0.5);
  const Vec2d landmark = k.p() + cv::Rot(k.theta()) * Vec2d(3.0, 1.2);
  const double z = 0.35;
  const cv::BearingFactor f = cv::EvaluateBearingFactor(k, landmark, z, 0.01, 0.1);
  EXPECT_GT(f.depth, 0.0);
  const auto Jk = NumericJacobian(
      [&](const KeyframeState& x) {
        return Eigen::VectorXd::Constant(1,
                                         cv::EvaluateBearingFactor(x, landmark, z, 0.01, 0.1).r);
      },
      k);
  EXPECT_LT((Jk - f.Jk).norm() / f.Jk.norm(), 1e-6);
  const double h = 1e-6;
  for (int a = 0; a < 2; ++a) {
    Vec2d lp = landmark, lm = landmark;
    lp(a) += h;
    lm(a) -= h;
    const double num = (cv::EvaluateBearingFactor(k, lp, z, 0.01, 0.1).r -
                        cv::EvaluateBearingFactor(k, lm, z, 0.01, 0.1).r) /
                       (2 * h);
    EXPECT_NEAR(num, f.Jf(a), 1e-5 * f.Jf.cwiseAbs().maxCoeff());
  }
  const cv::NonholonomicFactor nh = cv::EvaluateNonholonomicFactor(k, 0.05);
  const auto Jn = NumericJacobian(
      [&](const KeyframeState& x) {
        return Eigen::VectorXd::Constant(1, cv::EvaluateNonholonomicFactor(x, 0.05).r);
      },
      k);
  EXPECT_LT((Jn - nh.J).norm() / nh.J.norm(), 1e-6);
}

// The inverse-depth landmark: the bearing factor's Jacobians w.r.t. the observing keyframe,
// the anchor keyframe, ψ and ρ against central differences; the anchored point lies on the
// ray ψ from the anchor's camera at distance 1/ρ; the anchor coordinates of a point invert it,
// with their Jacobians.
TEST(Factors, InverseDepthBearingJacobians) {
  const KeyframeState k = MakeState(0.5), a = MakeState(0.1);
  const double psi = 0.2, rho = 0.25, z = 0.35, sigma = 0.01, off = 0.1;
  const cv::InverseDepthBearingFactor f =
      cv::EvaluateInverseDepthBearingFactor(k, a, psi, rho, z, sigma, off);
  auto r_of = [&](const KeyframeState& kk, const KeyframeState& aa, double pp, double rr) {
    return Eigen::VectorXd::Constant(
        1, cv::EvaluateInverseDepthBearingFactor(kk, aa, pp, rr, z, sigma, off).r);
  };
  const auto Jk = NumericJacobian([&](const KeyframeState& x) { return r_of(x, a, psi, rho); }, k);
  const auto Ja = NumericJacobian([&](const KeyframeState& x) { return r_of(k, x, psi, rho); }, a);
  EXPECT_LT((Jk - f.Jk).norm() / f.Jk.norm(), 1e-6);
  EXPECT_LT((Ja - f.Ja).norm() / f.Ja.norm(), 1e-6);
  EXPECT_GT(f.Ja.norm(), 0.1 * f.Jk.norm());  // the anchor's pose matters
  const double h = 1e-7;
  EXPECT_NEAR((r_of(k, a, psi + h, rho)(0) - r_of(k, a, psi - h, rho)(0)) / (2 * h), f.Jl(0),
              1e-6 * std::abs(f.Jl(0)));
  EXPECT_NEAR((r_of(k, a, psi, rho + h)(0) - r_of(k, a, psi, rho - h)(0)) / (2 * h), f.Jl(1),
              1e-6 * std::abs(f.Jl(1)));
  // The point: on the ray ψ from the anchor's camera, 1/ρ away.
  const cv::AnchoredPoint p = cv::EvaluateAnchoredPoint(a, psi, rho, off);
  const Vec2d c = a.p() + cv::Rot(a.theta()) * Vec2d(off, 0.0);
  EXPECT_NEAR((p.f - c).norm(), 1.0 / rho, 1e-12);
  EXPECT_NEAR(std::atan2((p.f - c).y(), (p.f - c).x()), a.theta() + psi, 1e-12);
  // Seen from its anchor the bearing factor is ψ − z.
  EXPECT_NEAR(cv::EvaluateInverseDepthBearingFactor(a, a, psi, rho, z, sigma, off).r,
              (psi - z) / sigma, 1e-9);
  // Its anchor coordinates give ψ and ρ back; Jacobians by differences.
  const cv::AnchorCoordinates ac = cv::EvaluateAnchorCoordinates(a, p.f, off);
  EXPECT_NEAR(ac.psi, psi, 1e-12);
  EXPECT_NEAR(ac.rho, rho, 1e-12);
  for (int row = 0; row < 2; ++row) {
    const auto Jc = NumericJacobian(
        [&](const KeyframeState& x) {
          const cv::AnchorCoordinates c2 = cv::EvaluateAnchorCoordinates(x, p.f, off);
          return Eigen::VectorXd::Constant(1, row == 0 ? c2.psi : c2.rho);
        },
        a);
    EXPECT_LT((Jc - ac.Ja.row(row)).norm() / ac.Ja.row(row).norm(), 1e-6) << row;
    for (int i = 0; i < 2; ++i) {
      Vec2d fp = p.f, fm = p.f;
      fp(i) += h;
      fm(i) -= h;
      const auto cp = cv::EvaluateAnchorCoordinates(a, fp, off),
                 cm = cv::EvaluateAnchorCoordinates(a, fm, off);
      EXPECT_NEAR(((row == 0 ? cp.psi : cp.rho) - (row == 0 ? cm.psi : cm.rho)) / (2 * h),
                  ac.Jf(row, i), 1e-6)
          << row << " " << i;
    }
  }
}

TEST(Factors, ZeroResidualForConsistentMotion) {
  // A state pair that agrees with the pre-integrated motion gives a zero IMU residual.
  const cv::ImuPreintegration pre = SomeImu();
  KeyframeState i = MakeState(0.1);
  i.set_bg(pre.lin_bg());
  i.set_ba(pre.lin_ba());
  KeyframeState j = i;
  const cv::Mat2d R = cv::Rot(i.theta());
  j.set_theta(formsim::control::WrapToPi(i.theta() + pre.delta_theta()));
  j.set_v(i.v() + R * pre.delta_v());
  j.set_p(i.p() + i.v() * pre.sum_dt() + R * pre.delta_p());
  EXPECT_LT(cv::EvaluateImuFactor(pre, i, j).r.norm(), 1e-9);
}
