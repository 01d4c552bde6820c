#pragma once
/// \file Velocity control from fused camera, wheel odometry and IMU (paper 004) as an
/// Experiment (type "velocity").
///
/// One or more differential-drive robots (DC motors, slip-based traction on floors of different
/// friction) follow a commanded (v, ω) with one incremental PID per wheel motor. Each robot
/// carries encoders, an IMU and a bearing camera, and runs the sliding-window estimator fusing
/// all three (and, for comparison, a visual-inertial-only one). The speed loop takes its speed
/// from the odometry or from the fused estimate (paper's strategy: the window's velocity at an
/// update, odometry minus the last estimated odometry bias in between), switchable live.
///
/// Step order: Sense(t) samples the IMU, the encoders and the camera when due and feeds the
/// estimators; at every `keyframe_every`-th camera frame both estimators add a keyframe and
/// optimise (timed). On the control grid Sense(t) also forms the speed estimates and scores them
/// against the truth. Control(t) on the same grid reads the command, compensates an estimate jump
/// (optimiser update or feedback switch) in the PIDs and sets the motor voltages.
///
/// Recorder channels (declared in DeclareChannels), per robot with prefix "<name>.": x y theta;
/// v_true w_true (body forward speed, yaw rate); v_cmd w_cmd; v_odo w_odo; v_fused w_fused;
/// v_vi w_vi (empty without vi_baseline); v_feedback (what the speed loop used); err_odo
/// err_fused err_vi (speed estimate − truth; err_vi empty without vi_baseline); slip_l slip_r
/// (slip ratio); mu_l mu_r; u_l u_r (V); i_l i_r (A); bv bw (estimated odometry biases; compare
/// err_odo); bg bg_true (gyro bias); ba_x ba_y; landmarks (in the window); feedback (0 odometry,
/// 1 fused: the live choice, so both estimates are recorded whatever it is); slipping (1 when a
/// wheel is at its friction limit or the robot skids).
///
/// Events: "slip" on each entry into slipping or skidding, filter_fault on each entry into a run
/// of estimator faults (subject "<robot>.fused" or "<robot>.vi_only"; every fault is counted).

#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "control/velocity/command_profile.hpp"
#include "control/velocity/fused_speed.hpp"
#include "control/velocity/sliding_window_estimator.hpp"
#include "control/velocity/speed_loop.hpp"
#include "sim/core/error_stats.hpp"
#include "sim/core/experiment.hpp"
#include "sim/velocity/diff_drive.hpp"
#include "sim/velocity/velocity_config.hpp"
#include "sim/velocity/vio_sensors.hpp"

namespace formsim::sim::velocity {

/// Speed-estimate and control errors of one robot on one floor (or overall).
struct FloorStats {
  ErrorStats odo, fused, vi;                      ///< speed estimate − true speed
  ErrorStats w_odo, w_fused, w_vi;                ///< yaw-rate estimate − true yaw rate
  ErrorStats v_ctrl, w_ctrl;                      ///< true − commanded speed / yaw rate
  double distance = 0.0, turn = 0.0, time = 0.0;  ///< ∫v, ∫ω, ∫dt after settling
  double v_cmd_int = 0.0, w_cmd_int = 0.0;        ///< ∫v_cmd, ∫ω_cmd
};

/// Everything one robot carries.
struct RobotUnit {
  RobotSpec spec;  ///< as configured; feedback follows live edits
  int index = 0;
  Robot* robot = nullptr;
  DiffDrive* drive = nullptr;
  WheelOdometry odometry;
  ImuSensor imu;
  BearingCamera camera;
  cv::SlidingWindowEstimator fused, vi;
  cv::FusedSpeedEstimate fused_speed;
  cv::WheelSpeedLoop loop;

  // Latest values.
  OdometryReading odo;
  double last_gyro = 0.0;  ///< latest raw gyro reading, rad/s
  double v_cmd = 0.0, w_cmd = 0.0;
  cv::BodyTwist est_fused, est_vi, est_feedback;
  cv::WheelSpeedLoop::Output ctrl;
  std::vector<cv::BearingObservation> last_obs;
  long camera_frames = 0;
  int last_feedback = -1;
  double jump_v = 0.0, jump_w = 0.0;  ///< estimate jump at the last update, to compensate
  bool keyframe_now = false;  ///< this step's camera frame is a keyframe (estimators update)
  cv::UpdateReport fused_report, vi_report;  ///< of this step's updates
  double fused_ms = 0.0;                     ///< wall time of this step's fused update
  double imu_offset = 0.0;  ///< test seam: added to the accelerometer x the estimators see

  // Metrics and diagnostics.
  FloorStats total;
  std::map<std::string, FloorStats> floors;
  double update_ms_sum = 0.0, update_ms_max = 0.0;
  long updates = 0, faults = 0;
  EventLog::ConditionId slip = 0, fused_fault = 0, vi_fault = 0;
  std::deque<Vec2> trail;
};

class VelocityExperiment : public ExperimentOf<VelocityConfig> {
 public:
  static VelocityConfig ReadConfig(YamlReader& root, const ExperimentSetup& setup) {
    return ReadVelocityConfig(root, setup.dt);
  }
  VelocityExperiment(const ExperimentSetup& setup, const VelocityConfig& config);

  std::vector<FigureSpec> Figures() const override;
  std::vector<TableSpec> Tables() const override;
  void Bounds(Vec2& lo, Vec2& hi) const override;
  Metrics Results() const override;

  /// Read-only views for tests and benchmarks.
  int robot_count() const { return static_cast<int>(units_.size()); }
  const RobotUnit& unit(int i) const { return *units_[i]; }
  const std::vector<Landmark>& landmarks() const { return landmarks_; }
  /// Seconds between optimiser updates.
  double keyframe_period() const {
    return cfg_.estimator.keyframe_every * cfg_.every.camera * dt();
  }

  /// Test seam for the estimators' fault path, which no valid scenario reaches: from now on the
  /// accelerometer samples robot `i`'s estimators receive are offset by `accel_x` m/s² (the
  /// sensor model and its recorded bias are unchanged).
  void OffsetEstimatorImuForTest(int i, double accel_x) { units_[i]->imu_offset = accel_x; }

 protected:
  void Control(double t) override;
  void Sense(double t) override;
  void DrawScene(DrawSink& draw) const override;
  void ApplyTunables(const VelocityConfig& next) override;

 private:
  void BuildLandmarks();
  void DeclareChannels();
  cv::SlidingWindowDef EstimatorDef(bool use_odometry) const;
  cv::SpeedLoopDef LoopDef() const;
  /// The keyframe updates of this step: every marked unit's fused (and VI-only) window, each on
  /// its own, in parallel on the pool.
  void UpdateEstimators(double t);
  /// What follows a unit's updates, in unit order: fault events, the speed-loop compensation.
  void AfterUpdate(RobotUnit& u, double t);
  void Estimate(RobotUnit& u);
  void Score(RobotUnit& u);
  /// Figures of one robot ("" suffix when there is only one).
  void RobotFigures(const RobotUnit& u, std::vector<FigureSpec>& out) const;

  cv::CommandProfile command_;
  std::vector<Landmark> landmarks_;
  std::vector<std::unique_ptr<RobotUnit>> units_;
};

}  // namespace formsim::sim::velocity
