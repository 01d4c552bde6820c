#pragma once
/// \file The two feedback-linearising formation laws (paper 000, eq. 22-26, re-derived).
///
/// l-φ (one leader i): [l̇; φ̇] = G [v_j; ω_j] + f with G = [[cosγ, L sinγ], [−sinγ/l, L cosγ/l]],
/// det G = L/l > 0, f = [−v_i cosφ; v_i sinφ/l − ω_i]. The command
/// [v_j; ω_j] = G⁻¹ (−K (s − s_des) − f), G⁻¹ = [[cosγ, −l sinγ], [sinγ/L, (l/L) cosγ]],
/// gives ė = −K e exactly. The angular error is wrapped, wrap(φ − φ_des).
///
/// l-l (leaders i, k): [l̇_ij; l̇_kj] = A [v_j; ω_j] − [v_i cosφ_ij; v_k cosφ_kj] with
/// A = [[cosγ_ij, L sinγ_ij], [cosγ_kj, L sinγ_kj]], det A = L sin(γ_kj − γ_ij): singular when the
/// follower's control point lies on the line through its two leaders.
/// Near the singularity (|sin(γ_kj − γ_ij)| < threshold) the inverse is replaced by a damped
/// least-squares inverse with a damping that grows smoothly from 0 at the threshold (Nakamura's
/// variable damping, applied to the unit-free matrix A·diag(1, 1/L)), so the command stays bounded
/// (|[v, Lω]| ≤ |c| / (2 μ_max), μ_max = threshold) and continuous; outside the band the law is
/// the exact inverse.

#include "control/formation/link_kinematics.hpp"

namespace formsim::control::formation {

/// Continuous-time gains (1/s) of a follower's two outputs.
struct FormationGains {
  double k1 = 0.15;  ///< l (l-φ) or l to the first leader (l-l)
  double k2 = 0.08;  ///< φ (l-φ) or l to the second leader (l-l)
};

/// How the printed gains are read: as continuous gains (time constants 1/k, 7-12 s with the
/// paper's numbers) or as per-sample gains of a discrete loop (K = k / Tc).
enum class GainReading { kPrinted, kPerSample };

/// Continuous gain from a printed gain under a reading, for controller period Tc.
inline double EffectiveGain(double k, GainReading reading, double Tc) {
  return reading == GainReading::kPerSample ? k / Tc : k;
}

/// The part of the l-φ law that does not depend on the leader's command: its sines, cosines and
/// error terms. A cascade prepares every follower's at once (in parallel) and finishes them in
/// cascade order, each with its leader's command of the same step.
struct LPhiPrepared {
  double cg = 1, sg = 0;      ///< cos γ, sin γ
  double cp = 1, sp = 0;      ///< cos φ, sin φ
  double e1 = 0, e2 = 0;      ///< −k1 (l − l_des), −k2 wrap(φ − φ_des)
  double l = 1;
};
inline LPhiPrepared PrepareLPhi(const LinkState& s, double l_des, double phi_des,
                                const FormationGains& gains) {
  const SinCos g = SinCosOf(s.gamma()), p = SinCosOf(s.phi);
  return {g.c, g.s, p.c, p.s, -gains.k1 * (s.l - l_des), -gains.k2 * WrapToPi(s.phi - phi_des), s.l};
}
/// The command from a prepared law and the leader's twist (feed-forward).
inline Twist FinishLPhi(const LPhiPrepared& p, const Twist& leader, double L) {
  // Desired output rates: −K e minus the drift f.
  const double c1 = p.e1 + leader.v * p.cp;
  const double c2 = p.e2 - leader.v * p.sp / p.l + leader.w;
  return {p.cg * c1 - p.l * p.sg * c2, (p.sg * c1 + p.l * p.cg * c2) / L};
}

/// l-φ law. `s` is the (measured or estimated) link state, `leader` the leader's twist
/// (feed-forward), `l_des`/`phi_des` the target, `gains` the continuous gains.
inline Twist LPhiControl(const LinkState& s, const Twist& leader, double l_des, double phi_des,
                         const FormationGains& gains, double L) {
  return FinishLPhi(PrepareLPhi(s, l_des, phi_des, gains), leader, L);
}

/// Result of the l-l law.
struct LLCommand {
  Twist cmd;
  double sin_angle = 0.0;  ///< sin(γ_kj − γ_ij): 0 on the singular line
  bool singular = false;   ///< |sin_angle| < threshold: the regularised inverse was used
};

/// The part of the l-l law that does not depend on the leaders' commands (see LPhiPrepared).
struct LLPrepared {
  double e1 = 0, e2 = 0;    ///< −k1 (l_ij − l1_des), −k2 (l_kj − l2_des)
  double cp1 = 1, cp2 = 1;  ///< cos φ_ij, cos φ_kj
  double a = 1, b = 0, c = 0, d = 1;  ///< cos γ_ij, sin γ_ij, cos γ_kj, sin γ_kj
  double p = 1, q = 0, det = 1;       ///< the regularised inverse's terms (singular only)
  double sin_angle = 1;
  bool singular = false;
};
inline LLPrepared PrepareLL(const LinkState& s1, const LinkState& s2, double l1_des, double l2_des,
                            const FormationGains& gains, double singular_threshold) {
  LLPrepared r;
  r.e1 = -gains.k1 * (s1.l - l1_des);
  r.e2 = -gains.k2 * (s2.l - l2_des);
  r.cp1 = SinCosOf(s1.phi).c;
  r.cp2 = SinCosOf(s2.phi).c;
  // Unit-free matrix B = A diag(1, 1/L) acting on u' = [v, Lω]; det B = sin(g2 − g1).
  const SinCos g1 = SinCosOf(s1.gamma()), g2 = SinCosOf(s2.gamma());
  r.a = g1.c, r.b = g1.s, r.c = g2.c, r.d = g2.s;
  r.sin_angle = r.a * r.d - r.b * r.c;
  r.singular = std::abs(r.sin_angle) < singular_threshold;
  if (r.singular) {
    // Damped least squares u' = Bᵀ (B Bᵀ + μ² I)⁻¹ c with μ = thr (1 − (sin/thr)²).
    const double ratio = r.sin_angle / singular_threshold;
    const double mu = singular_threshold * (1.0 - ratio * ratio);
    const double mu2 = mu * mu;
    // B Bᵀ + μ² I = [[1 + μ², ac + bd], [ac + bd, 1 + μ²]] (rows of B are unit vectors).
    r.p = 1.0 + mu2, r.q = r.a * r.c + r.b * r.d;
    r.det = r.p * r.p - r.q * r.q;  // = sin² + μ²(2 + μ²) > 0 whenever μ > 0 or sin ≠ 0
  }
  return r;
}
/// The command from a prepared law and the leaders' twists.
inline LLCommand FinishLL(const LLPrepared& r, const Twist& leader1, const Twist& leader2, double L) {
  // Desired output rates plus the drift: A [v; ω] = c.
  const double c1 = r.e1 + leader1.v * r.cp1;
  const double c2 = r.e2 + leader2.v * r.cp2;
  LLCommand out;
  out.sin_angle = r.sin_angle;
  out.singular = r.singular;
  double u1, u2;
  if (!r.singular) {
    const double det = r.sin_angle;
    u1 = (r.d * c1 - r.b * c2) / det;
    u2 = (-r.c * c1 + r.a * c2) / det;
  } else {
    const double w1 = (r.p * c1 - r.q * c2) / r.det, w2 = (-r.q * c1 + r.p * c2) / r.det;
    u1 = r.a * w1 + r.c * w2;
    u2 = r.b * w1 + r.d * w2;
  }
  out.cmd = {u1, u2 / L};
  return out;
}

/// l-l law. `s1` is the link to the first leader (i), `s2` to the second (k).
inline LLCommand LLControl(const LinkState& s1, const LinkState& s2, const Twist& leader1,
                           const Twist& leader2, double l1_des, double l2_des,
                           const FormationGains& gains, double L, double singular_threshold) {
  return FinishLL(PrepareLL(s1, s2, l1_des, l2_des, gains, singular_threshold), leader1, leader2, L);
}

}  // namespace formsim::control::formation
