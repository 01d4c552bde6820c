#pragma once
/// \file Residuals of the sliding-window estimator with their exact Jacobians, already whitened
/// (multiplied by the square root of the information matrix), so that the cost of each factor
/// is ½‖r‖². Every angle residual is wrapped to (-π, π]. Jacobian columns follow
/// KeyframeState::Index; feature Jacobians are w.r.t. the landmark's world position, or w.r.t.
/// its anchor keyframe and inverse depth for the inverse-depth parameterisation.

#include <Eigen/Dense>

#include "control/velocity/imu_preintegration.hpp"
#include "control/velocity/keyframe_state.hpp"
#include "control/velocity/odometry_preintegration.hpp"

namespace formsim::control::velocity {

/// IMU pre-integration factor between keyframes i and j (8 rows):
///   r_θ = θj - θi - Δθ(bgi)
///   r_v = Riᵀ (vj - vi) - Δv(bgi, bai)
///   r_p = Riᵀ (pj - pi - vi Δt) - Δp(bgi, bai)
///   r_bg = bgj - bgi,  r_ba = baj - bai   (bias random walk over Δt)
struct ImuFactor {
  static constexpr int kRows = 8;
  Eigen::Matrix<double, kRows, 1> r;
  Eigen::Matrix<double, kRows, KeyframeState::kDim> Ji, Jj;
};
ImuFactor EvaluateImuFactor(const ImuPreintegration& pre, const KeyframeState& i,
                            const KeyframeState& j);

/// Wheel-odometry factor between keyframes i and j (5 rows):
///   r_θ = θj - θi - Δθᴼ(bψi),  r_p = Riᵀ (pj - pi) - Δpᴼ(bvi, bψi),
///   r_bv = bvj - bvi,  r_bψ = bψj - bψi   (odometry bias random walk over Δt).
struct OdometryFactor {
  static constexpr int kRows = 5;
  Eigen::Matrix<double, kRows, 1> r;
  Eigen::Matrix<double, kRows, KeyframeState::kDim> Ji, Jj;
};
OdometryFactor EvaluateOdometryFactor(const OdometryPreintegration& pre, const KeyframeState& i,
                                      const KeyframeState& j);

/// Non-holonomic constraint of a wheeled robot at one keyframe: the lateral body-frame
/// velocity is zero up to `sigma` (m/s), which allows some sideways skid.
struct NonholonomicFactor {
  double r = 0.0;
  Eigen::Matrix<double, 1, KeyframeState::kDim> J;
};
NonholonomicFactor EvaluateNonholonomicFactor(const KeyframeState& k, double sigma);

/// Bearing of a point landmark seen by a camera looking along the body x axis, mounted
/// `camera_offset` metres ahead of the body origin: r = (atan2(q_y, q_x) - z) / σ with
/// q = R(θ)ᵀ (f - p) - [offset, 0]ᵀ.
struct BearingFactor {
  double r = 0.0;
  Eigen::Matrix<double, 1, KeyframeState::kDim> Jk;
  Eigen::Matrix<double, 1, 2> Jf;
  double depth = 0.0;  ///< q_x: positive when the landmark is in front of the camera
};
BearingFactor EvaluateBearingFactor(const KeyframeState& k, const Vec2d& landmark, double bearing,
                                    double sigma, double camera_offset);

/// A landmark held in inverse-depth form at the keyframe that anchors it (the first one in
/// the window that saw it): ψ, the bearing of its ray from the anchor's camera (relative to the
/// anchor's heading, like a measured bearing), and ρ, the inverse of its distance along that
/// ray (Civera, Davison and Montiel's inverse-depth parameterisation, in the plane). Its world
/// position is f = c_a + u(θ_a + ψ) / ρ, with c_a = p_a + R(θ_a) [offset, 0]ᵀ the anchor's
/// camera centre and u(φ) = [cos φ, sin φ]ᵀ.
struct AnchoredPoint {
  Vec2d f = Vec2d::Zero();  ///< world position
  Eigen::Matrix<double, 2, KeyframeState::kDim> Ja =
      Eigen::Matrix<double, 2, KeyframeState::kDim>::Zero();  ///< ∂f/∂(anchor state)
  Vec2d Jpsi = Vec2d::Zero();                                 ///< ∂f/∂ψ
  Vec2d Jrho = Vec2d::Zero();                                 ///< ∂f/∂ρ
};
AnchoredPoint EvaluateAnchoredPoint(const KeyframeState& anchor, double psi, double rho,
                                    double camera_offset);

/// The inverse: ψ and ρ of the world point f seen from `anchor`, with their Jacobians (used to
/// initialise a landmark and to move it to another anchor without moving it).
struct AnchorCoordinates {
  double psi = 0.0;  ///< wrapped to (-π, π]
  double rho = 0.0;
  Eigen::Matrix<double, 2, KeyframeState::kDim> Ja;  ///< ∂(ψ, ρ)/∂(anchor state)
  Eigen::Matrix2d Jf;                                ///< ∂(ψ, ρ)/∂f
};
AnchorCoordinates EvaluateAnchorCoordinates(const KeyframeState& anchor, const Vec2d& f,
                                            double camera_offset);

/// Bearing of an anchored landmark from another keyframe k: the BearingFactor at the anchored
/// point, with Jacobians w.r.t. the observing keyframe, the anchor keyframe, ψ and ρ. (From the
/// anchor itself the bearing is ψ: that residual is (ψ − z) / σ.)
struct InverseDepthBearingFactor {
  double r = 0.0;
  Eigen::Matrix<double, 1, KeyframeState::kDim> Jk;  ///< observing keyframe
  Eigen::Matrix<double, 1, KeyframeState::kDim> Ja;  ///< anchor keyframe
  Eigen::Matrix<double, 1, 2> Jl;                    ///< landmark (ψ, ρ)
  double depth = 0.0;  ///< depth in the observing camera (> 0 in front of it)
};
InverseDepthBearingFactor EvaluateInverseDepthBearingFactor(const KeyframeState& k,
                                                            const KeyframeState& anchor, double psi,
                                                            double rho, double bearing,
                                                            double sigma, double camera_offset);

/// Square root U of an information matrix, UᵀU = cov⁻¹, from the covariance (Cholesky with a
/// tiny jitter so that a zero-length interval stays finite).
Eigen::MatrixXd SqrtInformation(const Eigen::MatrixXd& cov);

}  // namespace formsim::control::velocity
