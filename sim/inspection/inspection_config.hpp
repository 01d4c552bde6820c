#pragma once
/// \file The inspection scenario (type "inspection"), read strictly from YAML; the reader also
/// declares every tunable of the kind (label, unit, validity, slider, group). Keys (defaults in
/// InspectionConfig; angles in degrees, distances in metres):
///   route:        {start: [x, y], straight_length, turn_radius, turn: right|left}
///   posts:        {radius, spacing, side_offset, stagger, turn_outer, turn_inner, omit: [names],
///                  survey_sigma}   reference posts generated along both sides of the U, named
///                  P1, P2, ... (see assets/scenarios/inspection_u_route.yaml); survey_sigma is
///                  the error of their surveyed coordinates (the paper's first error source)
///   obstacles, patches, world: the shared blocks (equipment cabinets, slippery ground)
///   robot:        {name, start: {lateral, along, heading_deg}, body: {...}, drive: {...}}
///   laser:        LaserScannerDef          odometry: WheelOdometryDef
///   localisation: {min_beams, cluster_jump, span_tolerance, fit_tolerance, gate, pair,
///                  range_tolerance, min_subtended_deg, angle_tolerance_deg, max_range}
///                 pair: best_angle (default) | nearest, the pair of posts a fix is tried from
///                 first
///   estimation:   {controller_source: kalman|classical|raw|dead_reckoning|truth,
///                  kalman: {q_per_m, q_per_s, r, p0, nis_gate, reacquire_after},
///                  classical: {limit_step, limit_rate, mean_window, reacquire_after},
///                  heading: {limit_deg, mean_window, reacquire_after}}
///   control:      {rate_hz, feedforward}
///   fuzzy:        {file, s_scale, dphi_scale}   the FLL rule base, relative to the scenario's
///                 folder (Save rewrites it); it is loaded and checked by the reader. Reloading
///                 it during a run is the experiment's action "reload_rules", not a key. The
///                 scales (default 1, live) stretch the universe and every term of the input s
///                 (dphi): the classical scaling factors of a fuzzy controller, see
///                 FuzzyController::SetInputScales.
///   metrics:      {lateral_bound, transient_m}
/// Every number has a hard validity (Tune) that keeps the run finite: lengths within
/// [1e-3, 1e3] m, coordinates within ±1e3 m (also of the robot body and the obstacles, which
/// the shared readers do not bound yet), mass in [1e-3, 1e6] kg, rates that give between 1 and
/// 10^8 world steps per period, probabilities in [0, 1], bounded noise.

#include <string>
#include <vector>

#include "control/inspection/axis_kalman.hpp"
#include "control/inspection/classic_filters.hpp"
#include "control/inspection/post_detector.hpp"
#include "control/inspection/route.hpp"
#include "control/inspection/trilateration.hpp"
#include "sim/core/experiment.hpp"
#include "sim/inspection/laser_scanner.hpp"
#include "sim/inspection/steered_drive.hpp"
#include "sim/inspection/wheel_odometry.hpp"

namespace formsim::sim::inspection {

/// A reference post: where it stands, and where the survey says it stands.
struct InspectionPost {
  std::string name;
  Vec2 position;
  Vec2 surveyed;
};

/// Where the controller's (and the post identification's) pose estimate comes from.
enum class NavSource { kKalman, kClassical, kRaw, kDeadReckoning, kTruth };
const std::vector<std::string>& NavSourceNames();
/// The YAML names of control::inspection::PairChoice, in its order.
const std::vector<std::string>& PairChoiceNames();

struct InspectionConfig {
  // World: floor, the user's obstacles (cabinets...) and patches (the posts are added).
  WorldDef world;
  std::vector<ObstacleDef> obstacles;
  std::vector<PatchDef> patches;
  // Route (Fig. 7).
  Vec2 route_start{3.3, 2.0};
  double straight_length = 18.0;
  double turn_radius = 2.5;
  bool turn_right = true;
  // Reference posts.
  double post_radius = 0.1;
  double post_spacing = 3.0;
  double post_side_offset = 1.3;
  bool post_stagger = true;
  int turn_outer = 5;
  int turn_inner = 2;
  double survey_sigma = 0.02;
  std::vector<InspectionPost> posts;
  // Robot.
  RobotDef body;
  double start_lateral = 0.0, start_along = 0.0, start_heading_deg = 0.0;
  SteeredDriveDef drive;
  LaserScannerDef laser;
  WheelOdometryDef odometry;
  // Localisation.
  control::inspection::PostDetectorDef detector;
  double range_tolerance = 0.10;
  int pair_choice = 0;  ///< index into PairChoiceNames()
  double min_subtended_deg = 20.0;
  double angle_tolerance_deg = 4.0;
  double max_range = 12.0;
  // Estimation.
  int source = 0;  ///< index into NavSourceNames()
  control::inspection::AxisKalmanDef kalman;
  control::inspection::LimitFilterDef limit;
  int mean_window = 5;
  double heading_limit_deg = 10.0;
  int heading_window = 5;
  int heading_reacquire = 10;
  // Control.
  double control_rate_hz = 5.0;
  int control_every = 20;  ///< world steps per control period
  int laser_every = 2;     ///< world steps per scan
  bool feedforward = true;
  std::string fuzzy_file;         ///< resolved path
  std::string fuzzy_text;         ///< the rule base as read (and checked) by the reader
  double fuzzy_s_scale = 1.0;     ///< stretch of the s terms (1 = as written)
  double fuzzy_dphi_scale = 1.0;  ///< stretch of the dphi terms (1 = as written)
  // Metrics.
  double lateral_bound = 0.3;  ///< |true lateral offset| allowed after the transient, m
  double transient_m = 6.0;    ///< start transient excluded from the tracking metrics, m of route

  control::inspection::TrilaterationDef Trilateration() const;
  control::inspection::HeadingFilterDef Heading() const;
  control::inspection::Route MakeRoute() const;
  control::inspection::PostMap SurveyedMap() const;
};

/// Reads everything but the loader's root keys (strict) and declares the tunables. `survey`
/// draws the survey errors of the posts. Throws ScenarioError.
InspectionConfig ReadInspectionConfig(YamlReader& root, const ExperimentSetup& setup, Rng survey);

}  // namespace formsim::sim::inspection
