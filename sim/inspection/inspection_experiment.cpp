#include "sim/inspection/inspection_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "control/common/angle.hpp"
#include "control/inspection/paper_frame.hpp"

namespace formsim::sim {

namespace ins = control::inspection;
using control::AngleDiff;
using ins::Deg;
using ins::Rad;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Recorder columns, in declaration order (see the header for their meaning).
// clang-format off
enum Col {
  kT, kTrueX, kTrueY, kTrueHeading, kRawX, kRawY, kRawHeading, kClassicX, kClassicY, kKfX, kKfY,
  kKfSdX, kKfSdY, kDrX, kDrY, kEstHeading, kErrRaw, kErrClassic, kErrKf, kErrDr, kSTrue,
  kDphiTrue, kSCtrl, kDphiCtrl, kFzU1, kFzU2, kFzU3, kU1, kU2, kU3, kSteer, kSpeed, kPostsSeen,
  kFix, kTurnDr, kTurnDphi, kSlipping, kProgress, kRawEx, kRawEy, kClassicEx, kClassicEy, kKfEx,
  kKfEy, kS1RawX, kS1ClassicX, kS1KfX, kS1TrueX, kS1RawY, kS1ClassicY, kS1KfY, kS1TrueY,
  kColumnCount,
};
const char* const kColumnNames[kColumnCount] = {
    "t", "true_x", "true_y", "true_heading_deg", "raw_x", "raw_y", "raw_heading_deg",
    "classic_x", "classic_y", "kf_x", "kf_y", "kf_sd_x", "kf_sd_y", "dr_x", "dr_y",
    "est_heading_deg", "err_raw", "err_classic", "err_kf", "err_dr", "s_true", "dphi_true_deg",
    "s_ctrl", "dphi_ctrl_deg", "fz_u1", "fz_u2", "fz_u3", "u1", "u2", "u3", "steer_deg", "speed",
    "posts_seen", "fix", "turn_dr", "turn_dphi_deg", "slipping", "progress", "raw_ex", "raw_ey",
    "classic_ex", "classic_ey", "kf_ex", "kf_ey", "s1_raw_x", "s1_classic_x", "s1_kf_x",
    "s1_true_x", "s1_raw_y", "s1_classic_y", "s1_kf_y", "s1_true_y",
};
// clang-format on

int StepsPer(double rate_hz, double dt) {
  return std::max(1, static_cast<int>(std::lround(1.0 / (rate_hz * dt))));
}

}  // namespace

InspectionExperiment::InspectionExperiment(const ExperimentSetup& setup, YamlReader& root)
    : Experiment(setup),
      cfg_(ReadInspectionConfig(root, setup, rng_.Fork(3))),
      laser_(cfg_.laser, rng_.Fork(1)),
      odometry_(cfg_.odometry, rng_.Fork(2)) {
  // World: floor, patches, the user's obstacles (cabinets...), then the reference posts.
  YamlReader world = root.Map("world");
  world_.SetDef(ReadWorldDef(world));
  for (const PatchDef& p : ReadPatches(root)) world_.CreatePatch(p);
  const std::vector<ObstacleDef> obstacles = ReadObstacles(root);
  for (const ObstacleDef& o : obstacles) {
    for (const InspectionPost& p : cfg_.posts)
      if (o.name == p.name)
        root.Fail("obstacles", "obstacle name '" + o.name + "' is taken by a reference post");
    world_.CreateObstacle(o);
  }
  for (const InspectionPost& p : cfg_.posts) {
    ObstacleDef def = DefaultObstacleDef();
    def.name = p.name;
    def.shape = ObstacleDef::Shape::kCircle;
    def.pose = {p.position.x, p.position.y, 0.0};
    def.radius = cfg_.post_radius;
    world_.CreateObstacle(def);
  }
  route_ = cfg_.MakeRoute();
  map_ = cfg_.SurveyedMap();

  // The robot starts near the route start, offsets in the paper convention.
  const ins::RouteProjection start = route_.Project(route_.segments()[0].a, 0);
  const Vec2 along = ins::AzimuthDirection(start.tangent);
  const Vec2 right{along.y, -along.x};
  initial_pose_.x = cfg_.route_start.x + along.x * cfg_.start_along + right.x * cfg_.start_lateral;
  initial_pose_.y = cfg_.route_start.y + along.y * cfg_.start_along + right.y * cfg_.start_lateral;
  initial_pose_.theta = control::WrapToPi(start.tangent + Rad(cfg_.start_heading_deg));
  // The tracked point is the rear axle centre: place the body centre ahead of it.
  RobotDef body = cfg_.body;
  const double theta0 = ins::MathFromPaper(initial_pose_.theta);
  const Vec2 centre0 =
      Pose2{initial_pose_.x, initial_pose_.y, theta0}.ToWorld({-cfg_.drive.rear_axle, 0.0});
  body.pose = {centre0.x, centre0.y, theta0};
  robot_ = &world_.CreateRobot(body);
  auto drive = std::make_unique<SteeredDrive>(cfg_.drive);
  drive_ = drive.get();
  drive_->SetCommand(0.0, 0.0, cfg_.drive.servo_center);
  robot_->SetDrive(std::move(drive));
  fz_.u1 = fz_.u2 = fz_.u3 = kNaN;  // no decision yet

  try {
    fuzzy_.LoadFile(cfg_.fuzzy_file);
  } catch (const std::exception& e) {
    root.Map("fuzzy").Fail("file", e.what());
  }
  cfg_.fuzzy_reload = false;

  // The system is given its initial position and heading (paper section 1.3).
  kf_.Reset(initial_pose_.p());
  heading_.Reset(initial_pose_.theta);
  dr_.Reset(initial_pose_);
  classic_nav_ = raw_nav_ = initial_pose_;
  SyncSettings();
  RegisterParams();
  DeclareColumns();
  Start();
}

void InspectionExperiment::SyncSettings() {
  // Live edits may leave a value outside its meaningful range: bring it back rather than fail.
  cfg_.control_rate_hz = std::clamp(cfg_.control_rate_hz, 0.1, 1.0 / setup_.dt);
  cfg_.laser.rate_hz = std::clamp(cfg_.laser.rate_hz, 0.1, 1.0 / setup_.dt);
  cfg_.laser.resolution_deg = std::clamp(cfg_.laser.resolution_deg, 0.05, 10.0);
  cfg_.kalman.r = std::max(cfg_.kalman.r, 1e-10);
  cfg_.kalman.q_per_m = std::max(cfg_.kalman.q_per_m, 0.0);
  cfg_.kalman.q_per_s = std::max(cfg_.kalman.q_per_s, 0.0);
  cfg_.kalman.reacquire_after = std::max(cfg_.kalman.reacquire_after, 1);
  cfg_.mean_window = std::clamp(cfg_.mean_window, 1, 100);
  cfg_.heading_window = std::clamp(cfg_.heading_window, 1, 100);
  cfg_.detector.min_beams = std::max(cfg_.detector.min_beams, 1);
  cfg_.drive.speed_per_level = std::max(cfg_.drive.speed_per_level, 0.0);
  cfg_.drive.steer_per_unit_deg = std::max(cfg_.drive.steer_per_unit_deg, 1e-4);
  drive_->def() = cfg_.drive;
  laser_.def() = cfg_.laser;
  odometry_.def() = cfg_.odometry;
  kf_.SetDef(cfg_.kalman);
  classic_.Configure(cfg_.limit, cfg_.mean_window);
  heading_.SetDef(cfg_.Heading());
  tri_ = cfg_.Trilateration();
  control_every_ = StepsPer(cfg_.control_rate_hz, setup_.dt);
  laser_every_ = StepsPer(cfg_.laser.rate_hz, setup_.dt);
}

void InspectionExperiment::OnParamsChanged() {
  SyncSettings();
  if (cfg_.fuzzy_reload) {
    cfg_.fuzzy_reload = false;
    const std::string err = ReloadFuzzy();
    if (err.empty()) {
      AddEvent("fuzzy_reloaded", robot_->name(), "rule base reloaded from " + cfg_.fuzzy_file);
    } else {
      AddEvent("fuzzy_reload_failed", robot_->name(), err + " (the previous rule base stays)");
    }
  }
}

std::string InspectionExperiment::ReloadFuzzy() {
  try {
    fuzzy_.LoadFile(cfg_.fuzzy_file);
  } catch (const std::exception& e) {
    return e.what();
  }
  return std::string();
}

void InspectionExperiment::RegisterParams() {
  auto& d = cfg_.drive;
  params_.AddDouble("robot.drive.speed_per_level", "Gains/vehicle scales", "speed per level",
                    &d.speed_per_level, 0.02, 0.4, "m/s");
  params_.AddDouble("robot.drive.steer_per_unit_deg", "Gains/vehicle scales",
                    "steer per servo unit", &d.steer_per_unit_deg, 0.05, 0.5, "deg");
  params_.AddDouble("robot.drive.servo_center", "Gains/vehicle scales", "servo centre",
                    &d.servo_center, 300, 420);
  params_.AddDouble("robot.drive.steer_rate_deg_s", "Gains/vehicle scales", "servo slew rate",
                    &d.steer_rate_deg_s, 10, 360, "deg/s");
  params_.AddDouble("robot.drive.motor_force_max", "Gains/vehicle scales", "motor force limit",
                    &d.motor_force_max, 5, 200, "N");
  params_.AddBool("fuzzy.reload", "Gains/fuzzy", "reload rule base (FLL)", &cfg_.fuzzy_reload);
  params_.AddBool("control.feedforward", "Gains/fuzzy", "turn feed-forward", &cfg_.feedforward);
  params_.AddDouble("control.rate_hz", "Gains/fuzzy", "control rate", &cfg_.control_rate_hz, 1, 50,
                    "Hz");
  auto& l = cfg_.laser;
  params_.AddDouble("laser.range_sigma", "Noise/laser", "range noise σ", &l.range_sigma, 0.0, 0.2,
                    "m");
  params_.AddDouble("laser.angle_sigma_deg", "Noise/laser", "beam jitter σ", &l.angle_sigma_deg,
                    0.0, 1.0, "deg");
  params_.AddDouble("laser.outlier_prob", "Noise/laser", "outlier probability", &l.outlier_prob,
                    0.0, 0.05);
  params_.AddDouble("laser.outlier_sigma", "Noise/laser", "outlier σ", &l.outlier_sigma, 0.0, 2.0,
                    "m");
  params_.AddDouble("laser.resolution_deg", "Noise/laser", "angular resolution", &l.resolution_deg,
                    0.1, 2.0, "deg");
  params_.AddDouble("laser.range_max", "Noise/laser", "max range", &l.range_max, 2.0, 30.0, "m");
  params_.AddDouble("laser.rate_hz", "Noise/laser", "scan rate", &l.rate_hz, 1.0, 100.0, "Hz");
  auto& o = cfg_.odometry;
  params_.AddDouble("odometry.sigma_per_sqrt_m", "Noise/odometry", "encoder noise",
                    &o.sigma_per_sqrt_m, 0.0, 0.05, "m/√m");
  params_.AddDouble("odometry.scale_error_left", "Noise/odometry", "left scale error",
                    &o.scale_error_left, -0.1, 0.1);
  params_.AddDouble("odometry.scale_error_right", "Noise/odometry", "right scale error",
                    &o.scale_error_right, -0.1, 0.1);
  params_
      .AddDouble("posts.survey_sigma", "Noise/survey", "post survey error σ", &cfg_.survey_sigma,
                 0.0, 0.2, "m")
      .requires_reset = true;
  auto& det = cfg_.detector;
  params_.AddDouble("localisation.gate", "Localisation/laser", "identification gate", &det.gate,
                    0.05, 1.4, "m");
  params_.AddDouble("localisation.fit_tolerance", "Localisation/laser", "circle fit tolerance",
                    &det.fit_tolerance, 0.005, 0.2, "m");
  params_.AddInt("localisation.min_beams", "Localisation/laser", "min beams per post",
                 &det.min_beams, 1, 10);
  params_.AddDouble("localisation.max_range", "Localisation/laser", "max post range",
                    &cfg_.max_range, 1.0, 30.0, "m");
  params_.AddDouble("localisation.min_subtended_deg", "Localisation/laser",
                    "min angle between posts", &cfg_.min_subtended_deg, 1.0, 89.0, "deg");
  params_.AddDouble("localisation.angle_tolerance_deg", "Localisation/laser", "angle consistency",
                    &cfg_.angle_tolerance_deg, 0.1, 20.0, "deg");
  params_.AddDouble("localisation.range_tolerance", "Localisation/laser", "circle miss tolerance",
                    &cfg_.range_tolerance, 0.0, 0.5, "m");
  params_.AddChoice("estimation.controller_source", "Estimation/source", "controller uses",
                    &cfg_.source, NavSourceNames());
  auto& k = cfg_.kalman;
  params_.AddDouble("estimation.kalman.q_per_m", "Estimation/Kalman", "Q per metre", &k.q_per_m,
                    1e-7, 1e-1, "m²/m", true);
  params_.AddDouble("estimation.kalman.q_per_s", "Estimation/Kalman", "Q per second", &k.q_per_s,
                    1e-8, 1e-1, "m²/s", true);
  params_.AddDouble("estimation.kalman.r", "Estimation/Kalman", "R (fix variance)", &k.r, 1e-6, 1.0,
                    "m²", true);
  params_.AddDouble("estimation.kalman.nis_gate", "Estimation/Kalman", "innovation gate (≤0 off)",
                    &k.nis_gate, 0.0, 100.0);
  params_.AddInt("estimation.kalman.reacquire_after", "Estimation/Kalman", "re-init after gated",
                 &k.reacquire_after, 1, 200);
  params_.AddDouble("estimation.classical.limit_step", "Estimation/classical", "limit step",
                    &cfg_.limit.max_step, 0.01, 2.0, "m");
  params_.AddDouble("estimation.classical.limit_rate", "Estimation/classical", "limit rate",
                    &cfg_.limit.max_rate, 0.0, 5.0, "m/s");
  params_.AddInt("estimation.classical.mean_window", "Estimation/classical", "mean window",
                 &cfg_.mean_window, 1, 50);
  params_.AddDouble("estimation.heading.limit_deg", "Estimation/heading", "heading limit",
                    &cfg_.heading_limit_deg, 0.5, 45.0, "deg");
  params_.AddInt("estimation.heading.mean_window", "Estimation/heading", "heading mean window",
                 &cfg_.heading_window, 1, 50);
}

void InspectionExperiment::DeclareColumns() {
  cols_.resize(kColumnCount);
  for (int c = 0; c < kColumnCount; ++c) cols_[c] = recorder_.AddColumn(kColumnNames[c]);
}

Pose2 InspectionExperiment::SensorPose() const {
  const Pose2 body = robot_->pose();
  const Vec2 p = body.ToWorld({cfg_.drive.rear_axle, 0.0});
  return {p.x, p.y, body.theta};
}

ins::PaperPose InspectionExperiment::TruePose() const {
  const Pose2 p = SensorPose();
  return {p.x, p.y, ins::PaperFromMath(p.theta)};
}

ins::PaperPose InspectionExperiment::NavPose() const {
  switch (static_cast<NavSource>(cfg_.source)) {
    case NavSource::kKalman:
      return {kf_.position().x, kf_.position().y, heading_.value()};
    case NavSource::kClassical:
      return {classic_nav_.x, classic_nav_.y, heading_.value()};
    case NavSource::kRaw:
      return {raw_nav_.x, raw_nav_.y, heading_.value()};
    case NavSource::kDeadReckoning:
      return dr_.pose();
    case NavSource::kTruth:
      return TruePose();
  }
  return TruePose();
}

void InspectionExperiment::Control(double) {
  if (steps() % control_every_ != 0) return;
  ++control_updates_;
  const ins::PaperPose nav = NavPose();
  const ins::RouteProjection pr = route_.Project(nav.p(), ctrl_hint_);
  ctrl_hint_ = pr.segment;
  s_ctrl_ = pr.lateral;
  dphi_ctrl_ = AngleDiff(nav.theta, pr.tangent);
  if (pr.finished) {
    // End of the route: stop, wheels straight.
    if (!stopped_)
      AddEvent("route_end", robot_->name(), "the estimate reached the end of the route: stopping");
    stopped_ = true;
    fz_ = ins::FuzzyOutputs{};
    fz_.u3 = cfg_.drive.servo_center;
    drive_->SetCommand(0.0, 0.0, cfg_.drive.servo_center);
    return;
  }
  fz_ = fuzzy_.Process(s_ctrl_, Deg(dphi_ctrl_));
  if (!fz_.ok) {
    ++no_rule_;
    if (!no_rule_active_) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "no fuzzy rule fired at s = %.2f m, dphi = %.1f deg: stopping",
                    s_ctrl_, Deg(dphi_ctrl_));
      AddEvent("fuzzy_no_rule", robot_->name(), msg);
    }
    no_rule_active_ = true;
    drive_->SetCommand(0.0, 0.0, cfg_.drive.servo_center);
    return;
  }
  no_rule_active_ = false;
  double u1 = fz_.u1, u2 = fz_.u2, u3 = fz_.u3;
  if (cfg_.feedforward && pr.curvature != 0.0) {
    // The turn's own steering angle and wheel-speed ratio, so the fuzzy rules only correct.
    const double delta = std::atan(cfg_.drive.wheelbase * pr.curvature);
    u3 += Deg(delta) / cfg_.drive.steer_per_unit_deg;
    const double mean = 0.5 * (u1 + u2), k = 0.5 * cfg_.drive.track * pr.curvature;
    u1 += mean * k;
    u2 -= mean * k;
  }
  drive_->SetCommand(u1, u2, u3);
}

void InspectionExperiment::Sense(double t) {
  ++sense_steps_;
  // Encoders every step: dead reckoning (eq. 1) and the Kalman time update with the filtered
  // heading at the start of the step, then the heading follows the encoder increment.
  const ins::OdometryIncrement inc =
      odometry_.Read(drive_->wheel_distance_left(), drive_->wheel_distance_right());
  dr_.Step(inc);
  if (!kf_.Predict(inc.ds, heading_.value(), setup_.dt)) {
    ++kf_faults_;
    char msg[160];
    std::snprintf(msg, sizeof msg,
                  "Kalman prediction at t = %.2f s gave a non-finite state; step skipped", t);
    AddEvent("filter_fault", robot_->name(), msg);
  }
  classic_nav_ = ins::DeadReckonStep(classic_nav_, inc.ds, heading_.value());
  raw_nav_ = ins::DeadReckonStep(raw_nav_, inc.ds, heading_.value());
  heading_.Propagate(inc.dtheta);
  if (drive_->slipping()) ++slip_steps_;

  ScoreTracking(t);
  if (steps() % laser_every_ == 0) ScanAndFix(t);
  if (steps() % 10 == 0 && trail_true_.size() < 20000) {
    trail_true_.push_back(TruePose().p());
    trail_kf_.push_back(kf_.position());
  }
}

void InspectionExperiment::ScoreTracking(double t) {
  const ins::PaperPose truth = TruePose();
  const ins::RouteProjection pr = route_.Project(truth.p(), true_hint_);
  true_hint_ = pr.segment;
  s_true_ = pr.lateral;
  dphi_true_ = AngleDiff(truth.theta, pr.tangent);
  progress_ = pr.progress;
  if (completed_) return;
  if (pr.finished) {
    completed_ = true;
    completion_time_ = t;
    return;
  }
  lateral_.Add(s_true_);
  // The tracking metrics leave out the start transient (the robot starts off the line).
  if (progress_ >= cfg_.transient_m) {
    lateral_tracking_.Add(s_true_);
    dphi_tracking_.Add(Deg(dphi_true_));
  }
}

void InspectionExperiment::ScanAndFix(double t) {
  ++scans_;
  scan_pose_ = SensorPose();
  const ins::Scan scan = laser_.Sample(world_, scan_pose_, robot_, &scan_endpoints_);
  // Identification predicts where the posts should be from the on-board estimate: the chain
  // the controller uses when that is the classical or the raw one (no Kalman filter on board),
  // the Kalman estimate otherwise (dead reckoning alone drifts past the gate, the truth is not
  // known on board).
  const NavSource source = static_cast<NavSource>(cfg_.source);
  const ins::PaperPose nav =
      source == NavSource::kClassical || source == NavSource::kRaw
          ? NavPose()
          : ins::PaperPose{kf_.position().x, kf_.position().y, heading_.value()};
  detection_ = ins::DetectPosts(scan, nav, map_, cfg_.detector);
  fix_ = ins::Localise(detection_.sightings, tri_);
  ++status_counts_[static_cast<int>(fix_.status)];
  used_posts_.clear();
  turn_valid_ = false;
  const ins::PaperPose truth = TruePose();
  if (fix_.ok()) {
    ++fixes_;
    const auto& sa = detection_.sightings[fix_.sighting_a];
    const auto& sb = detection_.sightings[fix_.sighting_b];
    used_posts_ = {sa.post, sb.post};
    raw_ = fix_.position;
    has_raw_ = raw_new_ = true;
    // Heading: eq. 3 on the straights; on the turn eq. 4 with the post nearest the centre.
    double heading = fix_.heading;
    const ins::RouteProjection fp = route_.Project(raw_, ctrl_hint_);
    if (fp.on_arc) {
      const ins::RouteSegment& arc = route_.segments()[fp.segment];
      const auto& inner =
          (sa.position - arc.centre).Norm() <= (sb.position - arc.centre).Norm() ? sa : sb;
      turn_ = ins::TurnGeometry(raw_, arc.centre, arc.radius, arc.clockwise(), inner);
      if (turn_.ok) {
        heading = turn_.heading;
        turn_valid_ = true;
      }
    }
    raw_heading_ = heading;
    heading_.Update(heading);
    const auto r = kf_.Update(raw_);
    if (r.x == ins::AxisUpdate::kGated || r.y == ins::AxisUpdate::kGated) ++kf_gated_;
    if (r.reinitialised()) {
      ++kf_reinit_;
      AddEvent("filter_reset", robot_->name(),
               "Kalman filter re-initialised on the laser fix after repeated gated fixes");
    }
    if (r.fault()) {
      ++kf_faults_;
      char msg[160];
      std::snprintf(msg, sizeof msg,
                    "Kalman update at t = %.2f s gave a non-finite state; fix ignored", t);
      AddEvent("filter_fault", robot_->name(), msg);
    }
    if (classic_.Filter(raw_, t)) {
      classic_nav_.x = classic_.value().x;
      classic_nav_.y = classic_.value().y;
    }
    raw_nav_.x = raw_.x;
    raw_nav_.y = raw_.y;
    err_raw_.Add((raw_ - truth.p()).Norm());
  }
  err_kf_.Add((kf_.position() - truth.p()).Norm());
  err_kf_x_.Add(kf_.position().x - truth.x);
  err_kf_y_.Add(kf_.position().y - truth.y);
  if (classic_.has_value()) err_classic_.Add((classic_.value() - truth.p()).Norm());
  err_dr_.Add((dr_.pose().p() - truth.p()).Norm());
  err_heading_.Add(Deg(AngleDiff(heading_.value(), truth.theta)));
}

void InspectionExperiment::Record(Recorder& rec) {
  const ins::PaperPose truth = TruePose();
  auto set = [&](Col c, double v) { rec.Set(cols_[c], v); };
  const bool raw_now = raw_new_;  // a fix arrived since the last row
  raw_new_ = false;
  set(kT, time());
  set(kTrueX, truth.x);
  set(kTrueY, truth.y);
  set(kTrueHeading, Deg(truth.theta));
  set(kRawX, raw_now ? raw_.x : kNaN);
  set(kRawY, raw_now ? raw_.y : kNaN);
  set(kRawHeading, raw_now ? Deg(raw_heading_) : kNaN);
  set(kErrRaw, raw_now ? (raw_ - truth.p()).Norm() : kNaN);
  if (classic_.has_value()) {
    set(kClassicX, classic_.value().x);
    set(kClassicY, classic_.value().y);
    set(kErrClassic, (classic_.value() - truth.p()).Norm());
  }
  set(kKfX, kf_.position().x);
  set(kKfY, kf_.position().y);
  set(kKfSdX, std::sqrt(kf_.axis_x().P()));
  set(kKfSdY, std::sqrt(kf_.axis_y().P()));
  set(kErrKf, (kf_.position() - truth.p()).Norm());
  set(kDrX, dr_.pose().x);
  set(kDrY, dr_.pose().y);
  set(kErrDr, (dr_.pose().p() - truth.p()).Norm());
  set(kEstHeading, Deg(heading_.value()));
  set(kSTrue, s_true_);
  set(kDphiTrue, Deg(dphi_true_));
  set(kSCtrl, s_ctrl_);
  set(kDphiCtrl, Deg(dphi_ctrl_));
  set(kFzU1, fz_.u1);
  set(kFzU2, fz_.u2);
  set(kFzU3, fz_.u3);
  set(kU1, drive_->u1());
  set(kU2, drive_->u2());
  set(kU3, drive_->u3());
  set(kSteer, Deg(drive_->steer_angle()));
  set(kSpeed, robot_->forward_speed());
  set(kPostsSeen, static_cast<double>(detection_.sightings.size()));
  set(kFix, fix_.ok() ? 1.0 : 0.0);
  set(kTurnDr, turn_valid_ ? turn_.delta_r : kNaN);
  set(kTurnDphi, turn_valid_ ? Deg(turn_.heading_error) : kNaN);
  set(kSlipping, drive_->slipping() ? 1.0 : 0.0);
  set(kProgress, progress_);
  // Per-axis errors (estimate − truth), and the coordinates on the first straight only (the
  // paper's Fig. 8-9 window; NaN elsewhere so the plots zoom onto it).
  set(kRawEx, raw_now ? raw_.x - truth.x : kNaN);
  set(kRawEy, raw_now ? raw_.y - truth.y : kNaN);
  if (classic_.has_value()) {
    set(kClassicEx, classic_.value().x - truth.x);
    set(kClassicEy, classic_.value().y - truth.y);
  }
  set(kKfEx, kf_.position().x - truth.x);
  set(kKfEy, kf_.position().y - truth.y);
  if (true_hint_ == 0 && !completed_) {
    set(kS1RawX, raw_now ? raw_.x : kNaN);
    set(kS1RawY, raw_now ? raw_.y : kNaN);
    if (classic_.has_value()) {
      set(kS1ClassicX, classic_.value().x);
      set(kS1ClassicY, classic_.value().y);
    }
    set(kS1KfX, kf_.position().x);
    set(kS1KfY, kf_.position().y);
    set(kS1TrueX, truth.x);
    set(kS1TrueY, truth.y);
  }
}

FORMSIM_REGISTER_EXPERIMENT("inspection", InspectionExperiment);

}  // namespace formsim::sim
