#include "sim/agv/agv_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "control/common/angle.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::sim::agv {

using ca::kMecanumWheels;
using control::AngleDiff;

FORMSIM_REGISTER_EXPERIMENT("agv", AgvExperiment);

namespace {
// Random streams, one per sensor (stable when sensors are added or reordered).
constexpr std::uint64_t kBeaconStream = 1;
constexpr std::uint64_t kEncoderStream = 2;
constexpr std::size_t kTrailLength = 4000;
constexpr double kRadToDeg = 180.0 / control::kPi;
}  // namespace

AgvExperiment::AgvExperiment(const ExperimentSetup& setup, const AgvConfig& config)
    : ExperimentOf(setup, config),
      beacon_(cfg_.beacon, rng_.Fork(kBeaconStream)),
      encoders_(cfg_.encoders, rng_.Fork(kEncoderStream)),
      filter_(cfg_.filter),
      tracker_(cfg_.tracker),
      control_(cfg_.control_every) {
  world_.SetDef(cfg_.world);
  for (const ObstacleDef& o : cfg_.obstacles) world_.CreateObstacle(o);
  for (const PatchDef& p : cfg_.patches) world_.CreatePatch(p);
  robot_ = &world_.CreateRobot(cfg_.body);
  auto drive = std::make_unique<MecanumDrive>(cfg_.drive);
  drive_ = drive.get();
  robot_->SetDrive(std::move(drive));
  filter_fault_ = events_.DeclareCondition(event::kFilterFault, cfg_.body.name);

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

  DeclareChannels();
  Start();
}

void AgvExperiment::DeclareChannels() {
  Recorder& r = recorder_;
  auto pose = [&r](const std::string& prefix, std::function<Pose2()> get) {
    r.AddGroup({prefix + "x", prefix + "y", prefix + "theta"}, [get](double* o) {
      const Pose2 p = get();
      o[0] = p.x, o[1] = p.y, o[2] = p.theta;
    });
  };
  pose("", [this] { return robot_->pose(); });
  pose("odo_", [this] { return odometry_.pose(); });
  pose("beacon_", [this] { return beacon_pose_; });
  pose("fused_", [this] { return filter_.pose(); });
  r.AddGroup({"fused_sd_x", "fused_sd_y", "fused_sd_theta"}, [this](double* o) {
    const Eigen::Matrix3d& P = filter_.covariance();
    for (int k = 0; k < 3; ++k) o[k] = std::sqrt(std::max(0.0, P(k, k)));
  });
  r.Add("cross_track", [this] { return true_cross_; });
  r.Add("cross_track_mm", [this] { return true_cross_ * 1000.0; });
  r.AddGroup({"est_cross_track", "es", "ed", "etheta"}, [this](double* o) {
    const ca::TrackingErrors& e = tracker_.errors();
    o[0] = e.cross_track, o[1] = e.es, o[2] = e.ed, o[3] = e.etheta;
  });
  r.AddGroup({"err_odo", "err_beacon", "err_fused", "herr_odo", "herr_beacon", "herr_fused"},
             [this](double* o) {
               const Pose2 truth = robot_->pose();
               const Pose2 est[3] = {odometry_.pose(), beacon_pose_, filter_.pose()};
               for (int k = 0; k < 3; ++k) {
                 o[k] = (est[k].p() - truth.p()).Norm() * 1000.0;
                 o[3 + k] = AngleDiff(est[k].theta, truth.theta) * kRadToDeg;
               }
             });
  r.Add("nis", [this] { return last_nis_; });
  r.Add("accepted", [this] { return static_cast<double>(counts_.accepted); });
  r.Add("rejected", [this] { return static_cast<double>(counts_.rejected); });
  r.AddGroup({"vx_cmd", "vy_cmd", "omega_cmd"}, [this](double* o) {
    o[0] = cmd_twist_.vx, o[1] = cmd_twist_.vy, o[2] = cmd_twist_.omega;
  });
  auto wheels = [&r](const std::string& prefix, std::function<double(int)> get) {
    std::vector<std::string> names;
    for (const char* w : ca::kWheelNames) names.push_back(prefix + w);
    r.AddGroup(names, [get](double* o) {
      for (int i = 0; i < kMecanumWheels; ++i) o[i] = get(i);
    });
  };
  wheels("w_cmd_", [this](int i) { return drive_->command()[i]; });
  wheels("w_", [this](int i) { return drive_->wheel_speeds()[i]; });
  wheels("slip_", [this](int i) { return drive_->slip()[i] * 1000.0; });
  r.Add("slipping", [this] { return drive_->slipping() ? 1.0 : 0.0; });
  r.Add("mu", [this] { return world_.FrictionAt(robot_->pose().p()); });
  r.Add("mode", [this] { return static_cast<double>(cfg_.mode); });
  r.Add("progress", [this] { return true_s_; });
}

void AgvExperiment::ApplyTunables(const AgvConfig& next) {
  cfg_ = next;
  // ticks_per_rev applies on reset (the session never hands over an unapplied reset edit; keep
  // the running encoders' resolution all the same).
  cfg_.encoders.ticks_per_rev = encoders_.def().ticks_per_rev;
  filter_.SetDef(cfg_.filter);
  beacon_.SetDef(cfg_.beacon);
  encoders_.SetDef(cfg_.encoders);
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

void AgvExperiment::RunFilter(double t, const ca::BodyTwist& odo) {
  fault_now_ = false;
  auto fault = [this](auto&& message) {
    if (!fault_now_) fault_message_ = message();
    fault_now_ = true;
  };
  // The odometry twist is constant over the period; predict up to each beacon sample taken
  // during it, fuse, and predict on to t (dead reckoning from the last fused pose).
  auto predict_to = [&](double until) {
    const double dt = until - filter_time_;
    if (dt > 0.0 && !filter_.Predict(odo, dt))
      fault([&] { return "Kalman prediction: " + filter_.last_fault(); });
    filter_time_ = std::max(filter_time_, until);
  };
  while (!pending_.empty()) {
    const BeaconFix fix = pending_.front();
    pending_.pop_front();
    predict_to(fix.t);
    const ca::FuseReport rep = filter_.Fuse(fix.pose);
    bool rejected = false;
    switch (rep.outcome) {
      case ca::FuseReport::Outcome::kAccepted:
        ++counts_.accepted;
        counts_.nis_sum += rep.nis;
        if (fix.outlier) ++counts_.accepted_outliers;
        break;
      case ca::FuseReport::Outcome::kRejected:
        rejected = true;
        ++counts_.rejected;
        if (fix.outlier) ++counts_.rejected_outliers;
        break;
      case ca::FuseReport::Outcome::kReinitialised:
        ++counts_.reinitialisations;
        AddEvent("filter_reset", cfg_.body.name, rep.message);
        break;
      case ca::FuseReport::Outcome::kFault:
        ++counts_.faults;
        fault([&] {
          return "Kalman update at beacon sample t=" + FormatDouble(fix.t) + ": " + rep.message;
        });
        break;
    }
    last_nis_ = rep.nis;
    fixes_.push_back({fix.t, fix.pose, rejected, rep.nis});
  }
  predict_to(t);
  // One event per run of control periods with a failure (the failures are counted above).
  events_.Update(filter_fault_, t, fault_now_, [this] { return fault_message_; });
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
    const ca::WheelArray w = encoders_.Read(drive_->wheel_angles(), period);
    odo_twist_ = ca::ForwardKinematics(cfg_.drive.geometry, w);
    odometry_.Step(odo_twist_, period);
  }
  RunFilter(t, odo_twist_);
  if (!tracking_done_) Score();
}

namespace {
double MillisecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

void AgvExperiment::Control(double t) {
  if (!control_.Due(steps())) return;
  const auto t0 = std::chrono::steady_clock::now();
  ++control_updates_;
  const double period = cfg_.control_every * setup_.dt;
  // Track the path with the chosen estimate; map the twist to wheel speeds (eq. 19).
  cmd_twist_ = tracker_.Step(ControlPose(), period);
  if (tracker_.finished() && !tracking_done_) {
    tracking_done_ = true;
    done_time_ = t;
  }
  wheel_cmd_ = ca::InverseKinematics(cfg_.drive.geometry, cmd_twist_);
  ca::ScaleToLimit(wheel_cmd_, cfg_.drive.wheel_speed_max);
  drive_->SetWheelCommand(wheel_cmd_);
  const double ms = estimate_ms_ + MillisecondsSince(t0);
  estimate_ms_ = 0.0;
  loop_ms_sum_ += ms;
  loop_ms_max_ = std::max(loop_ms_max_, ms);
}

void AgvExperiment::Sense(double t) {
  const Pose2 truth = robot_->pose();
  // True cross-track error, every world step while tracking.
  const ca::PathProjection pr =
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
  if (!control_.Due(steps())) return;
  // Estimators run on the control grid, here so that a recorded row holds truth and estimates
  // of the same instant; Control(t) then uses them.
  const auto t0 = std::chrono::steady_clock::now();
  Estimate(t);
  estimate_ms_ = MillisecondsSince(t0);
  // Trails for drawing (bounded).
  auto push = [](std::deque<Vec2>& d, Vec2 p) {
    d.push_back(p);
    if (d.size() > kTrailLength) d.pop_front();
  };
  push(trail_true_, truth.p());
  push(trail_fused_, filter_.pose().p());
  push(trail_odo_, odometry_.pose().p());
}

bool AgvExperiment::completed() const {
  return tracking_done_ && cross_track_.max_abs <= cfg_.completion_tolerance;
}

}  // namespace formsim::sim::agv
