#pragma once
/// \file Output kinematics of a leader→follower link of unicycles (paper 000, eq. 3-8, re-derived:
/// the printed F matrix is garbled).
///
/// Unicycle i: ẋ = v cosθ, ẏ = v sinθ, θ̇ = ω. The follower j's control point is
/// M_j = p_j + L (cosθ_j, sinθ_j). For the link i → j: r = M_j − p_i, l = |r|, β = atan2(r_y, r_x).
///  - bearing (Das et al. 2002 convention, the one eq. 7 follows): φ = wrap(β − θ_i)
///  - heading difference α = θ_i − θ_j (eq. 3), and γ = φ + α = β − θ_j (eq. 6)
///  - l̇ = v_j cosγ + L ω_j sinγ − v_i cosφ
///  - φ̇ = (−v_j sinγ + L ω_j cosγ + v_i sinφ) / l − ω_i
///  - α̇ = ω_i − ω_j
/// The printed eq. 4, φ = π − atan2(y_i − y_j − L sinθ_j, x_i − x_j − L cosθ_j) − θ_i, equals
/// wrap(−β − θ_i): the sign of β is mirrored, and its derivative (−β̇ − ω_i) is not the φ̇ above
/// (it depends on the leader's absolute heading). It is offered as the "printed" measurement
/// convention only, to show what feeding it to the controller does.

#include <Eigen/Core>

#include "control/common/angle.hpp"
#include "control/common/geometry.hpp"

namespace formsim::control::formation {

/// Which formula gives the bearing φ.
enum class BearingConvention {
  kDas,      ///< φ = β − θ_i (Das et al. 2002; consistent with the kinematics; default)
  kPrinted,  ///< φ = π − atan2(−r_y, −r_x) − θ_i (paper eq. 4 as printed; mirrored)
};

/// The relative state of one link (the UKF state x = [l, φ, α]).
struct LinkState {
  double l = 0.0;      ///< distance leader centre → follower control point, m
  double phi = 0.0;    ///< bearing of the control point seen from the leader, rad
  double alpha = 0.0;  ///< heading difference θ_i − θ_j, rad
  double gamma() const { return phi + alpha; }
  Eigen::Vector3d vec() const { return {l, phi, alpha}; }
  static LinkState FromVec(const Eigen::Vector3d& v) { return {v(0), v(1), v(2)}; }
};

/// Velocities of a unicycle (command or measured).
struct Twist {
  double v = 0.0;  ///< forward speed, m/s
  double w = 0.0;  ///< yaw rate, rad/s
};

/// Time derivative of a link state.
struct LinkRates {
  double l_dot = 0.0, phi_dot = 0.0, alpha_dot = 0.0;
};

/// Control point of a follower: p + L (cosθ, sinθ).
inline Vec2 ControlPoint(const Pose2& follower, double L) {
  const SinCos t = SinCosOf(follower.theta);
  return {follower.x + L * t.c, follower.y + L * t.s};
}

/// The true link state from two poses, under the chosen bearing convention. φ and α are wrapped
/// to (−π, π].
inline LinkState ComputeLinkState(const Pose2& leader, const Pose2& follower, double L,
                                  BearingConvention convention = BearingConvention::kDas) {
  const Vec2 m = ControlPoint(follower, L);
  const double rx = m.x - leader.x, ry = m.y - leader.y;
  LinkState s;
  s.l = std::sqrt(rx * rx + ry * ry);  // no overflow or underflow at robot distances
  if (convention == BearingConvention::kDas) {
    s.phi = WrapToPi(std::atan2(ry, rx) - leader.theta);
  } else {
    s.phi = WrapToPi(kPi - std::atan2(-ry, -rx) - leader.theta);
  }
  s.alpha = WrapToPi(leader.theta - follower.theta);
  return s;
}

/// Output kinematics (Das convention) from the sines and cosines of φ and γ = φ + α, which a
/// caller evaluating many nearby states (sigma points) can share.
inline LinkRates LinkDerivative(double l, const SinCos& phi, const SinCos& gamma,
                                const Twist& leader, const Twist& follower, double L) {
  LinkRates r;
  r.l_dot = follower.v * gamma.c + L * follower.w * gamma.s - leader.v * phi.c;
  r.phi_dot = (-follower.v * gamma.s + L * follower.w * gamma.c + leader.v * phi.s) / l - leader.w;
  r.alpha_dot = leader.w - follower.w;
  return r;
}

/// Output kinematics (Das convention): [l̇, φ̇, α̇] given the leader's and follower's twists.
inline LinkRates LinkDerivative(const LinkState& s, const Twist& leader, const Twist& follower,
                                double L) {
  return LinkDerivative(s.l, SinCosOf(s.phi), SinCosOf(s.gamma()), leader, follower, L);
}

/// The follower's control-point position and pose implied by a link state and the leader's pose
/// (Das convention): M = p_i + l (cos(θ_i+φ), sin(θ_i+φ)), θ_j = θ_i − α, p_j = M − L(cosθ_j,
/// sinθ_j).
inline Pose2 FollowerPoseFromLink(const Pose2& leader, const LinkState& s, double L) {
  const double b = leader.theta + s.phi, th = leader.theta - s.alpha;
  const SinCos sb = SinCosOf(b), st = SinCosOf(th);
  return {leader.x + s.l * sb.c - L * st.c, leader.y + s.l * sb.s - L * st.s, WrapToPi(th)};
}

/// Jacobian ∂(x_j, y_j)/∂(l, φ, α) of FollowerPoseFromLink (for mapping a link covariance to a
/// position ellipse).
inline Eigen::Matrix<double, 2, 3> FollowerPositionJacobian(const Pose2& leader, const LinkState& s,
                                                            double L) {
  const double b = leader.theta + s.phi, th = leader.theta - s.alpha;
  Eigen::Matrix<double, 2, 3> J;
  J << std::cos(b), -s.l * std::sin(b), -L * std::sin(th),  //
      std::sin(b), s.l * std::cos(b), L * std::cos(th);
  return J;
}

}  // namespace formsim::control::formation
