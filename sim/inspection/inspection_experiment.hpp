#pragma once
/// \file The substation inspection robot of paper 003 as an Experiment (type "inspection"): a
/// steered vehicle with two rear drive motors in Box2D, wheel encoders, a 50 Hz laser scanner
/// that finds known reference posts, trilateration (eq. 2-4), the per-axis Kalman filter of
/// section 1.3 next to the paper's classical limit + mean filters, and the fuzzy controller of
/// section 2 (fuzzylite, rule base in assets/fuzzy/inspection.fll) at 5 Hz on the U-route.
///
/// Loop: Control(t) runs every 1/control.rate_hz: the chosen pose estimate is projected on the
/// route (s, Δφ), the fuzzy controller gives u1, u2, u3, plus an optional curvature
/// feed-forward on the turn. The world steps. Sense(t+dt): encoders → dead reckoning (eq. 1)
/// and Kalman prediction every step; every 1/laser.rate_hz a scan → post identification →
/// two-post fix (eq. 2) and heading (eq. 3 on straights, eq. 4 on the turn) → Kalman update,
/// classical filter, heading filter; every estimate is scored against the truth.
///
/// The robot's position (the paper's (x, y)) is the centre of the rear axle, where the scanner
/// is mounted: that point moves along the heading, so eq. 1 holds without a lever arm, and its
/// heading is tangent to a turn (the paper's ideal θ = 90° to the radius).
///
/// Live tuning: the vehicle scales, noise, localisation and filter settings, the control rate
/// and the controller's source are tunables (YAML paths as keys, see inspection_config.hpp);
/// only the post layout (spacing, side offset) and survey error wait for a reset. The fuzzy
/// input scales (fuzzy.s_scale, fuzzy.dphi_scale) apply live. The action "reload_rules"
/// re-reads the FLL file between two steps (the GUI's "Reload rule base (FLL)" button);
/// success raises the event "fuzzy_reloaded", a bad file the event "fuzzy_reload_failed", and
/// the old rule base stays.
///
/// Recorder channels (declared in DeclareChannels; an empty cell means "no value in this row"):
///   t; true_x true_y true_heading_deg (the tracked point, paper convention);
///   raw_x raw_y raw_heading_deg (only in rows with a new fix since the previous row);
///   classic_x classic_y (once the classical chain has a value); kf_x kf_y kf_sd_x kf_sd_y;
///   dr_x dr_y; est_heading_deg; err_raw (with raw_x) err_classic err_kf err_dr (m);
///   s_true dphi_true_deg; s_ctrl dphi_ctrl_deg (what the controller saw, from its first update);
///   fz_u1 fz_u2 fz_u3 (fuzzy outputs, from the first decision); u1 u2 u3 (after feed-forward);
///   steer_deg; speed; posts_seen; fix (1/0); turn_dr turn_dphi_deg (eq. 4, only on the turn);
///   slipping; progress; raw_ex raw_ey classic_ex classic_ey kf_ex kf_ey (estimate − truth per
///   axis); s1_{raw,classic,kf,true}_{x,y} (coordinates on the first straight only: the window
///   of the paper's Fig. 8-9).
/// Every estimator runs and is recorded whatever the controller uses (the source is a live
/// tunable), so switching it mid-run changes s_ctrl / dphi_ctrl and the tracking, never the
/// columns.

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "control/inspection/axis_kalman.hpp"
#include "control/inspection/classic_filters.hpp"
#include "control/inspection/dead_reckoning.hpp"
#include "control/inspection/fuzzy_controller.hpp"
#include "control/inspection/post_detector.hpp"
#include "control/inspection/route.hpp"
#include "control/inspection/trilateration.hpp"
#include "sim/core/error_stats.hpp"
#include "sim/core/bounded_history.hpp"
#include "sim/core/experiment.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/multirate.hpp"
#include "sim/inspection/inspection_config.hpp"
#include "sim/inspection/laser_scanner.hpp"
#include "sim/inspection/steered_drive.hpp"
#include "sim/inspection/wheel_odometry.hpp"

namespace formsim::sim::inspection {

class InspectionExperiment : public ExperimentOf<InspectionConfig> {
 public:
  static InspectionConfig ReadConfig(YamlReader& root, const ExperimentSetup& setup) {
    return ReadInspectionConfig(root, setup, Rng(setup.seed).Fork(kSurveyStream));
  }
  InspectionExperiment(const ExperimentSetup& setup, const InspectionConfig& config);

  std::vector<FigureSpec> Figures() const override;
  std::vector<ActionSpec> Actions() const override;
  std::string RunAction(const std::string& id) override;
  std::vector<TableSpec> Tables() const override;
  void Bounds(Vec2& lo, Vec2& hi) const override;
  Metrics Results() const override;

  // Read-only views for tests and benchmarks.
  const control::inspection::Route& route() const { return route_; }
  const control::inspection::FuzzyController& fuzzy() const { return fuzzy_; }
  const SteeredDrive& drive() const { return *drive_; }
  /// The true robot reached the end of the route.
  bool completed() const { return completed_; }
  double completion_time() const { return completion_time_; }
  const ErrorStats& error_raw() const { return err_raw_; }
  const ErrorStats& error_classical() const { return err_classic_; }
  const ErrorStats& error_kalman() const { return err_kf_; }
  const ErrorStats& error_dead_reckoning() const { return err_dr_; }
  const ErrorStats& lateral() const { return lateral_; }
  /// Lateral offset after the start transient (route progress beyond metrics.transient_m).
  const ErrorStats& lateral_tracking() const { return lateral_tracking_; }
  /// Lateral offset while the true robot is on the turn (the arc of the route).
  const ErrorStats& lateral_turn() const { return lateral_turn_; }
  long scans() const { return scans_; }
  long fixes() const { return fixes_; }
  long control_updates() const { return control_updates_; }
  /// True pose of the tracked point (rear axle centre, where the scanner is), paper convention.
  control::inspection::PaperPose TruePose() const;
  /// The same in the world's convention (Box2D, drawing).
  Pose2 SensorPose() const;
  control::inspection::PaperPose NavPose() const;

  /// Rng stream of the post survey errors (the reader draws them), beside the laser's (1) and
  /// the encoders' (2).
  static constexpr std::uint64_t kSurveyStream = 3;

 protected:
  void Control(double t) override;
  void Sense(double t) override;
  void DrawScene(DrawSink& draw) const override;
  void ApplyTunables(const InspectionConfig& next) override;

 private:
  void BuildWorld();
  void DeclareChannels();
  void Configure();
  void ScanAndFix(double t);
  void ScoreTracking(double t);
  /// On the first straight and not finished: the rows of the s1_* channels.
  bool OnFirstStraight() const { return true_hint_ == 0 && !completed_; }

  control::inspection::Route route_;
  control::inspection::PostMap map_;
  control::inspection::TrilaterationDef tri_;
  Robot* robot_ = nullptr;
  SteeredDrive* drive_ = nullptr;
  LaserScanner laser_;
  WheelOdometry odometry_;
  control::inspection::FuzzyController fuzzy_;

  // Estimators.
  control::inspection::PositionKalman kf_;
  control::inspection::ClassicPositionFilter classic_;
  control::inspection::HeadingFilter heading_;
  control::inspection::DeadReckoning dr_;
  control::inspection::PaperPose initial_pose_;
  control::inspection::PaperPose classic_nav_, raw_nav_;  ///< last fix carried on by odometry
  bool has_raw_ = false;
  bool raw_new_ = false;  ///< a fix arrived since the last recorded row
  bool raw_row_ = false;  ///< the row being recorded holds a new fix
  Vec2 raw_;
  double raw_heading_ = 0.0;

  // Last scan, for drawing and the record.
  std::vector<Vec2> scan_endpoints_;
  Pose2 scan_pose_;
  control::inspection::PostDetection detection_;
  control::inspection::Fix fix_;
  std::vector<int> used_posts_;
  control::inspection::TurnMeasurement turn_;
  bool turn_valid_ = false;

  // Control.
  MultiRate control_rate_, laser_rate_;
  int ctrl_hint_ = 0, true_hint_ = 0;
  control::inspection::FuzzyOutputs fz_;
  // What the controller saw at its last update (meaningful once control_updates_ > 0).
  double s_ctrl_ = 0.0, dphi_ctrl_ = 0.0;
  double s_true_ = 0.0, dphi_true_ = 0.0, progress_ = 0.0;
  bool stopped_ = false;

  // Events: lasting conditions, declared once.
  EventLog::ConditionId no_rule_ = 0, filter_fault_ = 0;

  // Metrics.
  ErrorStats err_raw_, err_classic_, err_kf_, err_dr_, err_kf_x_, err_kf_y_, err_heading_;
  ErrorStats lateral_, lateral_tracking_, lateral_turn_, dphi_tracking_;
  std::array<long, 5> status_counts_{};
  long scans_ = 0, fixes_ = 0, control_updates_ = 0, no_rule_steps_ = 0;
  long kf_gated_ = 0, kf_reinit_ = 0, kf_faults_ = 0, slip_steps_ = 0, sense_steps_ = 0;
  enum class Fault { kNone, kPredict, kUpdate };
  Fault fault_ = Fault::kNone;  ///< the first Kalman fault of the current step
  bool completed_ = false;
  double completion_time_ = -1.0;
  BoundedHistory<Vec2> trail_true_, trail_kf_;  ///< the whole run, evenly thinned when long
};


}  // namespace formsim::sim::inspection
