#pragma once
/// \file Generated formations of any size that hold together: the benchmarks' cascades, the
/// tests' and the shipped formation_swarm_* scenarios. Every choice follows from the robots'
/// limits (see MakeCascadeScenario); the scenario text says so in its header.
///
/// Shape: an equilateral triangular lattice filling a wedge behind the root R1 (row r has r + 1
/// slots, neighbours `spacing` apart, rows spacing·√3/2 apart; a partial last row is filled from
/// its middle). Graph: one l-φ link (R3, diagonally behind R1, fixes the formation's orientation
/// to the root's heading); every other robot is l-l to the two robots of the row ahead nearest to
/// it or, on the wedge's edges, to the robot diagonally ahead and its inner neighbour in its own
/// row, so every l-l triangle is equilateral (|sin(γ_kj − γ_ij)| ≈ 0.87, far from the singular
/// band). The cascade depth is the number of rows − 1, about √(2N).
///
/// Why l-l: the l-l law places a follower from its leaders' positions only, so a disturbance of
/// a leader's heading reaches the next row low-pass filtered (gain at most 1 at every
/// frequency). A chain of l-φ followers straight behind one another instead multiplies heading
/// rates by l/L at each level (3.3 for l = 0.5 m, L = 0.15 m): a deep grid of them falls apart.

#include <string>

namespace formsim::sim::formation {

/// What to generate.
struct CascadeOptions {
  int robots = 10;         ///< ≥ 1
  bool ukf = false;        ///< a UKF per link (see MakeCascadeScenario), else the true states
  double spacing = 0.6;    ///< neighbour distance, m (see MakeCascadeScenario)
  double duration = 10.0;  ///< s
  std::string name;        ///< scenario name; empty: "cascade<N>[_ukf]"
  std::string description; ///< one line; empty: generated
};

/// The YAML text of a `type: formation` scenario (see the file comment for the shape and the
/// graph). Spacing 0.6 m for the default body (circumradius 0.1 m): 0.4 m between neighbours'
/// bodies, about a hundred times the formation's errors, and Box2D's proxies of neighbours (the
/// body's box grown by b2_aabbExtension = 0.1 m) never overlap at any heading (that needs
/// 2√2·0.2 = 0.57 m), so its broad phase finds no pairs and a step costs only the integration.
/// Spacings below the bodies' diameter plus 0.2 m are refused. Per-sample gains 0.15 (K = 15/s; the start offsets of at most 3 cm and 0.05 rad then
/// ask for |ω| ≈ K·3 cm / L = 3 rad/s, a quarter of the drive's limit). The root drives at
/// 2.5 m/s: straight for 2 s, then turns alternating left and right every 4 s, of radius
/// R = max(2E, 5 m) for a formation extending E from R1 (so its farthest robot runs at most
/// v(1 + E/R) = 1.5 v, well under the drive's 6 m/s, and none has to reverse), each change of
/// turn rate spread over 1 s. dt = Tc = 0.01 s, record_every 10. With `ukf` every link's UKF
/// measures [l, φ, α] with the paper's angle noise and 3 mm on the range: with angles alone l is
/// unobservable while the formation drives straight or turns as gently as a large one must, and
/// the estimates of l drift by their σ of about 1 cm. Throws std::invalid_argument for robots < 1
/// or a spacing too small for the bodies.
std::string MakeCascadeScenario(const CascadeOptions& options);

/// Shorthand for the benchmarks and tests.
std::string MakeCascadeScenario(int n_robots, bool ukf, double spacing = 0.6);

}  // namespace formsim::sim::formation
