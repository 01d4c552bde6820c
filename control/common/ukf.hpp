#pragma once
/// \file An unscented Kalman filter over fixed-size Eigen types (Wan & van der Merwe 2000, as
/// used by paper 000, eq. 12-21), reusable by every robot.
///
/// Usage (mherb/kalman style: the model is a callable, the filter owns x and P):
///   Ukf<3, 2> ukf;  ukf.Reset(x0, P0);  ukf.SetAngleStates({1, 2});  ukf.SetAngleMeas({0, 1});
///   ukf.Predict([&](const Ukf<3, 2>::State& s) { return s + Tc * F(s) * u; }, Q);   // Γ(s, u)
///   ukf.Update(z, [&](const Ukf<3, 2>::State& s) { return D * s; }, R);
///
/// Sigma points (eq. 12): 2n+1 points s̄, s̄ ± columns of the Cholesky factor of (n+λ)P, with
/// λ = a²(n+κ) − n, W0m = λ/(n+λ), W0c = W0m + 1 − a² + b, Wi = 1/(2(n+λ)). After the
/// prediction the points are redrawn from the predicted mean and covariance (eq. 16).
///
/// Angles: components flagged as angles are averaged as circular means (atan2 of the weighted
/// sines and cosines), and their deviations and residuals are wrapped to (−π, π].
///
/// Faults: if a covariance is not symmetric positive definite (its Cholesky factorisation fails)
/// or anything becomes non-finite, the step is abandoned, x and P keep their previous values and
/// a fault status is returned; the caller decides (e.g. reset P and report an event).

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <initializer_list>

#include "control/common/angle.hpp"

namespace formsim::control {

/// Result of a UKF step.
enum class UkfStatus {
  kOk = 0,
  kNotPositiveDefinite,  ///< P, the predicted P or the innovation covariance lost definiteness
  kNonFinite,            ///< a NaN or infinity appeared in the state, a sigma point or P
};

/// Human-readable name of a status ("ok", "covariance not positive definite", "non-finite").
inline const char* UkfStatusName(UkfStatus s) {
  switch (s) {
    case UkfStatus::kOk:
      return "ok";
    case UkfStatus::kNotPositiveDefinite:
      return "covariance not positive definite";
    case UkfStatus::kNonFinite:
      return "non-finite value";
  }
  return "unknown";
}

/// Scaling of the sigma points. Defaults follow the paper's choice a = 1, b = 2 (δ in the
/// paper), κ = 3 − n (so λ = 3 − n).
struct UkfScaling {
  double alpha = 1.0;
  double beta = 2.0;
  double kappa = 0.0;  ///< used as given; see DefaultUkfScaling for κ = 3 − n
};
/// The paper's scaling for an n-dimensional state: a = 1, b = 2, κ = 3 − n.
inline UkfScaling DefaultUkfScaling(int n) {
  return UkfScaling{1.0, 2.0, 3.0 - n};
}

template <int N, int M>
class Ukf {
 public:
  static_assert(N > 0 && M > 0, "fixed sizes only");
  static constexpr int kSigma = 2 * N + 1;
  using State = Eigen::Matrix<double, N, 1>;
  using Meas = Eigen::Matrix<double, M, 1>;
  using Cov = Eigen::Matrix<double, N, N>;
  using MeasCov = Eigen::Matrix<double, M, M>;
  using CrossCov = Eigen::Matrix<double, N, M>;

  Ukf() { SetScaling(DefaultUkfScaling(N)); }

  /// Sets a, b, κ and recomputes the weights.
  void SetScaling(const UkfScaling& s) {
    scaling_ = s;
    lambda_ = s.alpha * s.alpha * (N + s.kappa) - N;
    const double c = N + lambda_;
    wm_[0] = lambda_ / c;
    wc_[0] = wm_[0] + 1.0 - s.alpha * s.alpha + s.beta;
    for (int i = 1; i < kSigma; ++i) wm_[i] = wc_[i] = 0.5 / c;
  }
  const UkfScaling& scaling() const { return scaling_; }
  double lambda() const { return lambda_; }
  double weight_mean(int i) const { return wm_[i]; }
  double weight_cov(int i) const { return wc_[i]; }

  /// Marks state components that are angles (circular means, wrapped deviations).
  void SetAngleStates(std::initializer_list<int> idx) { SetFlags(angle_state_, idx); }
  /// Marks measurement components that are angles (wrapped residuals).
  void SetAngleMeas(std::initializer_list<int> idx) { SetFlags(angle_meas_, idx); }
  void SetAngleState(int i, bool is_angle) { angle_state_[i] = is_angle; }
  void SetAngleMeasComponent(int i, bool is_angle) { angle_meas_[i] = is_angle; }

  void Reset(const State& x0, const Cov& P0) {
    x_ = x0;
    P_ = P0;
    WrapState(x_);
  }

  /// Time update (eq. 13-15): propagates the sigma points through `f` (State -> State) and adds
  /// the process noise covariance Q.
  template <class F>
  UkfStatus Predict(F&& f, const Cov& Q) {
    std::array<State, kSigma> pts;
    UkfStatus st = SigmaPoints(x_, P_, pts);
    if (st != UkfStatus::kOk) return st;
    for (auto& p : pts) {
      p = f(static_cast<const State&>(p));
      if (!p.allFinite()) return UkfStatus::kNonFinite;
    }
    const State mean = MeanState(pts);
    Cov P = Q;
    for (int i = 0; i < kSigma; ++i) {
      const State d = StateDiff(pts[i], mean);
      P.noalias() += wc_[i] * d * d.transpose();
    }
    P = 0.5 * (P + P.transpose());
    if (!mean.allFinite() || !P.allFinite()) return UkfStatus::kNonFinite;
    if (Eigen::LLT<Cov>(P).info() != Eigen::Success) return UkfStatus::kNotPositiveDefinite;
    x_ = mean;
    P_ = P;
    return UkfStatus::kOk;
  }

  /// Measurement update (eq. 16-21) with measurement function `h` (State -> Meas) and noise R.
  template <class H>
  UkfStatus Update(const Meas& z, H&& h, const MeasCov& R) {
    std::array<State, kSigma> pts;
    UkfStatus st = SigmaPoints(x_, P_, pts);
    if (st != UkfStatus::kOk) return st;
    std::array<Meas, kSigma> ys;
    for (int i = 0; i < kSigma; ++i) {
      ys[i] = h(static_cast<const State&>(pts[i]));
      if (!ys[i].allFinite()) return UkfStatus::kNonFinite;
    }
    const Meas y_mean = MeanMeas(ys);
    MeasCov Pyy = R;
    CrossCov Psy = CrossCov::Zero();
    for (int i = 0; i < kSigma; ++i) {
      const Meas dy = MeasDiff(ys[i], y_mean);
      const State ds = StateDiff(pts[i], x_);
      Pyy.noalias() += wc_[i] * dy * dy.transpose();
      Psy.noalias() += wc_[i] * ds * dy.transpose();
    }
    Pyy = 0.5 * (Pyy + Pyy.transpose());
    const Eigen::LLT<MeasCov> llt(Pyy);
    if (!Pyy.allFinite()) return UkfStatus::kNonFinite;
    if (llt.info() != Eigen::Success) return UkfStatus::kNotPositiveDefinite;
    // K = Psy Pyy^-1, computed as (Pyy^-1 Psy')' with the Cholesky factor.
    const CrossCov K = llt.solve(Psy.transpose()).transpose();
    const Meas innovation = MeasDiff(z, y_mean);
    last_nis_ = innovation.dot(llt.solve(innovation));
    State x = x_ + K * innovation;
    Cov P = P_ - K * Pyy * K.transpose();
    P = 0.5 * (P + P.transpose());
    WrapState(x);
    if (!x.allFinite() || !P.allFinite()) return UkfStatus::kNonFinite;
    if (Eigen::LLT<Cov>(P).info() != Eigen::Success) return UkfStatus::kNotPositiveDefinite;
    x_ = x;
    P_ = P;
    return UkfStatus::kOk;
  }

  const State& x() const { return x_; }
  const Cov& P() const { return P_; }
  /// Normalised innovation squared of the last successful update.
  double last_nis() const { return last_nis_; }

  /// Sigma points of (mean, P) (eq. 12). Fails when P is not positive definite.
  UkfStatus SigmaPoints(const State& mean, const Cov& P, std::array<State, kSigma>& pts) const {
    if (!mean.allFinite() || !P.allFinite()) return UkfStatus::kNonFinite;
    const Eigen::LLT<Cov> llt((N + lambda_) * P);
    if (llt.info() != Eigen::Success) return UkfStatus::kNotPositiveDefinite;
    const Cov S = llt.matrixL();
    pts[0] = mean;
    for (int i = 0; i < N; ++i) {
      pts[1 + i] = mean + S.col(i);
      pts[1 + N + i] = mean - S.col(i);
    }
    return UkfStatus::kOk;
  }

 private:
  template <std::size_t K>
  static void SetFlags(std::array<bool, K>& flags, std::initializer_list<int> idx) {
    flags.fill(false);
    for (int i : idx) flags[i] = true;
  }
  void WrapState(State& x) const {
    for (int i = 0; i < N; ++i)
      if (angle_state_[i]) x(i) = WrapToPi(x(i));
  }
  State StateDiff(const State& a, const State& b) const {
    State d = a - b;
    for (int i = 0; i < N; ++i)
      if (angle_state_[i]) d(i) = WrapToPi(d(i));
    return d;
  }
  Meas MeasDiff(const Meas& a, const Meas& b) const {
    Meas d = a - b;
    for (int i = 0; i < M; ++i)
      if (angle_meas_[i]) d(i) = WrapToPi(d(i));
    return d;
  }
  // Weighted mean; angle components as the circular mean atan2(Σ w sin, Σ w cos).
  template <class Vec, std::size_t K, std::size_t D>
  Vec Mean(const std::array<Vec, K>& pts, const std::array<bool, D>& angle) const {
    Vec mean = Vec::Zero();
    for (std::size_t i = 0; i < K; ++i) mean += wm_[i] * pts[i];
    for (std::size_t c = 0; c < D; ++c) {
      if (!angle[c]) continue;
      double s = 0.0, co = 0.0;
      for (std::size_t i = 0; i < K; ++i) {
        s += wm_[i] * std::sin(pts[i](c));
        co += wm_[i] * std::cos(pts[i](c));
      }
      mean(c) = std::atan2(s, co);
    }
    return mean;
  }
  State MeanState(const std::array<State, kSigma>& pts) const { return Mean(pts, angle_state_); }
  Meas MeanMeas(const std::array<Meas, kSigma>& ys) const { return Mean(ys, angle_meas_); }

  UkfScaling scaling_;
  double lambda_ = 0.0;
  std::array<double, kSigma> wm_{}, wc_{};
  std::array<bool, N> angle_state_{};
  std::array<bool, M> angle_meas_{};
  State x_ = State::Zero();
  Cov P_ = Cov::Identity();
  double last_nis_ = 0.0;
};

}  // namespace formsim::control
