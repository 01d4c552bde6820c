#pragma once
/// \file Formation switching (beyond paper 000, which names it as future work): the desired
/// outputs of every follower (its slot) move from one shape to another over a transition time.
///
/// A slot is the follower's desired outputs: l-φ (l_des, φ_des), l-l (l_des, l2_des). A
/// transition of duration T started at t0 moves each slot along the straight segment from its
/// value at t0 to the target, with the minimum-jerk profile λ(τ) = 10τ³ − 15τ⁴ + 6τ⁵,
/// τ = (t − t0) / T: the desired values and their rates are continuous, so the laws (with the
/// desired rates as feed-forward, ṡ = ṡ_des − K (s − s_des)) keep ė = −K e along the way. φ moves
/// along the shorter way round.
///
/// The l-l triangle condition (the desired control point must lie off the line through its two
/// leaders, by the loader's singular threshold) is checked along the whole segment by
/// CheckTransition: the profile only re-times the segment, so checking the segment in λ is
/// checking the transition.

#include <string>
#include <vector>

#include "control/formation/formation_graph.hpp"

namespace formsim::control::formation {

/// A follower's desired outputs (unused fields are ignored: φ_des for l-l, l2_des for l-φ).
struct SlotValues {
  double l_des = 0.3;
  double phi_des = 0.0;
  double l2_des = 0.3;
};

/// Rates of the desired outputs (the feed-forward of a moving slot).
struct SlotRates {
  double l_des = 0.0, phi_des = 0.0, l2_des = 0.0;
};

/// The slot of a node as declared in its FormationNodeDef.
inline SlotValues SlotOf(const FormationNodeDef& n) { return {n.l_des, n.phi_des, n.l2_des}; }

/// Minimum-jerk profile λ(τ) on [0, 1] (clamped outside) and its derivative dλ/dτ.
inline double MinimumJerk(double tau) {
  if (tau <= 0.0) return 0.0;
  if (tau >= 1.0) return 1.0;
  return tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
}
inline double MinimumJerkRate(double tau) {
  if (tau <= 0.0 || tau >= 1.0) return 0.0;
  const double u = tau * (1.0 - tau);
  return 30.0 * u * u;
}

/// The point λ ∈ [0, 1] of the segment from `a` to `b` (φ the shorter way round).
SlotValues LerpSlot(const SlotValues& a, const SlotValues& b, double lambda);

/// A transition in progress: every robot's slot from `from` to `to` (same size as the graph).
struct SlotTransition {
  std::vector<SlotValues> from, to;
  double start = 0.0;     ///< s
  double duration = 1.0;  ///< s, > 0
  bool Done(double t) const { return t >= start + duration; }
  /// The slot of robot i at time t and its rate.
  SlotValues At(int i, double t, SlotRates* rates) const;
};

/// Checks a transition: the nodes with every slot moved to λ ∈ [0, 1] along the segment from
/// `from` to `to` (`samples` + 1 evenly spaced values of λ, ends included) must form a valid
/// graph (BuildFormationGraph: every l-l triangle exists and is outside the singular band).
/// Returns "" or the first failure: the robot's name, λ and the graph's reason.
std::string CheckTransition(const std::vector<FormationNodeDef>& nodes,
                            const std::vector<SlotValues>& from, const std::vector<SlotValues>& to,
                            double singular_threshold, int samples = 128, int* robot = nullptr);

}  // namespace formsim::control::formation
