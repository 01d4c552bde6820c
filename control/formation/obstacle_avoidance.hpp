#pragma once
/// \file Obstacle avoidance after Das et al. 2002 (paper 000's reference [19]): a follower that
/// comes within a safety distance d_s of an obstacle switches from its law to the l-l law with
/// two "leaders": its (first) real leader, kept at its desired distance l_des, and the
/// obstacle's nearest point p_o, a virtual leader kept at d_s. The virtual leader does not move
/// (v_o = 0), so its heading plays no part: with heading 0 its link is l = |M_j − p_o|,
/// φ = β = atan2 of M_j − p_o, α = −θ_j, γ = β − θ_j, and the l-l law
///   [l̇_1; l̇_o] = A [v_j; ω_j] − [v_1 cos φ_1; 0],  A = [[cos γ_1, L sin γ_1], [cos γ_o, L sin γ_o]]
/// makes both distance errors decay as e^{−k t} (its singular line is the one through the
/// leader and p_o; the regularised inverse of formation_laws.hpp applies there too).
///
/// Switching (with hysteresis, so a follower grazing the boundary does not chatter):
///  - enter when the control point's distance d to the nearest obstacle falls below d_s;
///  - leave after at least `min_dwell` s when the follower's desired slot lies at least
///    d_s + hysteresis from the obstacle and the nominal law's command would not move the
///    control point closer to it (ḋ ≥ 0): the obstacle no longer constrains the follower.

#include "control/formation/formation_laws.hpp"

namespace formsim::control::formation {

/// Switching thresholds of the avoidance behaviour.
struct AvoidanceDef {
  double safety_distance = 0.3;  ///< d_s, m: entry threshold and the distance held
  double hysteresis = 0.1;       ///< m: margin the slot needs before switching back
  double min_dwell = 0.2;        ///< s: shortest time in avoidance
};

/// The link from a stationary virtual leader at p to follower j (heading 0, see above).
inline LinkState VirtualLeaderLink(const Vec2& p, const Pose2& follower, double L) {
  return ComputeLinkState(Pose2{p.x, p.y, 0.0}, follower, L, BearingConvention::kDas);
}

/// Rate of change of the distance from a fixed point p to the control point M of `follower`
/// moving with `cmd`: ḋ = n · Ṁ, n = (M − p) / |M − p|, Ṁ = v (cos θ, sin θ) + L ω (−sin θ, cos θ).
inline double DistanceRate(const Vec2& p, const Pose2& follower, const Twist& cmd, double L) {
  const Vec2 m = ControlPoint(follower, L);
  const Vec2 r = m - p;
  const double d = r.Norm();
  if (!(d > 0.0)) return 0.0;
  const double c = std::cos(follower.theta), s = std::sin(follower.theta);
  const Vec2 mdot{cmd.v * c - L * cmd.w * s, cmd.v * s + L * cmd.w * c};
  return r.Dot(mdot) / d;
}

/// The avoidance law: l-l with the real leader's link `leader_link` (desired l_des, rate
/// l_rate as feed-forward) and the virtual leader at p (desired d_s). `gains.k1` acts on the
/// leader distance, `gains.k2` on the obstacle distance.
inline LLCommand AvoidanceControl(const LinkState& leader_link, const Twist& leader, double l_des,
                                  double l_rate, const Vec2& p, const Pose2& follower,
                                  double safety_distance, const FormationGains& gains, double L,
                                  double singular_threshold) {
  LLPrepared r = PrepareLL(leader_link, VirtualLeaderLink(p, follower, L), l_des, safety_distance,
                           gains, singular_threshold);
  r.e1 += l_rate;
  return FinishLL(r, leader, Twist{}, L);
}

/// The mode for the next period. `avoiding`: the mode now; `d`: distance of the control point
/// to the nearest obstacle; `slot_d`: distance of the desired slot's control point to it;
/// `nominal_rate`: ḋ under the nominal law's command; `since`: time in the current mode, s.
inline bool NextAvoiding(bool avoiding, double d, double slot_d, double nominal_rate, double since,
                         const AvoidanceDef& def) {
  if (!avoiding) return d < def.safety_distance;
  if (since < def.min_dwell) return true;
  return !(slot_d >= def.safety_distance + def.hysteresis && nominal_rate >= 0.0);
}

}  // namespace formsim::control::formation
