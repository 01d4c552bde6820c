#include "sim/agv/agv_experiment.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::sim {

using control::AngleDiff;
using control::kMecanumWheels;

FORMSIM_REGISTER_EXPERIMENT("mecanum_agv", AgvExperiment);

namespace {
// Random streams, one per sensor (stable when sensors are added or reordered).
constexpr std::uint64_t kBeaconStream = 1;
constexpr std::uint64_t kEncoderStream = 2;
constexpr std::size_t kTrailLength = 4000;
constexpr long kMaxFilterEvents = 50;
}  // namespace

AgvExperiment::AgvExperiment(const ExperimentSetup& setup, YamlReader& root)
    : Experiment(setup),
      cfg_(ReadAgvConfig(root, setup.dt)),
      beacon_(cfg_.beacon, rng_.Fork(kBeaconStream)),
      encoders_(cfg_.encoders, rng_.Fork(kEncoderStream)),
      filter_(cfg_.filter),
      tracker_(cfg_.tracker) {
  world_.SetDef(cfg_.world);
  for (const ObstacleDef& o : cfg_.obstacles) world_.CreateObstacle(o);
  for (const PatchDef& p : cfg_.patches) world_.CreatePatch(p);
  robot_ = &world_.CreateRobot(cfg_.body);
  auto drive = std::make_unique<MecanumDrive>(cfg_.drive);
  drive_ = drive.get();
  robot_->SetDrive(std::move(drive));

  // Every estimate starts at the true initial pose (the paper's AGV starts from a known pose).
  const Pose2 start = robot_->pose();
  odometry_.Reset(start);
  filter_.Reset(start);
  beacon_pose_ = start;
  encoders_.Latch(drive_->wheel_angles());
  tracker_.SetPath(cfg_.path);
  tracker_.Reset(start);
  true_s_ = cfg_.path.Project(start.p()).s;
  path_samples_ = cfg_.path.Sample(0.05);
  mode_index_ = static_cast<int>(cfg_.mode);

  RegisterParams();
  DeclareColumns();
  Start();
}

void AgvExperiment::RegisterParams() {
  params_.AddChoice("localisation.mode", "Localisation", "pose for control", &mode_index_,
                    LocalisationModeNames());

  control::PoseFilterDef& f = cfg_.filter;
  params_.AddDouble("estimation.q_xy", "Estimation/Q", "q x,y", &f.q_xy, 1e-5, 1.0, "m/√s", true);
  params_.AddDouble("estimation.q_theta", "Estimation/Q", "q θ", &f.q_theta, 1e-5, 1.0, "rad/√s",
                    true);
  params_.AddDouble("estimation.r_xy", "Estimation/R", "r x,y", &f.r_xy, 1e-4, 1.0, "m", true);
  params_.AddDouble("estimation.r_theta", "Estimation/R", "r θ", &f.r_theta, 1e-4, 1.0, "rad",
                    true);
  params_.AddBool("estimation.gate", "Estimation/gate", "innovation gate", &f.gate);
  params_.AddDouble("estimation.gate_probability", "Estimation/gate", "χ² probability",
                    &f.gate_probability, 0.9, 0.99999);
  params_.AddInt("estimation.gate_reset_after", "Estimation/gate", "re-init after rejections",
                 &f.gate_reset_after, 0, 50);
  params_.AddBool("estimation.adaptive_r", "Estimation/adaptive R", "adaptive R", &f.adaptive_r);
  params_.AddInt("estimation.adaptive_window", "Estimation/adaptive R", "window",
                 &f.adaptive_window, 2, 300);

  BeaconDef& b = cfg_.beacon;
  params_.AddDouble("beacon.period", "Noise/beacon", "period Ts", &b.period, 0.02, 1.0, "s");
  params_.AddDouble("beacon.sigma_xy", "Noise/beacon", "σ x,y", &b.sigma_xy, 1e-4, 0.5, "m", true);
  params_.AddDouble("beacon.sigma_theta", "Noise/beacon", "σ θ", &b.sigma_theta, 1e-4, 0.5, "rad",
                    true);
  params_.AddDouble("beacon.outlier_probability", "Noise/beacon", "outlier rate",
                    &b.outlier_probability, 0.0, 0.5);
  params_.AddDouble("beacon.outlier_size", "Noise/beacon", "outlier size", &b.outlier_size, 0.0,
                    3.0, "m");
  params_.AddDouble("beacon.outlier_heading", "Noise/beacon", "outlier heading", &b.outlier_heading,
                    0.0, 3.14, "rad");
  params_.AddDouble("beacon.dropout_probability", "Noise/beacon", "dropout rate",
                    &b.dropout_probability, 0.0, 0.9);

  params_.AddDouble("robot.encoders.speed_noise", "Noise/encoders", "speed σ",
                    &cfg_.encoders.speed_noise, 0.0, 1.0, "rad/s");
  params_
      .AddInt("robot.encoders.ticks_per_rev", "Noise/encoders", "ticks/rev",
              &cfg_.encoders.ticks_per_rev, 0, 20000)
      .requires_reset = true;
  // List items are addressed by index, which only works when the list exists in the file (a
  // GUI save would otherwise create a map): the radius errors are tunable when given.
  static const char* kWheelNames[] = {"FL", "FR", "RL", "RR"};
  for (int i = 0; i < kMecanumWheels && cfg_.radius_error_given; ++i)
    params_.AddDouble("robot.wheels.radius_error." + std::to_string(i), "Noise/wheels",
                      std::string("radius error ") + kWheelNames[i], &cfg_.drive.radius_error[i],
                      -0.05, 0.05);

  control::PathTrackerDef& t = cfg_.tracker;
  params_.AddDouble("control.v_ref", "Gains/path", "v_ref", &t.v_ref, 0.05, 1.0, "m/s");
  struct Loop {
    const char* key;
    const char* group;
    control::PidGains* g;
  };
  for (const Loop& l : {Loop{"control.along", "Gains/along-track es", &t.along},
                        Loop{"control.cross", "Gains/cross-track ed", &t.cross},
                        Loop{"control.heading_pid", "Gains/heading eθ", &t.heading}}) {
    const std::string k = l.key;
    params_.AddDouble(k + ".kp", l.group, "kp", &l.g->kp, 0.0, 10.0);
    params_.AddDouble(k + ".ki", l.group, "ki", &l.g->ki, 0.0, 5.0);
    params_.AddDouble(k + ".kd", l.group, "kd", &l.g->kd, 0.0, 2.0);
  }
}

void AgvExperiment::OnParamsChanged() {
  // Values typed into the YAML-backed table may be out of range: clamp and say so.
  auto clamp_min = [this](double& v, double lo, const char* name) {
    if (!(v >= lo)) {
      AddEvent("invalid_param", cfg_.body.name,
               std::string(name) + " must be >= " + std::to_string(lo) + "; clamped");
      v = lo;
    }
  };
  control::PoseFilterDef& f = cfg_.filter;
  clamp_min(f.q_xy, 0.0, "estimation.q_xy");
  clamp_min(f.q_theta, 0.0, "estimation.q_theta");
  clamp_min(f.r_xy, 0.0, "estimation.r_xy");
  clamp_min(f.r_theta, 0.0, "estimation.r_theta");
  f.gate_probability = std::clamp(f.gate_probability, 0.5, 1.0 - 1e-9);
  f.gate_reset_after = std::max(0, f.gate_reset_after);
  f.adaptive_window = std::max(2, f.adaptive_window);
  BeaconDef& b = cfg_.beacon;
  clamp_min(b.period, 0.005, "beacon.period");
  clamp_min(b.sigma_xy, 0.0, "beacon.sigma_xy");
  clamp_min(b.sigma_theta, 0.0, "beacon.sigma_theta");
  b.outlier_probability = std::clamp(b.outlier_probability, 0.0, 1.0);
  b.dropout_probability = std::clamp(b.dropout_probability, 0.0, 1.0);
  clamp_min(b.outlier_size, 0.0, "beacon.outlier_size");
  clamp_min(cfg_.encoders.speed_noise, 0.0, "robot.encoders.speed_noise");
  for (double& e : cfg_.drive.radius_error) e = std::clamp(e, -0.49, 0.49);
  clamp_min(cfg_.tracker.v_ref, 0.01, "control.v_ref");

  cfg_.mode = static_cast<LocalisationMode>(std::clamp(mode_index_, 0, 2));
  filter_.SetDef(cfg_.filter);
  beacon_.SetDef(cfg_.beacon);
  WheelEncoderDef enc = encoders_.def();
  enc.speed_noise = cfg_.encoders.speed_noise;  // ticks_per_rev waits for a reset
  encoders_.SetDef(enc);
  drive_->def().radius_error = cfg_.drive.radius_error;
  tracker_.SetDef(cfg_.tracker);
}

Pose2 AgvExperiment::ControlPose() const {
  switch (cfg_.mode) {
    case LocalisationMode::kOdometry:
      return odometry_.pose();
    case LocalisationMode::kBeacon:
      return beacon_pose_;
    case LocalisationMode::kFused:
      break;
  }
  return filter_.pose();
}

void AgvExperiment::AddCappedEvent(const std::string& kind, const std::string& message) {
  if (filter_events_++ < kMaxFilterEvents) {
    AddEvent(kind, cfg_.body.name, message);
  } else {
    ++suppressed_events_;
  }
}

void AgvExperiment::RunFilter(double t, const control::BodyTwist& odo) {
  // The odometry twist is constant over the period; predict up to each beacon sample taken
  // during it, fuse, and predict on to t (dead reckoning from the last fused pose).
  auto predict_to = [&](double until) {
    const double dt = until - filter_time_;
    if (dt > 0.0 && !filter_.Predict(odo, dt))
      AddCappedEvent("filter_fault", "Kalman prediction: " + filter_.last_fault());
    filter_time_ = std::max(filter_time_, until);
  };
  while (!pending_.empty()) {
    const BeaconFix fix = pending_.front();
    pending_.pop_front();
    predict_to(fix.t);
    const control::FuseReport rep = filter_.Fuse(fix.pose);
    bool rejected = false;
    switch (rep.outcome) {
      case control::FuseReport::Outcome::kAccepted:
        ++counts_.accepted;
        counts_.nis_sum += rep.nis;
        if (fix.outlier) ++counts_.accepted_outliers;
        break;
      case control::FuseReport::Outcome::kRejected:
        rejected = true;
        ++counts_.rejected;
        if (fix.outlier) ++counts_.rejected_outliers;
        break;
      case control::FuseReport::Outcome::kReinitialised:
        ++counts_.reinitialisations;
        AddCappedEvent("filter_reset", rep.message);
        break;
      case control::FuseReport::Outcome::kFault:
        ++counts_.faults;
        AddCappedEvent("filter_fault", "Kalman update at beacon sample t=" + std::to_string(fix.t) +
                                           ": " + rep.message);
        break;
    }
    last_nis_ = rep.nis;
    fixes_.push_back({fix.t, fix.pose, rejected, rep.nis});
  }
  predict_to(t);
}

void AgvExperiment::Score() {
  const Pose2 truth = robot_->pose();
  const double thr = cfg_.jump_threshold;
  auto add = [&](EstimateStats& s, const Pose2& e) {
    s.Add(e, truth, AngleDiff(e.theta, truth.theta), thr);
  };
  add(stats_odo_, odometry_.pose());
  add(stats_beacon_, beacon_pose_);
  add(stats_fused_, filter_.pose());
}

void AgvExperiment::Estimate(double t) {
  const double period = cfg_.control_every * setup_.dt;
  // Encoders -> wheel speeds -> body twist (nominal radius) -> dead reckoning and filter.
  if (steps() > 0) {
    const control::WheelArray w = encoders_.Read(drive_->wheel_angles(), period);
    odo_twist_ = control::ForwardKinematics(cfg_.drive.geometry, w);
    odometry_.Step(odo_twist_, period);
  }
  RunFilter(t, odo_twist_);
  if (!tracking_done_) Score();
}

void AgvExperiment::Control(double t) {
  if (steps() % cfg_.control_every != 0) return;
  const double period = cfg_.control_every * setup_.dt;
  // Track the path with the chosen estimate; map the twist to wheel speeds (eq. 19).
  cmd_twist_ = tracker_.Step(ControlPose(), period);
  if (tracker_.finished() && !tracking_done_) {
    tracking_done_ = true;
    done_time_ = t;
  }
  wheel_cmd_ = control::InverseKinematics(cfg_.drive.geometry, cmd_twist_);
  control::ScaleToLimit(wheel_cmd_, cfg_.drive.wheel_speed_max);
  drive_->SetWheelCommand(wheel_cmd_);
}

void AgvExperiment::Sense(double t) {
  const Pose2 truth = robot_->pose();
  // True cross-track error, every world step while tracking.
  const control::PathProjection pr =
      cfg_.path.ProjectNear(truth.p(), true_s_, cfg_.tracker.projection_window);
  true_s_ = pr.s;
  true_cross_ = pr.cross_track;
  if (!tracking_done_) cross_track_.Add(true_cross_);

  if (beacon_.Due(t)) {
    const BeaconFix fix = beacon_.Sample(t, truth);
    ++counts_.samples;
    if (!fix.valid) {
      ++counts_.dropouts;
    } else {
      if (fix.outlier) ++counts_.outliers;
      beacon_pose_ = fix.pose;  // the beacon-only estimate: the raw reading, held
      pending_.push_back(fix);
    }
  }
  // Estimators run on the control grid, here so that a recorded row holds truth and estimates
  // of the same instant; Control(t) then uses them.
  if (steps() % cfg_.control_every == 0) Estimate(t);

  // Trails for drawing (bounded).
  if (steps() % cfg_.control_every == 0) {
    auto push = [](std::deque<Vec2>& d, Vec2 p) {
      d.push_back(p);
      if (d.size() > kTrailLength) d.pop_front();
    };
    push(trail_true_, truth.p());
    push(trail_fused_, filter_.pose().p());
    push(trail_odo_, odometry_.pose().p());
  }
}

bool AgvExperiment::completed() const {
  return tracking_done_ && cross_track_.max_abs <= cfg_.completion_tolerance;
}

}  // namespace formsim::sim
