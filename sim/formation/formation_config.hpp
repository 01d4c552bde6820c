#pragma once
/// \file The parsed configuration of a `type: formation` scenario (definition structs with
/// defaults) and its strict reader, which also declares every tunable of the kind.
///
/// Scenario layout (every key optional unless marked; unknown keys are errors):
///   formation: {L: 0.15, bearing: das|printed, gain_reading: printed|per_sample,
///               control_period: dt, settle_time: 1.0, singular_threshold: 0.1}
///   noise: {l_sigma|l_variance: 0, phi_sigma|phi_variance: 0, alpha_sigma|alpha_variance: 0}
///   ukf:   {alpha: 1, beta: 2, kappa: 0, q_l: 1e-8, q_phi: 1e-6, q_alpha: 1e-6,
///           r_l, r_phi, r_alpha (default: the sensor variances), p0_l: 1e-4,
///           p0_phi: 1e-4, p0_alpha: 1e-4, l0_error: 0, substeps: 1 (ours: Euler steps of
///           the prediction per Tc; 1 = the paper's single step)}
///   draw:  {trail_length: 400, trail_every: 5}
///   world, obstacles, patches: the shared blocks
///   robots: (required, a list)
///     - name: R1 (required)   pose: [x, y, theta]   body: {...}   drive: {...}
///       schedule: {kind: segments|line_curve|figure_eight|spiral, v, omega, accel, r0, r_rate,
///                  segments: [{until, v, w}, ...], ramp: 0}  # root leaders only
///       follow:                                             # followers only
///         law: l_phi|l_l (required)   leaders: [R1] or [R1, R2] (required)
///         l_des: 0.3   phi_des: 5π/4 (l_phi)   l2_des: 0.3 (l_l)
///         k_l: 0.15   k_phi: 0.08 (l_phi)   k_l2: 0.08 (l_l)
///         estimator: truth|raw|ukf   measure: [phi, alpha] | [l, phi, alpha] | [alpha]
///         noise: {...}   (per-follower override of the global noise block, key by key)
///   switching:                                              # formation switching (optional)
///     transition: 1.0                   # default transition time, s
///     shapes:                           # named shapes; "initial" is the follow: values
///       - name: column
///         slots: {R2: {l_des, phi_des}, R5: {l_des, l2_des}, ...}  # unlisted followers keep
///                                                                  # their follow: values
///     schedule:                         # fired in list order, each armed once the one
///       - {at: 4.0, to: column, transition: 1.5}                   # before it has fired
///       - {waypoint: [x, y], radius: 0.3, robot: R1, to: initial}
///   avoidance: {enabled: false, safety_distance: 0.3, hysteresis: 0.1, min_dwell: 0.2,
///               k_obstacle: 0.15}       # Das et al. 2002: obstacles as virtual leaders

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "control/formation/formation_graph.hpp"
#include "control/formation/formation_switch.hpp"
#include "control/formation/obstacle_avoidance.hpp"
#include "control/formation/leader_schedule.hpp"
#include "control/formation/link_filter.hpp"
#include "sim/core/unicycle_drive.hpp"
#include "sim/core/world.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim::formation {

namespace cf = control::formation;

/// One noise component, given as σ or as a variance (the paper's h is a variance).
struct NoiseValue {
  double value = 0.0;
  bool is_variance = false;
  bool present = false;  ///< the key was in this block (else inherited)
  double variance() const { return is_variance ? value : value * value; }
  double sigma() const { return is_variance ? std::sqrt(std::max(0.0, value)) : value; }
};

/// Noise of a link sensor: l, φ, α.
struct NoiseDef {
  NoiseValue l, phi, alpha;
};

/// UKF settings shared by every link filter (Q per filter step, R, initial P).
struct UkfDef {
  double alpha = 1.0, beta = 2.0, kappa = 0.0;
  double q_l = 1e-8, q_phi = 1e-6, q_alpha = 1e-6;
  double r_l = -1, r_phi = -1, r_alpha = -1;  ///< < 0: use the sensor's variance
  double p0_l = 1e-4, p0_phi = 1e-4, p0_alpha = 1e-4;
  double l0_error = 0.0;  ///< initial error of the l estimate when l is not measured, m
  int substeps = 1;       ///< Euler steps per prediction (ours; 1 = the paper's)
};

enum class EstimatorMode { kTruth, kRaw, kUkf };
const std::vector<std::string>& EstimatorModeNames();

/// Everything a follower needs beyond the graph node.
struct FollowerDef {
  double k1 = 0.15, k2 = 0.08;  ///< printed gains (k_l, k_phi) or (k_l, k_l2)
  EstimatorMode estimator = EstimatorMode::kTruth;
  cf::MeasurementSet measure = cf::MeasurementSet::kPhiAlpha;
  NoiseDef noise;  ///< own block (components with present = false inherit the global one)
};

/// One robot of the scenario.
struct FormationRobotDef {
  RobotDef body;
  UnicycleDriveDef drive;
  cf::FormationNodeDef node;
  cf::LeaderScheduleDef schedule;  ///< root leaders
  FollowerDef follow;              ///< followers
};

/// A named formation shape: one slot per robot (roots' unused), unlisted followers at their
/// follow: values.
struct ShapeDef {
  std::string name;
  std::vector<cf::SlotValues> slots;
};

/// One entry of the switching schedule.
struct SwitchDef {
  enum class Trigger { kTime, kWaypoint } trigger = Trigger::kTime;
  double at = 0.0;        ///< kTime: s
  Vec2 waypoint;          ///< kWaypoint: when `robot` comes within `radius` of it
  double radius = 0.3;    ///< m
  int robot = 0;          ///< index of the robot that triggers a waypoint switch
  int shape = -1;         ///< target: index into shapes, −1 for the initial shape
  double transition = 1.0;  ///< s
};

/// Formation switching: shapes, the default transition time and the schedule.
struct SwitchingDef {
  double transition = 1.0;
  std::vector<ShapeDef> shapes;
  std::vector<SwitchDef> schedule;
  bool enabled() const { return !shapes.empty(); }
  /// −1 for "initial", the shape's index, or −2 when no such shape.
  int Find(const std::string& name) const {
    if (name == "initial") return -1;
    for (std::size_t k = 0; k < shapes.size(); ++k)
      if (shapes[k].name == name) return static_cast<int>(k);
    return -2;
  }
};

/// Obstacle avoidance settings (off unless enabled).
struct AvoidanceConfig {
  bool present = false;  ///< the scenario has an avoidance: block (its channels exist)
  bool enabled = false;
  cf::AvoidanceDef def;
  double k_obstacle = 0.15;  ///< printed gain on the obstacle distance (read like the others)
};

/// The whole formation scenario (beyond the loader's root keys).
struct FormationConfig {
  double L = 0.15;
  cf::BearingConvention bearing = cf::BearingConvention::kDas;
  cf::GainReading gain_reading = cf::GainReading::kPrinted;
  double control_period = 0.01;
  int control_every = 1;  ///< world steps per control period
  double settle_time = 1.0;
  double singular_threshold = 0.1;
  NoiseDef noise;
  UkfDef ukf;
  int trail_length = 400;
  int trail_every = 5;
  WorldDef world;
  std::vector<ObstacleDef> obstacles;
  std::vector<PatchDef> patches;
  std::vector<FormationRobotDef> robots;
  cf::FormationGraph graph;
  SwitchingDef switching;
  AvoidanceConfig avoidance;
  /// The slots of a shape (−1: initial, the follow: values).
  std::vector<cf::SlotValues> ShapeSlots(int shape) const;
};

/// Reads the formation keys from the scenario root (strict) and declares the tunables.
/// Validates the graph; graph errors are reported at the offending robot's key. Throws
/// ScenarioError.
FormationConfig ReadFormationConfig(YamlReader& root, double dt);

/// The effective noise of a follower: its own components over the global ones.
NoiseDef EffectiveNoise(const FormationConfig& cfg, const FollowerDef& f);

}  // namespace formsim::sim::formation
