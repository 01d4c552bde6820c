#pragma once
/// \file A linear Kalman filter over fixed-size Eigen types, reusable by every robot.
///
/// Model: x(k+1) = A x(k) + B u(k) + w,  w ~ N(0, Q);  z = H x + v,  v ~ N(0, R).
/// Angle states: pass their indices to `angle_states` and the innovation and the state are
/// wrapped to (-pi, pi] for those components.

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "control/common/angle.hpp"

namespace formsim::control {

template <int N, int U, int M>
class LinearKalmanFilter {
 public:
  using State = Eigen::Matrix<double, N, 1>;
  using Input = Eigen::Matrix<double, U, 1>;
  using Meas = Eigen::Matrix<double, M, 1>;
  using Cov = Eigen::Matrix<double, N, N>;
  using MeasCov = Eigen::Matrix<double, M, M>;

  Eigen::Matrix<double, N, N> A = Eigen::Matrix<double, N, N>::Identity();
  Eigen::Matrix<double, N, U> B = Eigen::Matrix<double, N, U>::Zero();
  Eigen::Matrix<double, M, N> H = Eigen::Matrix<double, M, N>::Identity();
  Cov Q = Cov::Identity() * 1e-4;
  MeasCov R = MeasCov::Identity() * 1e-2;
  std::vector<int> angle_states;  ///< indices of x (and z, where H = I) that are angles

  void Reset(const State& x0, const Cov& P0) {
    x_ = x0;
    P_ = P0;
  }

  /// Time update with input u.
  void Predict(const Input& u) {
    x_ = A * x_ + B * u;
    P_ = A * P_ * A.transpose() + Q;
    WrapAngles(x_);
  }

  /// Innovation z - H x, with angle components wrapped.
  Meas Innovation(const Meas& z) const {
    Meas y = z - H * x_;
    for (int i : angle_states)
      if (i < M) y(i) = WrapToPi(y(i));
    return y;
  }

  /// Innovation covariance S = H P H' + R.
  MeasCov InnovationCov() const { return H * P_ * H.transpose() + R; }

  /// Normalised innovation squared y' S^-1 y (chi-square with M dof when the model is right).
  double Nis(const Meas& z) const {
    const Meas y = Innovation(z);
    return y.dot(InnovationCov().ldlt().solve(y));
  }

  /// Measurement update (Joseph form, keeps P symmetric positive definite).
  void Update(const Meas& z) {
    const Meas y = Innovation(z);
    const MeasCov S = InnovationCov();
    const Eigen::Matrix<double, N, M> K = P_ * H.transpose() * S.inverse();
    x_ = x_ + K * y;
    const Cov I_KH = Cov::Identity() - K * H;
    P_ = I_KH * P_ * I_KH.transpose() + K * R * K.transpose();
    P_ = 0.5 * (P_ + P_.transpose());
    WrapAngles(x_);
  }

  const State& x() const { return x_; }
  const Cov& P() const { return P_; }
  State& mutable_x() { return x_; }

 private:
  void WrapAngles(State& x) const {
    for (int i : angle_states) x(i) = WrapToPi(x(i));
  }
  State x_ = State::Zero();
  Cov P_ = Cov::Identity();
};

}  // namespace formsim::control
