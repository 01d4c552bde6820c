#include "control/velocity/odometry_preintegration.hpp"

namespace formsim::control::velocity {

OdometryPreintegration::OdometryPreintegration(double bv_lin, double bw_lin,
                                               const OdometryNoise& noise)
    : noise_(noise), bv_lin_(bv_lin), bw_lin_(bw_lin) {}

void OdometryPreintegration::Reset() {
  sum_dt_ = dtheta_ = 0.0;
  dp_.setZero();
  cov_.setZero();
  dtheta_dbw_ = 0.0;
  dp_dbv_.setZero();
  dp_dbw_.setZero();
}

void OdometryPreintegration::Integrate(double dt, double speed, double yaw_rate) {
  if (!(dt > 0.0)) return;
  samples_.push_back({dt, speed, yaw_rate});
  Step(samples_.back());
}

void OdometryPreintegration::Repropagate(double bv_lin, double bw_lin) {
  bv_lin_ = bv_lin;
  bw_lin_ = bw_lin;
  Reset();
  for (const Sample& s : samples_) Step(s);
}

void OdometryPreintegration::Step(const Sample& s) {
  const double dt = s.dt;
  const double u = s.speed - bv_lin_;
  const double w = s.yaw_rate - bw_lin_;
  const Mat2d R = Rot(dtheta_ + 0.5 * w * dt);
  const Vec2d step = R * Vec2d(u * dt, 0.0);  // displacement of this sample, keyframe frame
  const Vec2d Jstep = J90() * step;           // its derivative w.r.t. the mid-point angle

  // Error-state transition (θ, p) and noise input (n_v, n_ψ).
  Cov A = Cov::Identity();
  A.block<2, 1>(1, 0) = Jstep;
  Eigen::Matrix<double, 3, 2> B = Eigen::Matrix<double, 3, 2>::Zero();
  B(0, 1) = -dt;
  B.block<2, 1>(1, 0) = R.col(0) * dt;
  B.block<2, 1>(1, 1) = -0.5 * Jstep * dt;
  const Eigen::Vector2d q(noise_.speed_noise_density * noise_.speed_noise_density / dt,
                          noise_.yaw_rate_noise_density * noise_.yaw_rate_noise_density / dt);
  cov_ = A * cov_ * A.transpose() + B * q.asDiagonal() * B.transpose();

  const double dmid_dbw = dtheta_dbw_ - 0.5 * dt;
  dp_dbv_ += -R.col(0) * dt;
  dp_dbw_ += Jstep * dmid_dbw;
  dtheta_dbw_ += -dt;

  dp_ += step;
  dtheta_ += w * dt;
  sum_dt_ += dt;
}

double OdometryPreintegration::CorrectedTheta(double bw) const {
  return dtheta_ + dtheta_dbw_ * (bw - bw_lin_);
}

Vec2d OdometryPreintegration::CorrectedP(double bv, double bw) const {
  return dp_ + dp_dbv_ * (bv - bv_lin_) + dp_dbw_ * (bw - bw_lin_);
}

}  // namespace formsim::control::velocity
