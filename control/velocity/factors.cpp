#include "control/velocity/factors.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::control::velocity {

using S = KeyframeState;

Eigen::MatrixXd SqrtInformation(const Eigen::MatrixXd& cov) {
  const Eigen::Index n = cov.rows();
  Eigen::MatrixXd c = 0.5 * (cov + cov.transpose());
  // Jitter relative to the largest variance keeps the factorisation finite for degenerate
  // intervals without changing well-conditioned ones.
  const double scale = std::max(c.diagonal().maxCoeff(), 1e-30);
  c.diagonal().array() += 1e-12 * scale + 1e-300;
  Eigen::LLT<Eigen::MatrixXd> llt(c);
  const Eigen::MatrixXd L = llt.matrixL();
  return L.triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(n, n));
}

ImuFactor EvaluateImuFactor(const ImuPreintegration& pre, const KeyframeState& i,
                            const KeyframeState& j) {
  ImuFactor f;
  const Mat2d J = J90();
  const Mat2d RiT = Rot(i.theta()).transpose();
  const double dt = pre.sum_dt();
  const Vec2d dv = j.v() - i.v();
  const Vec2d dp = j.p() - i.p() - i.v() * dt;

  f.r(0) = WrapToPi(j.theta() - i.theta() - pre.CorrectedTheta(i.bg()));
  f.r.segment<2>(1) = RiT * dv - pre.CorrectedV(i.bg(), i.ba());
  f.r.segment<2>(3) = RiT * dp - pre.CorrectedP(i.bg(), i.ba());
  f.r(5) = j.bg() - i.bg();
  f.r.segment<2>(6) = j.ba() - i.ba();

  f.Ji.setZero();
  f.Jj.setZero();
  f.Ji(0, S::kTheta) = -1.0;
  f.Ji(0, S::kBg) = -pre.dtheta_dbg();
  f.Ji.block<2, 1>(1, S::kTheta) = -J * RiT * dv;
  f.Ji.block<2, 2>(1, S::kV) = -RiT;
  f.Ji.block<2, 1>(1, S::kBg) = -pre.dv_dbg();
  f.Ji.block<2, 2>(1, S::kBa) = -pre.dv_dba();
  f.Ji.block<2, 1>(3, S::kTheta) = -J * RiT * dp;
  f.Ji.block<2, 2>(3, S::kP) = -RiT;
  f.Ji.block<2, 2>(3, S::kV) = -RiT * dt;
  f.Ji.block<2, 1>(3, S::kBg) = -pre.dp_dbg();
  f.Ji.block<2, 2>(3, S::kBa) = -pre.dp_dba();
  f.Ji(5, S::kBg) = -1.0;
  f.Ji.block<2, 2>(6, S::kBa) = -Mat2d::Identity();

  f.Jj(0, S::kTheta) = 1.0;
  f.Jj.block<2, 2>(1, S::kV) = RiT;
  f.Jj.block<2, 2>(3, S::kP) = RiT;
  f.Jj(5, S::kBg) = 1.0;
  f.Jj.block<2, 2>(6, S::kBa) = Mat2d::Identity();

  // Whitening: pre-integration covariance for (θ, v, p), random-walk variances for the biases.
  Eigen::Matrix<double, 8, 8> U = Eigen::Matrix<double, 8, 8>::Zero();
  U.topLeftCorner<5, 5>() = SqrtInformation(pre.covariance());
  const double t = std::max(dt, 1e-6);
  const ImuNoise& n = pre.noise();
  U(5, 5) = 1.0 / std::max(n.gyro_bias_rw * std::sqrt(t), 1e-12);
  U(6, 6) = U(7, 7) = 1.0 / std::max(n.accel_bias_rw * std::sqrt(t), 1e-12);
  f.r = U * f.r;
  f.Ji = U * f.Ji;
  f.Jj = U * f.Jj;
  return f;
}

OdometryFactor EvaluateOdometryFactor(const OdometryPreintegration& pre, const KeyframeState& i,
                                      const KeyframeState& j) {
  OdometryFactor f;
  const Mat2d J = J90();
  const Mat2d RiT = Rot(i.theta()).transpose();
  const Vec2d dp = j.p() - i.p();

  f.r(0) = WrapToPi(j.theta() - i.theta() - pre.CorrectedTheta(i.bw()));
  f.r.segment<2>(1) = RiT * dp - pre.CorrectedP(i.bv(), i.bw());
  f.r(3) = j.bv() - i.bv();
  f.r(4) = j.bw() - i.bw();

  f.Ji.setZero();
  f.Jj.setZero();
  f.Ji(0, S::kTheta) = -1.0;
  f.Ji(0, S::kBw) = -pre.dtheta_dbw();
  f.Ji.block<2, 1>(1, S::kTheta) = -J * RiT * dp;
  f.Ji.block<2, 2>(1, S::kP) = -RiT;
  f.Ji.block<2, 1>(1, S::kBv) = -pre.dp_dbv();
  f.Ji.block<2, 1>(1, S::kBw) = -pre.dp_dbw();
  f.Ji(3, S::kBv) = -1.0;
  f.Ji(4, S::kBw) = -1.0;
  f.Jj(0, S::kTheta) = 1.0;
  f.Jj.block<2, 2>(1, S::kP) = RiT;
  f.Jj(3, S::kBv) = 1.0;
  f.Jj(4, S::kBw) = 1.0;

  Eigen::Matrix<double, 5, 5> U = Eigen::Matrix<double, 5, 5>::Zero();
  U.topLeftCorner<3, 3>() = SqrtInformation(pre.covariance());
  const double t = std::max(pre.sum_dt(), 1e-6);
  const OdometryNoise& n = pre.noise();
  U(3, 3) = 1.0 / std::max(n.speed_bias_rw * std::sqrt(t), 1e-12);
  U(4, 4) = 1.0 / std::max(n.yaw_rate_bias_rw * std::sqrt(t), 1e-12);
  f.r = U * f.r;
  f.Ji = U * f.Ji;
  f.Jj = U * f.Jj;
  return f;
}

NonholonomicFactor EvaluateNonholonomicFactor(const KeyframeState& k, double sigma) {
  NonholonomicFactor f;
  const Mat2d RT = Rot(k.theta()).transpose();
  const Vec2d vb = RT * k.v();
  const double w = 1.0 / std::max(sigma, 1e-9);
  f.r = w * vb(1);
  f.J.setZero();
  f.J(0, S::kTheta) = w * (-J90() * vb)(1);
  f.J.block<1, 2>(0, S::kV) = w * RT.row(1);
  return f;
}

BearingFactor EvaluateBearingFactor(const KeyframeState& k, const Vec2d& landmark, double bearing,
                                    double sigma, double camera_offset) {
  BearingFactor f;
  const Mat2d RT = Rot(k.theta()).transpose();
  const Vec2d rel = landmark - k.p();
  const Vec2d q = RT * rel - Vec2d(camera_offset, 0.0);
  const double n2 = std::max(q.squaredNorm(), 1e-12);
  const double w = 1.0 / std::max(sigma, 1e-12);
  f.depth = q.x();
  f.r = w * WrapToPi(std::atan2(q.y(), q.x()) - bearing);
  const Eigen::Matrix<double, 1, 2> dh_dq(-q.y() / n2, q.x() / n2);
  f.Jk.setZero();
  f.Jk.block<1, 2>(0, S::kP) = -w * dh_dq * RT;
  f.Jk(0, S::kTheta) = w * dh_dq * (-J90() * RT * rel);
  f.Jf = w * dh_dq * RT;
  return f;
}

AnchoredPoint EvaluateAnchoredPoint(const KeyframeState& anchor, double psi, double rho,
                                    double camera_offset) {
  AnchoredPoint a;
  const Vec2d o(camera_offset, 0.0);
  const Mat2d R = Rot(anchor.theta());
  const double phi = anchor.theta() + psi;
  const Vec2d u(std::cos(phi), std::sin(phi));
  a.f = anchor.p() + R * o + u / rho;
  a.Ja.block<2, 2>(0, S::kP) = Mat2d::Identity();
  a.Jpsi = J90() * u / rho;
  a.Ja.col(S::kTheta) = J90() * R * o + a.Jpsi;
  a.Jrho = -u / (rho * rho);
  return a;
}

AnchorCoordinates EvaluateAnchorCoordinates(const KeyframeState& anchor, const Vec2d& f,
                                            double camera_offset) {
  AnchorCoordinates c;
  const Vec2d o(camera_offset, 0.0);
  const Mat2d R = Rot(anchor.theta());
  const Vec2d d = f - anchor.p() - R * o;
  const double n2 = std::max(d.squaredNorm(), 1e-24), n = std::sqrt(n2);
  c.psi = WrapToPi(std::atan2(d.y(), d.x()) - anchor.theta());
  c.rho = 1.0 / n;
  c.Jf.row(0) = Eigen::RowVector2d(-d.y(), d.x()) / n2;
  c.Jf.row(1) = -d.transpose() / (n2 * n);
  const Vec2d dd_dtheta = -J90() * R * o;  // ∂d/∂θ_a
  c.Ja.setZero();
  c.Ja.block<2, 2>(0, S::kP) = -c.Jf;
  c.Ja.col(S::kTheta) = c.Jf * dd_dtheta;
  c.Ja(0, S::kTheta) -= 1.0;
  return c;
}

InverseDepthBearingFactor EvaluateInverseDepthBearingFactor(const KeyframeState& k,
                                                            const KeyframeState& anchor, double psi,
                                                            double rho, double bearing,
                                                            double sigma, double camera_offset) {
  const AnchoredPoint a = EvaluateAnchoredPoint(anchor, psi, rho, camera_offset);
  const BearingFactor b = EvaluateBearingFactor(k, a.f, bearing, sigma, camera_offset);
  InverseDepthBearingFactor f;
  f.r = b.r;
  f.Jk = b.Jk;
  f.Ja = b.Jf * a.Ja;
  f.Jl(0, 0) = b.Jf * a.Jpsi;
  f.Jl(0, 1) = b.Jf * a.Jrho;
  f.depth = b.depth;
  return f;
}

}  // namespace formsim::control::velocity
