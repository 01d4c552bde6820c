#include "control/agv/pose_filter.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "control/common/angle.hpp"
#include "control/agv/chi_square.hpp"
#include "control/agv/dead_reckoning.hpp"

namespace formsim::control::agv {
namespace {

bool AllFinite(const Eigen::MatrixXd& m) {
  return m.allFinite();
}

// Positive definite (Cholesky succeeds) and finite.
bool IsPd(const Eigen::Matrix3d& m) {
  if (!m.allFinite()) return false;
  Eigen::LLT<Eigen::Matrix3d> llt(m);
  return llt.info() == Eigen::Success;
}

}  // namespace

PoseFilter::PoseFilter(const PoseFilterDef& def) {
  kf_.angle_states = {2};
  SetDef(def);
  Reset(Pose2{});
}

void PoseFilter::SetDef(const PoseFilterDef& def) {
  const bool adaptive_was_on = def_.adaptive_r;
  def_ = def;
  def_.gate_probability = std::clamp(def_.gate_probability, 1e-6, 1.0 - 1e-12);
  gate_threshold_ = ChiSquareQuantile(def_.gate_probability, 3);
  if (!def_.adaptive_r || !adaptive_was_on) {
    window_y_.clear();
    window_p_.clear();
  }
  UpdateNominalR();
}

void PoseFilter::UpdateNominalR() {
  // The nominal R, unless the adaptive estimate has enough samples to replace it.
  const bool adapted =
      def_.adaptive_r && static_cast<int>(window_y_.size()) >= std::max(2, def_.adaptive_window);
  if (!adapted) {
    kf_.R =
        Eigen::Vector3d(def_.r_xy * def_.r_xy, def_.r_xy * def_.r_xy, def_.r_theta * def_.r_theta)
            .asDiagonal();
    return;
  }
  const std::size_t n = window_y_.size();
  Eigen::Vector3d pp = Eigen::Vector3d::Zero(), r;
  for (const auto& v : window_p_) pp += v;
  pp /= static_cast<double>(n);
  std::vector<double> col(n);
  for (int i = 0; i < 3; ++i) {
    for (std::size_t k = 0; k < n; ++k) col[k] = window_y_[k](i);
    std::nth_element(col.begin(), col.begin() + n / 2, col.end());
    const double sigma = 1.4826 * col[n / 2];  // MAD scale of a zero-mean Gaussian
    r(i) = sigma * sigma - pp(i);
  }
  const Eigen::Vector3d floor(def_.adaptive_min_xy * def_.adaptive_min_xy,
                              def_.adaptive_min_xy * def_.adaptive_min_xy,
                              def_.adaptive_min_theta * def_.adaptive_min_theta);
  r = r.cwiseMax(floor);
  kf_.R = r.asDiagonal();
}

void PoseFilter::ResetCovariance() {
  kf_.Reset(kf_.x(), Eigen::Vector3d(def_.p0_xy * def_.p0_xy, def_.p0_xy * def_.p0_xy,
                                     def_.p0_theta * def_.p0_theta)
                         .asDiagonal());
}

void PoseFilter::Reset(const Pose2& pose) {
  kf_.Reset(Eigen::Vector3d(pose.x, pose.y, WrapToPi(pose.theta)), Eigen::Matrix3d::Identity());
  ResetCovariance();
  consecutive_rejections_ = 0;
  streak_.clear();
  window_y_.clear();
  window_p_.clear();
  UpdateNominalR();
  last_fault_.clear();
}

bool PoseFilter::Predict(const BodyTwist& odo, double dt) {
  if (!(dt >= 0.0) || !std::isfinite(odo.vx) || !std::isfinite(odo.vy) ||
      !std::isfinite(odo.omega)) {
    last_fault_ = "non-finite odometry input or negative dt";
    return false;
  }
  // u = [ẋ ẏ θ̇] from the body twist at the mid-step heading, B = T·I, Q = diag(q²)·T.
  const WorldVelocity v = ToWorld(odo, kf_.x()(2) + 0.5 * odo.omega * dt);
  kf_.B = Eigen::Matrix3d::Identity() * dt;
  kf_.Q = Eigen::Vector3d(def_.q_xy * def_.q_xy, def_.q_xy * def_.q_xy, def_.q_theta * def_.q_theta)
              .asDiagonal() *
          dt;
  const Eigen::Vector3d x_before = kf_.x();
  const Eigen::Matrix3d p_before = kf_.P();
  kf_.Predict(Eigen::Vector3d(v.x_dot, v.y_dot, v.theta_dot));
  if (!AllFinite(kf_.x()) || !AllFinite(kf_.P())) {
    kf_.Reset(x_before, p_before);
    ResetCovariance();
    last_fault_ = "prediction produced non-finite state or covariance";
    return false;
  }
  return true;
}

FuseReport PoseFilter::Fuse(const Pose2& beacon) {
  FuseReport rep;
  const Eigen::Vector3d z(beacon.x, beacon.y, WrapToPi(beacon.theta));
  if (!z.allFinite()) {
    rep.outcome = FuseReport::Outcome::kFault;
    rep.message = last_fault_ = "non-finite beacon sample";
    return rep;
  }
  const Eigen::Matrix3d S = kf_.InnovationCov();
  if (!IsPd(S)) {
    ResetCovariance();
    rep.outcome = FuseReport::Outcome::kFault;
    rep.message = last_fault_ =
        "innovation covariance S = P + R is not positive definite (Q and R both zero?); "
        "update skipped, P re-initialised";
    return rep;
  }
  rep.innovation = kf_.Innovation(z);
  rep.nis = kf_.Nis(z);

  const Eigen::Matrix3d p_prior = kf_.P();
  if (def_.adaptive_r) {
    window_y_.push_back(rep.innovation.cwiseAbs());
    window_p_.push_back(p_prior.diagonal());
    while (static_cast<int>(window_y_.size()) > std::max(1, def_.adaptive_window)) {
      window_y_.pop_front();
      window_p_.pop_front();
    }
  }

  if (def_.gate && rep.nis > gate_threshold_) {
    ++consecutive_rejections_;
    streak_.push_back(rep.innovation);
    if (def_.gate_reset_after <= 0 || consecutive_rejections_ < def_.gate_reset_after) {
      rep.outcome = FuseReport::Outcome::kRejected;
      if (def_.adaptive_r) UpdateNominalR();
      return rep;
    }
    // Lost: the beacon has disagreed for a whole streak. Move by the median innovation of the
    // streak (robust to an outlier within it) and restart P from its initial value.
    Eigen::Vector3d shift;
    const std::size_t n = streak_.size();
    std::vector<double> col(n);
    for (int i = 0; i < 3; ++i) {
      for (std::size_t k = 0; k < n; ++k) col[k] = streak_[k](i);
      std::nth_element(col.begin(), col.begin() + n / 2, col.end());
      shift(i) = col[n / 2];
    }
    Eigen::Vector3d x = kf_.x() + shift;
    x(2) = WrapToPi(x(2));
    kf_.Reset(x, kf_.P());
    ResetCovariance();
    consecutive_rejections_ = 0;
    streak_.clear();
    if (def_.adaptive_r) UpdateNominalR();
    rep.outcome = FuseReport::Outcome::kReinitialised;
    rep.message = "innovation gate rejected " + std::to_string(def_.gate_reset_after) +
                  " beacon samples in a row; state moved by their median innovation (" +
                  std::to_string(shift.head<2>().norm()) + " m), P re-initialised";
    return rep;
  }
  consecutive_rejections_ = 0;
  streak_.clear();

  const Eigen::Vector3d x_before = kf_.x();
  kf_.Update(z);
  if (!AllFinite(kf_.x()) || !AllFinite(kf_.P()) || kf_.P().diagonal().minCoeff() < 0.0) {
    kf_.Reset(x_before, p_prior);
    ResetCovariance();
    rep.outcome = FuseReport::Outcome::kFault;
    rep.message = last_fault_ = "update produced a non-finite or indefinite covariance";
    return rep;
  }
  if (def_.adaptive_r) UpdateNominalR();
  rep.outcome = FuseReport::Outcome::kAccepted;
  return rep;
}

Pose2 PoseFilter::pose() const {
  return {kf_.x()(0), kf_.x()(1), kf_.x()(2)};
}

}  // namespace formsim::control::agv
