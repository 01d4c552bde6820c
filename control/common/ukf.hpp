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
/// sines and cosines), and their deviations and residuals are wrapped to (−π, π]. The circular
/// mean is taken around the first point, atan2(Σ w sin(aᵢ − a₀), Σ w cos(aᵢ − a₀)) + a₀, which is
/// the same angle and lets the small deviations use SinCosSmall instead of libm.
///
/// Selection measurements (y = D s, D picks components of s, as the link filter's [φ, α]): the
/// unscented transform of a selection is exact, so UpdateSelection computes the update in
/// closed form, K = P Dᵀ (D P Dᵀ + R)⁻¹, which equals the sigma-point update up to rounding
/// whenever the sigma points' angle spreads stay well inside ±π (checked: (n+λ)Pₖₖ < 9 for
/// every angle state and Pₖₖ < 1 for every measured angle, so no deviation is wrapped and no
/// circular mean flips); otherwise it runs the sigma-point update.
///
/// Faults: if a covariance is not symmetric positive definite (its Cholesky factorisation fails)
/// or anything becomes non-finite, the step is abandoned, x and P keep their previous values and
/// a fault status is returned; the caller decides (e.g. reset P and report an event).

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

/// Lower Cholesky factor L of a small symmetric matrix A (A = L Lᵀ), plain loops that the
/// compiler unrolls for fixed sizes. Returns false when A is not positive definite (a pivot
/// ≤ 0 or NaN), like Eigen::LLT's info().
// The small factorisations and solves are inlined into each filter step so that their operands
// stay in registers (called through memory, the solve's results were reloaded before the stores
// had completed, which stalls store forwarding).
#if defined(__GNUC__)
#define FORMSIM_UKF_INLINE inline __attribute__((always_inline))
#else
#define FORMSIM_UKF_INLINE inline
#endif

template <int K>
FORMSIM_UKF_INLINE bool CholeskyLower(const Eigen::Matrix<double, K, K>& A,
                                      Eigen::Matrix<double, K, K>& L) {
  L.setZero();
  for (int j = 0; j < K; ++j) {
    double d = A(j, j);
    for (int k = 0; k < j; ++k) d -= L(j, k) * L(j, k);
    if (!(d > 0.0)) return false;
    const double ljj = std::sqrt(d), inv = 1.0 / ljj;
    L(j, j) = ljj;
    for (int i = j + 1; i < K; ++i) {
      double v = A(i, j);
      for (int k = 0; k < j; ++k) v -= L(i, k) * L(j, k);
      L(i, j) = v * inv;
    }
  }
  return true;
}

/// Solves L Lᵀ x = b in place with a lower Cholesky factor and the reciprocals of its diagonal
/// (`inv`, shared by several solves with the same factor). The unknowns live in a local array
/// that the compiler keeps in registers.
template <int K>
FORMSIM_UKF_INLINE void CholeskySolveInPlace(const Eigen::Matrix<double, K, K>& L,
                                             const double (&inv)[K],
                                             Eigen::Matrix<double, K, 1>& b) {
  double x[K];
  for (int i = 0; i < K; ++i) {
    double v = b(i);
    for (int k = 0; k < i; ++k) v -= L(i, k) * x[k];
    x[i] = v * inv[i];
  }
  for (int i = K - 1; i >= 0; --i) {
    double v = x[i];
    for (int k = i + 1; k < K; ++k) v -= L(k, i) * x[k];
    x[i] = v * inv[i];
  }
  for (int i = 0; i < K; ++i) b(i) = x[i];
}

/// Solves L Lᵀ x = b in place with a lower Cholesky factor.
template <int K>
FORMSIM_UKF_INLINE void CholeskySolveInPlace(const Eigen::Matrix<double, K, K>& L,
                                             Eigen::Matrix<double, K, 1>& b) {
  double inv[K];
  for (int i = 0; i < K; ++i) inv[i] = 1.0 / L(i, i);
  CholeskySolveInPlace<K>(L, inv, b);
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
  /// The 2n+1 sigma points: [0] the mean, [1 + i] mean + column i, [1 + n + i] mean − column i
  /// of the Cholesky factor of (n+λ)P.
  using SigmaSet = std::array<State, kSigma>;

  Ukf() { SetScaling(DefaultUkfScaling(N)); }

  /// Sets a, b, κ and recomputes the weights.
  void SetScaling(const UkfScaling& s) {
    scaling_ = s;
    lambda_ = s.alpha * s.alpha * (N + s.kappa) - N;
    const double c = N + lambda_;
    wm_[0] = lambda_ / c;
    wc_[0] = wm_[0] + 1.0 - s.alpha * s.alpha + s.beta;
    for (int i = 1; i < kSigma; ++i) wm_[i] = wc_[i] = 0.5 / c;
    sqrt_c_ = c > 0.0 ? std::sqrt(c) : 0.0;
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
    chol_valid_ = false;
    pd_known_ = false;
  }

  /// Time update (eq. 13-15): propagates the sigma points through `f` (State -> State) and adds
  /// the process noise covariance Q.
  template <class F>
  UkfStatus Predict(F&& f, const Cov& Q) {
    return PredictSigma(
        [&](const SigmaSet& in, SigmaSet& out) {
          for (int i = 0; i < kSigma; ++i) out[i] = f(in[i]);
        },
        Q);
  }

  /// The same time update with a model that maps all sigma points at once,
  /// g(const SigmaSet& points, SigmaSet& out), so that it can share work between them (their
  /// layout is SigmaSet's: a mean and ± columns).
  template <class G>
  UkfStatus PredictSigma(G&& g, const Cov& Q) {
    SigmaSet pts;
    UkfStatus st = CurrentSigmaPoints(pts);
    if (st != UkfStatus::kOk) return st;
    SigmaSet out;
    g(static_cast<const SigmaSet&>(pts), out);
    for (const State& p : out)
      if (!p.allFinite()) return UkfStatus::kNonFinite;
    const State mean = MeanState(out);
    Cov P = Q;
    AddSpread(P, out, mean);
    Symmetrize(P);
    // Only checked here: the closed-form update that usually follows needs no factor.
    return Accept(mean, P, /*factor=*/false);
  }

  /// Measurement update (eq. 16-21) with measurement function `h` (State -> Meas) and noise R.
  template <class H>
  UkfStatus Update(const Meas& z, H&& h, const MeasCov& R) {
    SigmaSet pts;
    UkfStatus st = CurrentSigmaPoints(pts);
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
    return Correct(z, y_mean, Pyy, Psy);
  }

  /// Measurement update for y = D s where D selects the components `idx` of s (y(k) = s(idx[k])).
  /// Closed form when it is exact (see the file comment), else the sigma-point update.
  UkfStatus UpdateSelection(const Meas& z, const std::array<int, M>& idx, const MeasCov& R) {
    if (!x_.allFinite() || !P_.allFinite()) return UkfStatus::kNonFinite;
    if (!ClosedFormExact(idx))
      return Update(
          z,
          [&](const State& s) {
            Meas y;
            for (int k = 0; k < M; ++k) y(k) = s(idx[k]);
            return y;
          },
          R);
    // The sigma-point update would fail here when (n+λ)P is not positive definite.
    if (!pd_known_) {
      Cov L;
      if (!CholeskyLower<N>(P_, L)) return UkfStatus::kNotPositiveDefinite;
      Factored(L);
    }
    Meas y_mean;
    MeasCov Pyy = R;
    CrossCov Psy;
    for (int a = 0; a < M; ++a) {
      y_mean(a) = x_(idx[a]);
      for (int b = 0; b < M; ++b) Pyy(a, b) += P_(idx[a], idx[b]);
      for (int r = 0; r < N; ++r) Psy(r, a) = P_(r, idx[a]);
    }
    return Correct(z, y_mean, Pyy, Psy);
  }

  const State& x() const { return x_; }
  const Cov& P() const { return P_; }

  /// For a caller that updates several filters at once (SIMD lanes, link_update_lanes.hpp) and
  /// must give the same bits as UpdateSelection: true when UpdateSelection with `idx` would take
  /// the closed form with a covariance already known positive definite, or would fault on a
  /// non-finite x or P (unchecked here: every value of x and P reaches the new x or P, so the
  /// caller finds a non-finite result and runs UpdateSelection, which reports the fault).
  bool ClosedFormMayRun(const std::array<int, M>& idx) const {
    return pd_known_ && ClosedFormExact(idx);
  }
  /// The end of a closed-form update the caller computed with Correct's and Accept's operations
  /// and found finite and positive definite: the new state, P, its lower Cholesky factor, the NIS.
  void AcceptCorrected(const State& x, const Cov& P, const Cov& chol, double nis) {
    last_nis_ = nis;
    x_ = x;
    P_ = P;
    Factored(chol);
  }

  /// For a caller that propagates the sigma points of several filters at once (SIMD lanes,
  /// link_predict_lanes.hpp) and must give the same bits as PredictSigma: makes the Cholesky
  /// factor of P current exactly as PredictSigma's first step would (factoring a P that a
  /// prediction only checked). False when PredictSigma would take another path (no factor and
  /// P not known positive definite, n + λ ≤ 0, or P not positive definite): the caller then
  /// runs PredictSigma itself. The sigma points are x ± sigma_scale() · columns of chol().
  bool SigmaFactorReady() {
    if (!chol_valid_ && !pd_known_) return false;
    if (!(N + lambda_ > 0.0)) return false;
    if (!chol_valid_) {
      Cov L;
      if (!CholeskyLower<N>(P_, L)) return false;
      Factored(L);
    }
    return true;
  }
  /// Lower Cholesky factor of P (valid after SigmaFactorReady() returned true).
  const Cov& chol() const { return chol_; }
  /// √(n+λ): the sigma points' columns are sigma_scale() · chol().
  double sigma_scale() const { return sqrt_c_; }
  /// The end of PredictSigma for a mean and a (symmetric, Q included) covariance that the
  /// caller computed from the propagated sigma points with PredictSigma's operations.
  UkfStatus AcceptPrediction(const State& mean, const Cov& P) {
    return Accept(mean, P, /*factor=*/false);
  }
  /// Normalised innovation squared of the last successful update.
  double last_nis() const { return last_nis_; }
  /// eᵀ P⁻¹ e for the current P (e.g. the normalised estimation error squared, NEES); NaN when
  /// P is not positive definite.
  double Mahalanobis2(const State& e) const {
    Cov L = chol_;
    if (!chol_valid_ && !CholeskyLower<N>(P_, L)) return std::nan("");
    State v = e;
    CholeskySolveInPlace<N>(L, v);
    return e.dot(v);
  }

  /// Sigma points of (mean, P) (eq. 12). Fails when P is not positive definite.
  UkfStatus SigmaPoints(const State& mean, const Cov& P, SigmaSet& pts) const {
    if (!mean.allFinite() || !P.allFinite()) return UkfStatus::kNonFinite;
    Cov S;
    if (!CholeskyLower<N>(Cov((N + lambda_) * P), S)) return UkfStatus::kNotPositiveDefinite;
    pts[0] = mean;
    for (int i = 0; i < N; ++i) {
      pts[1 + i] = mean + S.col(i);
      pts[1 + N + i] = mean - S.col(i);
    }
    return UkfStatus::kOk;
  }

 private:
  // The sigma points of (x, P), from the Cholesky factor of P kept by the last step when there
  // is one ((n+λ)P = (√(n+λ) L)(√(n+λ) L)ᵀ).
  FORMSIM_UKF_INLINE UkfStatus CurrentSigmaPoints(SigmaSet& pts) {
    if (!chol_valid_ && !pd_known_) return SigmaPoints(x_, P_, pts);
    const double c = N + lambda_;
    if (!(c > 0.0)) return UkfStatus::kNotPositiveDefinite;
    if (!chol_valid_) {
      // A prediction checked P without factoring it.
      Cov L;
      if (!CholeskyLower<N>(P_, L)) return UkfStatus::kNotPositiveDefinite;
      Factored(L);
    }
    const Cov S = sqrt_c_ * chol_;
    pts[0] = x_;
    for (int i = 0; i < N; ++i) {
      pts[1 + i] = x_ + S.col(i);
      pts[1 + N + i] = x_ - S.col(i);
    }
    return UkfStatus::kOk;
  }
  // Whether the closed-form update of the components `idx` equals the sigma-point one (see the
  // file comment): the angle spreads well inside ±π.
  bool ClosedFormExact(const std::array<int, M>& idx) const {
    const double c = N + lambda_;
    bool exact = c > 0.0;
    for (int k = 0; k < N && exact; ++k) exact = !angle_state_[k] || c * P_(k, k) < 9.0;
    for (int k = 0; k < M && exact; ++k)
      exact =
          angle_meas_[k] == angle_state_[idx[k]] && (!angle_meas_[k] || P_(idx[k], idx[k]) < 1.0);
    return exact;
  }
  void Factored(const Cov& L) {
    chol_ = L;
    chol_valid_ = true;
    pd_known_ = true;
  }
  // Positive definiteness without the factor: the leading principal minors up to 3×3 (no square
  // root, no division: a Cholesky of a 3×3 is a chain of three of each), else a Cholesky.
  static bool PositiveDefinite(const Cov& P) {
    if constexpr (N == 1) {
      return P(0, 0) > 0.0;
    } else if constexpr (N == 2) {
      return P(0, 0) > 0.0 && P(0, 0) * P(1, 1) - P(1, 0) * P(1, 0) > 0.0;
    } else if constexpr (N == 3) {
      const double m2 = P(0, 0) * P(1, 1) - P(1, 0) * P(1, 0);
      const double m3 = P(0, 0) * (P(1, 1) * P(2, 2) - P(2, 1) * P(2, 1)) -
                        P(1, 0) * (P(1, 0) * P(2, 2) - P(2, 1) * P(2, 0)) +
                        P(2, 0) * (P(1, 0) * P(2, 1) - P(1, 1) * P(2, 0));
      return P(0, 0) > 0.0 && m2 > 0.0 && m3 > 0.0;
    } else {
      Cov L;
      return CholeskyLower<N>(P, L);
    }
  }
  template <std::size_t K>
  static void SetFlags(std::array<bool, K>& flags, std::initializer_list<int> idx) {
    flags.fill(false);
    for (int i : idx) flags[i] = true;
  }
  // P += Σᵢ wcᵢ dᵢ dᵢᵀ with dᵢ = ptsᵢ − mean (angles wrapped), lower triangle (Symmetrize
  // mirrors it), point by point in scalars: with each dᵢ in a vector on the stack the compiler
  // reloaded two just-stored doubles as one, which stalls store forwarding (12% of the paper
  // scenario's time went to that one load).
  void AddSpread(Cov& P, const SigmaSet& pts, const State& mean) const {
    if constexpr (N == 3) {
      // Six named sums: an array of them was packed in pairs and kept in memory.
      double p00 = P(0, 0), p10 = P(1, 0), p20 = P(2, 0), p11 = P(1, 1), p21 = P(2, 1),
             p22 = P(2, 2);
      for (int i = 0; i < kSigma; ++i) {
        double d0 = pts[i](0) - mean(0), d1 = pts[i](1) - mean(1), d2 = pts[i](2) - mean(2);
        if (angle_state_[0]) d0 = WrapToPi(d0);
        if (angle_state_[1]) d1 = WrapToPi(d1);
        if (angle_state_[2]) d2 = WrapToPi(d2);
        const double w = wc_[i], wd0 = w * d0, wd1 = w * d1, wd2 = w * d2;
        p00 += wd0 * d0, p10 += wd0 * d1, p20 += wd0 * d2;
        p11 += wd1 * d1, p21 += wd1 * d2;
        p22 += wd2 * d2;
      }
      P(0, 0) = p00, P(1, 0) = p10, P(2, 0) = p20, P(1, 1) = p11, P(2, 1) = p21, P(2, 2) = p22;
      return;
    }
    double acc[N][N];
    for (int c = 0; c < N; ++c)
      for (int r = c; r < N; ++r) acc[r][c] = P(r, c);
    for (int i = 0; i < kSigma; ++i) {
      double d[N];
      for (int k = 0; k < N; ++k) {
        const double v = pts[i](k) - mean(k);
        d[k] = angle_state_[k] ? WrapToPi(v) : v;
      }
      for (int c = 0; c < N; ++c) {
        const double wd = wc_[i] * d[c];
        for (int r = c; r < N; ++r) acc[r][c] += wd * d[r];
      }
    }
    for (int c = 0; c < N; ++c)
      for (int r = c; r < N; ++r) P(r, c) = acc[r][c];
  }
  template <int K>
  static void Symmetrize(Eigen::Matrix<double, K, K>& A) {
    for (int c = 0; c < K; ++c)
      for (int r = c + 1; r < K; ++r) A(c, r) = A(r, c);
  }
  // The update from the predicted measurement, its covariance and the cross covariance
  // (eq. 19-21): K = Psy Pyy⁻¹, x += K (z − ŷ), P −= K Pyy Kᵀ.
  UkfStatus Correct(const Meas& z, const Meas& y_mean, MeasCov Pyy, const CrossCov& Psy) {
    Pyy = 0.5 * (Pyy + Pyy.transpose());
    if (!Pyy.allFinite()) return UkfStatus::kNonFinite;
    MeasCov Ly;
    if (!CholeskyLower<M>(Pyy, Ly)) return UkfStatus::kNotPositiveDefinite;
    // K = Psy Pyy⁻¹, row by row: Pyy kᵀ = (row of Psy)ᵀ.
    double inv[M];
    for (int i = 0; i < M; ++i) inv[i] = 1.0 / Ly(i, i);
    CrossCov K;
    for (int r = 0; r < N; ++r) {
      Meas row = Psy.row(r).transpose();
      CholeskySolveInPlace<M>(Ly, inv, row);
      K.row(r) = row.transpose();
    }
    const Meas innovation = MeasDiff(z, y_mean);
    Meas w = innovation;
    CholeskySolveInPlace<M>(Ly, inv, w);
    last_nis_ = innovation.dot(w);
    State x = x_ + K * innovation;
    Cov P = P_ - K * Pyy * K.transpose();
    P = 0.5 * (P + P.transpose());
    WrapState(x);
    return Accept(x, P);
  }
  // The new state when it is finite and P positive definite (with `factor`, its Cholesky factor
  // is kept for the next sigma points; else it is computed when they are needed); else a fault
  // and nothing changes.
  UkfStatus Accept(const State& x, const Cov& P, bool factor = true) {
    if (!x.allFinite() || !P.allFinite()) return UkfStatus::kNonFinite;
    if (!factor) {
      if (!PositiveDefinite(P)) return UkfStatus::kNotPositiveDefinite;
      x_ = x;
      P_ = P;
      chol_valid_ = false;
      pd_known_ = true;
      return UkfStatus::kOk;
    }
    Cov L;
    if (!CholeskyLower<N>(P, L)) return UkfStatus::kNotPositiveDefinite;
    x_ = x;
    P_ = P;
    Factored(L);
    return UkfStatus::kOk;
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
  // Weighted mean; angle components as the circular mean atan2(Σ w sin, Σ w cos), taken
  // around the first point so that the deviations are small.
  template <class Vec, std::size_t K, std::size_t D>
  FORMSIM_UKF_INLINE Vec Mean(const std::array<Vec, K>& pts,
                              const std::array<bool, D>& angle) const {
    Vec mean = Vec::Zero();
    for (std::size_t i = 0; i < K; ++i) mean += wm_[i] * pts[i];
    for (std::size_t c = 0; c < D; ++c) {
      if (!angle[c]) continue;
      const double ref = pts[0](c);
      double dev[K], sn[K], cs[K];
      for (std::size_t i = 0; i < K; ++i) dev[i] = WrapToPi(pts[i](c) - ref);
      SinCosSmallAll(dev, sn, cs);
      double s = 0.0, co = 0.0;
      for (std::size_t i = 0; i < K; ++i) {
        s += wm_[i] * sn[i];
        co += wm_[i] * cs[i];
      }
      mean(c) = WrapToPi(ref + Atan2NearAxis(s, co));
    }
    return mean;
  }
  State MeanState(const SigmaSet& pts) const { return Mean(pts, angle_state_); }
  Meas MeanMeas(const std::array<Meas, kSigma>& ys) const { return Mean(ys, angle_meas_); }

  UkfScaling scaling_;
  double lambda_ = 0.0;
  double sqrt_c_ = 0.0;  ///< √(n+λ), the scale of the sigma points' columns
  std::array<double, kSigma> wm_{}, wc_{};
  std::array<bool, N> angle_state_{};
  std::array<bool, M> angle_meas_{};
  State x_ = State::Zero();
  Cov P_ = Cov::Identity();
  Cov chol_ = Cov::Identity();  ///< lower Cholesky factor of P_ when chol_valid_
  bool chol_valid_ = false;
  bool pd_known_ = false;  ///< P_ is known positive definite (factored, or its minors checked)
  double last_nis_ = 0.0;
};

}  // namespace formsim::control
