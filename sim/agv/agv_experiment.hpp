#pragma once
/// \file The omnidirectional Mecanum AGV of paper 002 as an Experiment (type "mecanum_agv"):
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
/// Recorder columns (stable names):
///   t; x y theta (true pose); odo_x odo_y odo_theta; beacon_x beacon_y beacon_theta (last raw
///   fix, held); fused_x fused_y fused_theta; fused_sd_x fused_sd_y fused_sd_theta (√diag P);
///   cross_track (true, m); cross_track_mm; est_cross_track (what the controller saw, m);
///   es ed etheta (tracker errors); err_odo err_beacon err_fused (position error, mm);
///   herr_odo herr_beacon herr_fused (heading error, deg); nis (last sample); accepted rejected
///   (cumulative counts); vx_cmd vy_cmd omega_cmd; w_cmd_<FL|FR|RL|RR> w_<..> (rad/s);
///   slip_<..> (mm/s); slipping (1 if any wheel at its friction limit); mu (floor under the
///   body centre); mode (0 odometry, 1 beacon, 2 fused); progress (true arc length, m).

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "control/agv/dead_reckoning.hpp"
#include "control/agv/path_tracker.hpp"
#include "control/agv/pose_filter.hpp"
#include "sim/core/experiment.hpp"
#include "sim/agv/agv_config.hpp"
#include "sim/agv/agv_metrics.hpp"
#include "sim/agv/beacon_sensor.hpp"
#include "sim/agv/mecanum_drive.hpp"
#include "sim/agv/wheel_encoders.hpp"

namespace formsim::sim {

class AgvExperiment : public Experiment {
 public:
  AgvExperiment(const ExperimentSetup& setup, YamlReader& root);

  std::vector<FigureSpec> Figures() const override;
  std::vector<TableSpec> Tables() const override;
  void Bounds(Vec2& lo, Vec2& hi) const override;
  Json Summary() const override;
  std::string SummaryTable() const override;

  /// Read-only views for tests and benchmarks.
  const AgvConfig& config() const { return cfg_; }
  Pose2 true_pose() const { return robot_->pose(); }
  Pose2 odometry_pose() const { return odometry_.pose(); }
  Pose2 beacon_pose() const { return beacon_pose_; }
  Pose2 fused_pose() const { return filter_.pose(); }
  const control::PoseFilter& filter() const { return filter_; }
  const control::PathTracker& tracker() const { return tracker_; }
  const MecanumDrive& drive() const { return *drive_; }
  const ErrorStats& cross_track() const { return cross_track_; }
  const EstimateStats& odometry_stats() const { return stats_odo_; }
  const EstimateStats& beacon_stats() const { return stats_beacon_; }
  const EstimateStats& fused_stats() const { return stats_fused_; }
  const BeaconCounts& beacon_counts() const { return counts_; }
  /// The loop (or open path) was finished by the tracker with the true cross-track error never
  /// above `metrics.completion_tolerance`.
  bool completed() const;

 protected:
  void Control(double t) override;
  void Sense(double t) override;
  void Record(Recorder& rec) override;
  void DrawScene(DrawSink& draw) const override;
  void OnParamsChanged() override;

 private:
  void RegisterParams();
  void DeclareColumns();
  void Estimate(double t);
  void RunFilter(double t, const control::BodyTwist& odo);
  void Score();
  Pose2 ControlPose() const;
  void AddCappedEvent(const std::string& kind, const std::string& message);

  AgvConfig cfg_;
  Robot* robot_ = nullptr;
  MecanumDrive* drive_ = nullptr;
  BeaconSensor beacon_;
  WheelEncoders encoders_;
  control::DeadReckoning odometry_;
  control::PoseFilter filter_;
  control::PathTracker tracker_;
  int mode_index_ = 2;  ///< mirror of cfg_.mode for the parameter table

  // Estimation state.
  std::deque<BeaconFix> pending_;  ///< beacon samples not yet given to the filter
  Pose2 beacon_pose_;              ///< last valid raw fix
  double filter_time_ = 0.0;       ///< time the filter state refers to
  control::BodyTwist odo_twist_, cmd_twist_;
  control::WheelArray wheel_cmd_{};
  double last_nis_ = 0.0;

  // Metrics.
  ErrorStats cross_track_;
  double true_cross_ = 0.0, true_s_ = 0.0;
  EstimateStats stats_odo_, stats_beacon_, stats_fused_;
  BeaconCounts counts_;
  bool tracking_done_ = false;
  double done_time_ = -1.0;
  long filter_events_ = 0, suppressed_events_ = 0;

  // Drawing and figure data (bounded histories).
  struct FixRecord {
    double t;
    Pose2 pose;
    bool rejected;
    double nis;
  };
  std::vector<FixRecord> fixes_;  ///< every valid sample (for figures)
  std::deque<Vec2> trail_true_, trail_fused_, trail_odo_;
  std::vector<Vec2> path_samples_;

  // Recorder column indices.
  int c_t_ = -1, c_true_ = -1, c_odo_ = -1, c_beacon_ = -1, c_fused_ = -1, c_sd_ = -1;
  int c_cross_ = -1, c_cross_mm_ = -1, c_est_cross_ = -1, c_err_ = -1, c_herr_ = -1,
      c_track_err_ = -1;
  int c_nis_ = -1, c_acc_ = -1, c_rej_ = -1, c_twist_ = -1, c_wcmd_ = -1, c_w_ = -1, c_slip_ = -1;
  int c_slipping_ = -1, c_mu_ = -1, c_mode_ = -1, c_progress_ = -1;
};

}  // namespace formsim::sim
