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

/// l-φ law. `s` is the (measured or estimated) link state, `leader` the leader's twist
/// (feed-forward), `l_des`/`phi_des` the target, `gains` the continuous gains.
inline Twist LPhiControl(const LinkState& s, const Twist& leader, double l_des, double phi_des,
                         const FormationGains& gains, double L) {
  const double g = s.gamma();
  const double cg = std::cos(g), sg = std::sin(g);
  // Desired output rates: −K e minus the drift f.
  const double c1 = -gains.k1 * (s.l - l_des) + leader.v * std::cos(s.phi);
  const double c2 =
      -gains.k2 * WrapToPi(s.phi - phi_des) - leader.v * std::sin(s.phi) / s.l + leader.w;
  return {cg * c1 - s.l * sg * c2, (sg * c1 + s.l * cg * c2) / L};
}

/// Result of the l-l law.
struct LLCommand {
  Twist cmd;
  double sin_angle = 0.0;  ///< sin(γ_kj − γ_ij): 0 on the singular line
  bool singular = false;   ///< |sin_angle| < threshold: the regularised inverse was used
};

/// l-l law. `s1` is the link to the first leader (i), `s2` to the second (k).
inline LLCommand LLControl(const LinkState& s1, const LinkState& s2, const Twist& leader1,
                           const Twist& leader2, double l1_des, double l2_des,
                           const FormationGains& gains, double L, double singular_threshold) {
  const double g1 = s1.gamma(), g2 = s2.gamma();
  // Desired output rates plus the drift: A [v; ω] = c.
  const double c1 = -gains.k1 * (s1.l - l1_des) + leader1.v * std::cos(s1.phi);
  const double c2 = -gains.k2 * (s2.l - l2_des) + leader2.v * std::cos(s2.phi);
  // Unit-free matrix B = A diag(1, 1/L) acting on u' = [v, Lω]; det B = sin(g2 − g1).
  const double a = std::cos(g1), b = std::sin(g1), c = std::cos(g2), d = std::sin(g2);
  LLCommand out;
  out.sin_angle = a * d - b * c;
  out.singular = std::abs(out.sin_angle) < singular_threshold;
  double u1, u2;
  if (!out.singular) {
    const double det = out.sin_angle;
    u1 = (d * c1 - b * c2) / det;
    u2 = (-c * c1 + a * c2) / det;
  } else {
    // Damped least squares u' = Bᵀ (B Bᵀ + μ² I)⁻¹ c with μ = thr (1 − (sin/thr)²).
    const double r = out.sin_angle / singular_threshold;
    const double mu = singular_threshold * (1.0 - r * r);
    const double mu2 = mu * mu;
    // B Bᵀ + μ² I = [[1 + μ², ac + bd], [ac + bd, 1 + μ²]] (rows of B are unit vectors).
    const double p = 1.0 + mu2, q = a * c + b * d;
    const double det = p * p - q * q;  // = sin² + μ²(2 + μ²) > 0 whenever μ > 0 or sin ≠ 0
    const double w1 = (p * c1 - q * c2) / det, w2 = (-q * c1 + p * c2) / det;
    u1 = a * w1 + c * w2;
    u2 = b * w1 + d * w2;
  }
  out.cmd = {u1, u2 / L};
  return out;
}

}  // namespace formsim::control::formation
