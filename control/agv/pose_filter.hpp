#pragma once
/// \file The paper's odometry + beacon Kalman filter (paper 002, eq. 8-17), with two switchable
/// extensions the paper names as future work.
///
/// State X = [x y θ] (world), input u = [ẋ ẏ θ̇] from odometry (body twist rotated by the
/// estimated heading, eq. 3), A = I, B = T·I, H = I, Q and R diagonal. Predict() runs every
/// odometry period (dead reckoning from the last fused pose); Fuse() runs at every beacon
/// sample. θ is wrapped in the state and in the innovation.
///  - Innovation gate: a sample whose normalised innovation squared y'S⁻¹y exceeds the
///    chi-square quantile (3 dof, `gate_probability`) is rejected. After `gate_reset_after`
///    rejections in a row the filter is taken as lost: the state is moved by the component-wise
///    median innovation of that streak (one outlier in it cannot pull the state) and P is reset
///    to its initial value.
///  - Adaptive R: once `adaptive_window` samples (accepted or rejected) have been seen, R is
///    re-estimated from their innovations y by innovation-based estimation (Mehra 1972), robust:
///    R̂_ii = (1.4826 · median |y_i|)² − mean(P⁻_ii), floored. The median ignores interference
///    outliers, and counting rejected samples lets R grow when the nominal R was too optimistic
///    (otherwise the gate would only show it the small innovations).
/// Numerical faults (a non-positive-definite S or P, non-finite values) leave the state as it
/// was, re-initialise P and are reported, never propagated.

#include <Eigen/Dense>
#include <deque>
#include <string>
#include <vector>

#include "control/common/geometry.hpp"
#include "control/common/linear_kf.hpp"
#include "control/agv/kinematics.hpp"

namespace formsim::control::agv {

struct PoseFilterDef {
  double q_xy = 0.01;      ///< process noise of x and y, m/√s (Q = diag(q²)·T)
  double q_theta = 0.01;   ///< process noise of θ, rad/√s
  double r_xy = 0.02;      ///< beacon σ of x and y, m
  double r_theta = 0.02;   ///< beacon σ of θ, rad
  double p0_xy = 0.05;     ///< initial σ of x and y, m
  double p0_theta = 0.05;  ///< initial σ of θ, rad
  bool gate = true;
  double gate_probability = 0.999;  ///< chi-square acceptance probability (3 dof)
  int gate_reset_after = 5;         ///< consecutive rejections before re-initialising (0: never)
  bool adaptive_r = false;
  int adaptive_window = 50;           ///< innovations in the R estimate
  double adaptive_min_xy = 0.002;     ///< floor of the adapted σ of x and y, m
  double adaptive_min_theta = 0.002;  ///< floor of the adapted σ of θ, rad
};
inline PoseFilterDef DefaultPoseFilterDef() {
  return PoseFilterDef{};
}

/// What happened to one beacon sample.
struct FuseReport {
  enum class Outcome { kAccepted, kRejected, kReinitialised, kFault } outcome = Outcome::kAccepted;
  double nis = 0.0;  ///< normalised innovation squared (before the update)
  Eigen::Vector3d innovation = Eigen::Vector3d::Zero();
  std::string message;  ///< for kFault and kReinitialised
};

class PoseFilter {
 public:
  using Kf = LinearKalmanFilter<3, 3, 3>;

  explicit PoseFilter(const PoseFilterDef& def = DefaultPoseFilterDef());
  /// Changes noise settings and switches; the state is kept (live tuning).
  void SetDef(const PoseFilterDef& def);
  const PoseFilterDef& def() const { return def_; }

  /// Starts at `pose` with the def's initial covariance; clears the adaptive window.
  void Reset(const Pose2& pose);
  /// Time update over dt with the odometry body twist. Returns false (and leaves the state)
  /// on non-finite input or a numerical fault; `last_fault()` says why.
  bool Predict(const BodyTwist& odometry, double dt);
  /// Measurement update with a beacon pose (gated, possibly adapting R).
  FuseReport Fuse(const Pose2& beacon);

  Pose2 pose() const;
  const Eigen::Matrix3d& covariance() const { return kf_.P(); }
  /// The R in use (the adapted one when adaptive R is on and enough samples were seen).
  const Eigen::Matrix3d& measurement_cov() const { return kf_.R; }
  /// The gate threshold on the NIS.
  double gate_threshold() const { return gate_threshold_; }
  int consecutive_rejections() const { return consecutive_rejections_; }
  const std::string& last_fault() const { return last_fault_; }

 private:
  void UpdateNominalR();
  void ResetCovariance();
  PoseFilterDef def_;
  Kf kf_;
  double gate_threshold_ = 0.0;
  int consecutive_rejections_ = 0;
  // Adaptive R window: absolute innovations and the predicted covariance diagonal.
  std::deque<Eigen::Vector3d> window_y_, window_p_;
  // Innovations of the current streak of rejected samples.
  std::vector<Eigen::Vector3d> streak_;
  std::string last_fault_;
};

}  // namespace formsim::control::agv
