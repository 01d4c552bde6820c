#include "control/velocity/imu_preintegration.hpp"

namespace formsim::control::velocity {

ImuPreintegration::ImuPreintegration(double bg_lin, const Vec2d& ba_lin, const ImuNoise& noise)
    : noise_(noise), bg_lin_(bg_lin), ba_lin_(ba_lin) {}

void ImuPreintegration::Reset() {
  sum_dt_ = dtheta_ = 0.0;
  dv_.setZero();
  dp_.setZero();
  cov_.setZero();
  dtheta_dbg_ = 0.0;
  dv_dbg_.setZero();
  dp_dbg_.setZero();
  dv_dba_.setZero();
  dp_dba_.setZero();
}

void ImuPreintegration::Integrate(double dt, double gyro, const Vec2d& accel) {
  if (!(dt > 0.0)) return;
  samples_.push_back({dt, gyro, accel});
  Step(samples_.back());
}

void ImuPreintegration::Repropagate(double bg_lin, const Vec2d& ba_lin) {
  bg_lin_ = bg_lin;
  ba_lin_ = ba_lin;
  Reset();
  for (const Sample& s : samples_) Step(s);
}

void ImuPreintegration::Step(const Sample& s) {
  const double dt = s.dt, dt2 = dt * dt;
  const double w = s.gyro - bg_lin_;
  const Vec2d a = s.accel - ba_lin_;
  const Mat2d R = Rot(dtheta_ + 0.5 * w * dt);
  const Mat2d J = J90();
  const Vec2d Ra = R * a;
  const Vec2d JRa = J * Ra;

  // Error-state transition A (order θ, v, p) and noise input B (order n_g, n_a) for one sample.
  Eigen::Matrix<double, 5, 5> A = Eigen::Matrix<double, 5, 5>::Identity();
  A.block<2, 1>(1, 0) = JRa * dt;
  A.block<2, 1>(3, 0) = 0.5 * JRa * dt2;
  A.block<2, 2>(3, 1) = Mat2d::Identity() * dt;
  Eigen::Matrix<double, 5, 3> B = Eigen::Matrix<double, 5, 3>::Zero();
  B(0, 0) = -dt;
  B.block<2, 1>(1, 0) = -0.5 * JRa * dt2;
  B.block<2, 1>(3, 0) = -0.25 * JRa * dt2 * dt;
  B.block<2, 2>(1, 1) = R * dt;
  B.block<2, 2>(3, 1) = 0.5 * R * dt2;
  // Discrete white noise of a sample averaged over dt: variance density² / dt.
  Eigen::Vector3d q(noise_.gyro_noise_density * noise_.gyro_noise_density / dt,
                    noise_.accel_noise_density * noise_.accel_noise_density / dt,
                    noise_.accel_noise_density * noise_.accel_noise_density / dt);
  cov_ = A * cov_ * A.transpose() + B * q.asDiagonal() * B.transpose();

  // Bias Jacobians (use the values before this sample's update).
  const double dmid_dbg = dtheta_dbg_ - 0.5 * dt;
  dp_dbg_ += dv_dbg_ * dt + 0.5 * JRa * dmid_dbg * dt2;
  dp_dba_ += dv_dba_ * dt - 0.5 * R * dt2;
  dv_dbg_ += JRa * dmid_dbg * dt;
  dv_dba_ += -R * dt;
  dtheta_dbg_ += -dt;

  dp_ += dv_ * dt + 0.5 * Ra * dt2;
  dv_ += Ra * dt;
  dtheta_ += w * dt;
  sum_dt_ += dt;
}

double ImuPreintegration::CorrectedTheta(double bg) const {
  return dtheta_ + dtheta_dbg_ * (bg - bg_lin_);
}

Vec2d ImuPreintegration::CorrectedV(double bg, const Vec2d& ba) const {
  return dv_ + dv_dbg_ * (bg - bg_lin_) + dv_dba_ * (ba - ba_lin_);
}

Vec2d ImuPreintegration::CorrectedP(double bg, const Vec2d& ba) const {
  return dp_ + dp_dbg_ * (bg - bg_lin_) + dp_dba_ * (ba - ba_lin_);
}

}  // namespace formsim::control::velocity
