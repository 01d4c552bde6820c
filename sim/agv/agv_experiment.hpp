#pragma once
/// \file The omnidirectional Mecanum AGV of paper 002 as an Experiment (type "agv"):
/// wheel-level Mecanum drive in Box2D, wheel encoders, a StarGazer-like ceiling beacon, the
/// paper's odometry + beacon Kalman filter (with optional innovation gate and adaptive R), and
/// PID tracking of a path at 15 Hz using the odometry, beacon or fused estimate (live switch).
///
/// Step order: Sense(t) samples the beacon when due, scores the true cross-track error and, every
/// `control_every` world steps (15 Hz), runs the estimators: read the encoders over the last
/// period, dead-reckon, run the filter (predict to each beacon sample taken since the last
/// period, fuse it, predict on to t) and score every estimate against the truth. Control(t) on
/// the same grid tracks the path with the chosen estimate and commands the four wheels
/// (inverse kinematics). The world steps (MecanumDrive applies the traction forces). With
/// record_every = control_every every recorded row holds truth and estimates of one instant.
///
/// Recorder channels (stable names, declared in DeclareChannels; every estimator runs whatever
/// the localisation mode, so every channel is sampled in every row):
///   t; x y theta (true pose); odo_x odo_y odo_theta; beacon_x beacon_y beacon_theta (last raw
///   fix, held); fused_x fused_y fused_theta; fused_sd_x fused_sd_y fused_sd_theta (√diag P);
///   cross_track (true, m); cross_track_mm; est_cross_track (what the controller saw, m);
///   es ed etheta (tracker errors); err_odo err_beacon err_fused (position error, mm);
///   herr_odo herr_beacon herr_fused (heading error, deg); nis (last sample); accepted rejected
///   (cumulative counts); vx_cmd vy_cmd omega_cmd; w_cmd_<FL|FR|RL|RR> w_<..> (rad/s);
///   slip_<..> (mm/s); slipping (1 if any wheel at its friction limit); mu (floor under the
///   body centre); mode (0 odometry, 1 beacon, 2 fused); progress (true arc length, m).
///
/// Events: filter_fault (one per run of control periods in which the Kalman prediction or
/// update failed; every failed update is counted in the results' beacon.faults), filter_reset
/// (the gate re-initialised the filter after a streak of rejections).

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "control/agv/dead_reckoning.hpp"
#include "control/agv/path_tracker.hpp"
#include "control/agv/pose_filter.hpp"
#include "sim/agv/agv_config.hpp"
#include "sim/agv/beacon_sensor.hpp"
#include "sim/agv/estimate_stats.hpp"
#include "sim/agv/mecanum_drive.hpp"
#include "sim/agv/wheel_encoders.hpp"
#include "sim/core/bounded_history.hpp"
#include "sim/core/experiment.hpp"
#include "sim/core/multirate.hpp"

namespace formsim::sim::agv {

class AgvExperiment : public ExperimentOf<AgvConfig> {
 public:
  static AgvConfig ReadConfig(YamlReader& root, const ExperimentSetup& setup) {
    return ReadAgvConfig(root, setup.dt);
  }
  AgvExperiment(const ExperimentSetup& setup, const AgvConfig& config);

  std::vector<FigureSpec> Figures() const override;
  void Bounds(Vec2& lo, Vec2& hi) const override;
  Metrics Results() const override;

  /// Read-only views for tests and benchmarks.
  Pose2 true_pose() const { return robot_->pose(); }
  Pose2 odometry_pose() const { return odometry_.pose(); }
  Pose2 beacon_pose() const { return beacon_pose_; }
  Pose2 fused_pose() const { return filter_.pose(); }
  const ca::PoseFilter& filter() const { return filter_; }
  const ca::PathTracker& tracker() const { return tracker_; }
  const MecanumDrive& drive() const { return *drive_; }
  const ErrorStats& cross_track() const { return cross_track_; }
  const EstimateStats& odometry_stats() const { return stats_odo_; }
  const EstimateStats& beacon_stats() const { return stats_beacon_; }
  const EstimateStats& fused_stats() const { return stats_fused_; }
  const BeaconCounts& beacon_counts() const { return counts_; }
  /// Control loop iterations (estimators, tracker, wheel commands) run so far; their number
  /// per simulated second is the measured loop rate of the results.
  long control_updates() const { return control_updates_; }
  /// The loop (or open path) was finished by the tracker with the true cross-track error never
  /// above `metrics.completion_tolerance`.
  bool completed() const;

 protected:
  void Control(double t) override;
  void Sense(double t) override;
  void DrawScene(DrawSink& draw) const override;
  void ApplyTunables(const AgvConfig& next) override;

 private:
  void DeclareChannels();
  void Estimate(double t);
  void RunFilter(double t, const ca::BodyTwist& odo);
  void Score();
  Pose2 ControlPose() const;

  Robot* robot_ = nullptr;
  MecanumDrive* drive_ = nullptr;
  BeaconSensor beacon_;
  WheelEncoders encoders_;
  ca::DeadReckoning odometry_;
  ca::PoseFilter filter_;
  ca::PathTracker tracker_;
  MultiRate control_;  ///< the 15 Hz grid of the estimators and the tracker

  // Estimation state.
  std::deque<BeaconFix> pending_;  ///< beacon samples not yet given to the filter
  Pose2 beacon_pose_;              ///< last valid raw fix
  double filter_time_ = 0.0;       ///< time the filter state refers to
  ca::BodyTwist odo_twist_, cmd_twist_;
  ca::WheelArray wheel_cmd_{};
  double last_nis_ = 0.0;
  EventLog::ConditionId filter_fault_ = 0;
  bool fault_now_ = false;     ///< a prediction or update failed in this control period
  std::string fault_message_;  ///< the first failure of this control period

  // Metrics.
  ErrorStats cross_track_;
  double true_cross_ = 0.0, true_s_ = 0.0;
  EstimateStats stats_odo_, stats_beacon_, stats_fused_;
  BeaconCounts counts_;
  bool tracking_done_ = false;
  double done_time_ = -1.0;
  // The loop as run: iterations, and the wall-clock time of each (estimators in Sense plus the
  // tracker in the next Control), reported as a printed note, never in summary.json.
  long control_updates_ = 0;
  double estimate_ms_ = 0.0;  ///< wall clock of the latest Estimate(), added to its loop
  double loop_ms_sum_ = 0.0, loop_ms_max_ = 0.0;

  // Drawing and figure data (bounded histories).
  struct FixRecord {
    double t;
    Pose2 pose;
    bool rejected;
    double nis;
  };
  BoundedHistory<FixRecord> fixes_;  ///< valid samples for the figures (bounded, evenly thinned)
  std::deque<Vec2> trail_true_, trail_fused_, trail_odo_;
  std::vector<Vec2> path_samples_;
};

}  // namespace formsim::sim::agv
