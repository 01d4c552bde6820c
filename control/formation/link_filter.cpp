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
    // Γ(s, U) = s + Tc F(s) U.
    auto gamma = [&](const Eigen::Vector3d& s) -> Eigen::Vector3d {
      const LinkRates r = LinkDerivative(LinkState::FromVec(s), leader, follower, L);
      return s + Tc * Eigen::Vector3d(r.l_dot, r.phi_dot, r.alpha_dot);
    };
    return ukf_.Predict(gamma, Eigen::Matrix3d(def_.q.asDiagonal()));
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
    auto h = [&](const Eigen::Vector3d& s) {
      typename Filter::Meas y;
      for (int k = 0; k < M; ++k) y(k) = s(idx_[k]);
      return y;
    };
    return ukf_.Update(z, h, R);
  }

  LinkState state() const override { return LinkState::FromVec(ukf_.x()); }
  Eigen::Matrix3d cov() const override { return ukf_.P(); }
  double nis() const override { return ukf_.last_nis(); }

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
