#include "control/formation/link_filter.hpp"

#include <array>

namespace formsim::control::formation {
namespace {

// A link UKF measuring the components `idx` (indices into [l, φ, α]) of the state.
template <int M>
class LinkUkf final : public LinkFilter {
 public:
  using Filter = Ukf<3, M>;
  LinkUkf(const LinkFilterDef& def, std::array<int, M> idx) : LinkFilter(def), idx_(idx) {
    ukf_.SetScaling(def.scaling);
    ukf_.SetAngleStates({1, 2});
    for (int k = 0; k < M; ++k) ukf_.SetAngleMeasComponent(k, idx_[k] != 0);
    ukf_.Reset(Eigen::Vector3d::Zero(), def.p0.asDiagonal());
  }

  void Reset(const LinkState& x0, const Eigen::Matrix3d& P0) override { ukf_.Reset(x0.vec(), P0); }

  UkfStatus Predict(const Twist& leader, const Twist& follower) override {
    const double Tc = def_.Tc, L = def_.L;
    // Γ(s, U) = s + Tc F(s) U on all sigma points at once. They are s̄ ± columns, so the sines
    // and cosines of φ and γ = φ + α come from those of the mean (one sincos each) and of the
    // small column offsets (SinCosSmall) by angle addition.
    if (def_.substeps > 1) return PredictSubsteps(leader, follower);
    auto gamma = [&](const typename Filter::SigmaSet& pts, typename Filter::SigmaSet& out) {
      const Eigen::Vector3d& m = pts[0];
      const SinCos phi0 = SinCosOf(m(1)), gamma0 = SinCosOf(m(1) + m(2));
      auto propagate = [&](const Eigen::Vector3d& s, const SinCos& phi, const SinCos& g) {
        const LinkRates r = LinkDerivative(s(0), phi, g, leader, follower, L);
        return Eigen::Vector3d(s(0) + Tc * r.l_dot, s(1) + Tc * r.phi_dot, s(2) + Tc * r.alpha_dot);
      };
      out[0] = propagate(m, phi0, gamma0);
      // The six offsets' sines and cosines in one vectorised pass: [0, 3) of φ, [3, 6) of γ.
      double off[6], sn[6], cs[6];
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d& plus = pts[1 + j];
        off[j] = plus(1) - m(1);
        off[3 + j] = (plus(1) + plus(2)) - (m(1) + m(2));
      }
      SinCosSmallAll(off, sn, cs);
      for (int j = 0; j < 3; ++j) {
        const SinCos dphi{sn[j], cs[j]}, dgamma{sn[3 + j], cs[3 + j]};
        out[1 + j] = propagate(pts[1 + j], AddAngles(phi0, dphi), AddAngles(gamma0, dgamma));
        out[4 + j] = propagate(pts[4 + j], SubAngles(phi0, dphi), SubAngles(gamma0, dgamma));
      }
    };
    return ukf_.PredictSigma(gamma, Eigen::Matrix3d(def_.q.asDiagonal()));
  }

  // The same Γ integrated with `substeps` Euler steps of Tc / substeps; each step takes the
  // sines and cosines of the point it reached (the inputs are held over the period).
  UkfStatus PredictSubsteps(const Twist& leader, const Twist& follower) {
    const int n = def_.substeps;
    const double h = def_.Tc / n, L = def_.L;
    auto gamma = [&](const typename Filter::SigmaSet& pts, typename Filter::SigmaSet& out) {
      for (std::size_t k = 0; k < pts.size(); ++k) {
        Eigen::Vector3d s = pts[k];
        for (int i = 0; i < n; ++i) {
          const LinkRates r =
              LinkDerivative(s(0), SinCosOf(s(1)), SinCosOf(s(1) + s(2)), leader, follower, L);
          s += h * Eigen::Vector3d(r.l_dot, r.phi_dot, r.alpha_dot);
        }
        out[k] = s;
      }
    };
    return ukf_.PredictSigma(gamma, Eigen::Matrix3d(def_.q.asDiagonal()));
  }

  UkfStatus Update(const LinkState& measured) override {
    const Eigen::Vector3d full = measured.vec();
    typename Filter::Meas z;
    typename Filter::MeasCov R = Filter::MeasCov::Zero();
    for (int k = 0; k < M; ++k) {
      z(k) = full(idx_[k]);
      R(k, k) = def_.r(idx_[k]);
    }
    // y = D s: D selects the measured components.
    return ukf_.UpdateSelection(z, idx_, R);
  }

  bool PredictBasis(LinkPredictBasis& b) override {
    // The lanes hard-code Predict's single Euler step and the angle states φ and α.
    if (def_.substeps > 1 || !ukf_.SigmaFactorReady()) return false;
    b.x = ukf_.x();
    b.chol = ukf_.chol();
    b.scale = ukf_.sigma_scale();
    b.wm0 = ukf_.weight_mean(0), b.wm = ukf_.weight_mean(1);
    b.wc0 = ukf_.weight_cov(0), b.wc = ukf_.weight_cov(1);
    b.Tc = def_.Tc, b.L = def_.L;
    b.q = def_.q;
    return true;
  }
  UkfStatus AcceptPrediction(const Eigen::Vector3d& mean, const Eigen::Matrix3d& P) override {
    return ukf_.AcceptPrediction(mean, P);
  }

  int UpdateBasis(LinkUpdateBasis& b) const override {
    if constexpr (M == 1) {
      return 0;
    } else {
      if (!ukf_.ClosedFormMayRun(idx_)) return 0;
      b.x = ukf_.x().data();
      b.P = ukf_.P().data();
      b.r = def_.r.data();
      return M;
    }
  }
  void AcceptUpdate(const LinkUpdateResult& u) override {
    Eigen::Vector3d x;
    Eigen::Matrix3d P, L;
    for (int k = 0; k < 3; ++k) {
      x(k) = u.x[k * u.stride];
      for (int c = 0; c < 3; ++c)
        P(k, c) = u.P[(k * 3 + c) * u.stride], L(k, c) = u.chol[(k * 3 + c) * u.stride];
    }
    ukf_.AcceptCorrected(x, P, L, u.nis);
  }

  LinkState state() const override { return LinkState::FromVec(ukf_.x()); }
  Eigen::Matrix3d cov() const override { return ukf_.P(); }
  double nis() const override { return ukf_.last_nis(); }
  double Mahalanobis2(const Eigen::Vector3d& e) const override { return ukf_.Mahalanobis2(e); }

 private:
  Filter ukf_;
  std::array<int, M> idx_;
};

}  // namespace

std::unique_ptr<LinkFilter> LinkFilter::Make(const LinkFilterDef& def) {
  switch (def.measure) {
    case MeasurementSet::kPhiAlpha:
      return std::make_unique<LinkUkf<2>>(def, std::array<int, 2>{1, 2});
    case MeasurementSet::kLPhiAlpha:
      return std::make_unique<LinkUkf<3>>(def, std::array<int, 3>{0, 1, 2});
    case MeasurementSet::kAlpha:
      return std::make_unique<LinkUkf<1>>(def, std::array<int, 1>{2});
  }
  return nullptr;
}

}  // namespace formsim::control::formation
