#include "sim/inspection/inspection_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "control/common/angle.hpp"
#include "control/inspection/paper_frame.hpp"
#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::sim::inspection {

FORMSIM_REGISTER_EXPERIMENT("inspection", InspectionExperiment);

namespace ins = control::inspection;
using control::AngleDiff;
using ins::Deg;
using ins::Rad;

namespace {

constexpr const char* kReloadAction = "reload_rules";

}  // namespace

InspectionExperiment::InspectionExperiment(const ExperimentSetup& setup, const InspectionConfig& config)
    : ExperimentOf(setup, config),
      laser_(cfg_.laser, rng_.Fork(1)),
      odometry_(cfg_.odometry, rng_.Fork(2)) {
  BuildWorld();
  // The reader loaded and checked this text already; a failure here is a programming error.
  fuzzy_.LoadText(cfg_.fuzzy_text, cfg_.fuzzy_file);
  // The system is given its initial position and heading (paper section 1.3).
  Configure();
  kf_.Reset(initial_pose_.p());
  heading_.Reset(initial_pose_.theta);
  dr_.Reset(initial_pose_);
  classic_nav_ = raw_nav_ = initial_pose_;
  no_rule_ = events_.DeclareCondition("fuzzy_no_rule", robot_->name());
  filter_fault_ = events_.DeclareCondition(event::kFilterFault, robot_->name());
  DeclareChannels();
  Start();
}

void InspectionExperiment::BuildWorld() {
  // World: floor, patches, the user's obstacles (cabinets...), then the reference posts.
  world_.SetDef(cfg_.world);
  for (const PatchDef& p : cfg_.patches) world_.CreatePatch(p);
  for (const ObstacleDef& o : cfg_.obstacles) world_.CreateObstacle(o);
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
}

void InspectionExperiment::Configure() {
  drive_->def() = cfg_.drive;
  laser_.def() = cfg_.laser;
  odometry_.def() = cfg_.odometry;
  kf_.SetDef(cfg_.kalman);
  classic_.Configure(cfg_.limit, cfg_.mean_window);
  heading_.SetDef(cfg_.Heading());
  tri_ = cfg_.Trilateration();
  fuzzy_.SetInputScales(cfg_.fuzzy_s_scale, cfg_.fuzzy_dphi_scale);
  control_rate_ = MultiRate(cfg_.control_every);
  laser_rate_ = MultiRate(cfg_.laser_every);
}

void InspectionExperiment::ApplyTunables(const InspectionConfig& next) {
  // The posts (survey errors) apply on reset only and are unchanged in `next`; the rule base
  // stays as loaded (reloading it is the action).
  cfg_ = next;
  Configure();
}

std::vector<ActionSpec> InspectionExperiment::Actions() const {
  return {{kReloadAction, "Reload rule base (FLL)", "Gains/fuzzy",
           "Re-reads " + cfg_.fuzzy_file + " between two steps; a bad file keeps the current rules"}};
}

std::string InspectionExperiment::RunAction(const std::string& id) {
  if (id != kReloadAction) return Experiment::RunAction(id);
  try {
    // Read like every file formsim opens (a regular file, bounded); keeps the previous engine on
    // any error.
    fuzzy_.LoadText(ReadBoundedFile(cfg_.fuzzy_file), cfg_.fuzzy_file);
  } catch (const std::exception& e) {
    AddEvent("fuzzy_reload_failed", robot_->name(), std::string(e.what()) + " (the previous rule base stays)");
    return e.what();
  }
  AddEvent("fuzzy_reloaded", robot_->name(), "rule base reloaded from " + cfg_.fuzzy_file);
  return "";
}

void InspectionExperiment::DeclareChannels() {
  Recorder& r = recorder_;
  r.AddGroup({"true_x", "true_y", "true_heading_deg"}, [this](double* o) {
    const ins::PaperPose p = TruePose();
    o[0] = p.x, o[1] = p.y, o[2] = Deg(p.theta);
  });
  r.AddGroup({"raw_x", "raw_y", "raw_heading_deg"}, [this](double* o) {
    if (!raw_row_) return;
    o[0] = raw_.x, o[1] = raw_.y, o[2] = Deg(raw_heading_);
  });
  r.AddGroup({"classic_x", "classic_y"}, [this](double* o) {
    if (!classic_.has_value()) return;
    o[0] = classic_.value().x, o[1] = classic_.value().y;
  });
  r.AddGroup({"kf_x", "kf_y", "kf_sd_x", "kf_sd_y"}, [this](double* o) {
    o[0] = kf_.position().x, o[1] = kf_.position().y;
    o[2] = std::sqrt(kf_.axis_x().P()), o[3] = std::sqrt(kf_.axis_y().P());
  });
  r.AddGroup({"dr_x", "dr_y"}, [this](double* o) { o[0] = dr_.pose().x, o[1] = dr_.pose().y; });
  r.Add("est_heading_deg", [this] { return Deg(heading_.value()); });
  r.Add("err_raw", [this] { return raw_row_ ? (raw_ - TruePose().p()).Norm() : NotSampled(); });
  r.Add("err_classic", [this] {
    return classic_.has_value() ? (classic_.value() - TruePose().p()).Norm() : NotSampled();
  });
  r.Add("err_kf", [this] { return (kf_.position() - TruePose().p()).Norm(); });
  r.Add("err_dr", [this] { return (dr_.pose().p() - TruePose().p()).Norm(); });
  r.AddGroup({"s_true", "dphi_true_deg"}, [this](double* o) { o[0] = s_true_, o[1] = Deg(dphi_true_); });
  r.AddGroup({"s_ctrl", "dphi_ctrl_deg", "fz_u1", "fz_u2", "fz_u3"}, [this](double* o) {
    if (control_updates_ == 0) return;  // no decision yet
    o[0] = s_ctrl_, o[1] = Deg(dphi_ctrl_);
    o[2] = fz_.u1, o[3] = fz_.u2, o[4] = fz_.u3;
  });
  r.AddGroup({"u1", "u2", "u3"}, [this](double* o) { o[0] = drive_->u1(), o[1] = drive_->u2(), o[2] = drive_->u3(); });
  r.Add("steer_deg", [this] { return Deg(drive_->steer_angle()); });
  r.Add("speed", [this] { return robot_->forward_speed(); });
  r.Add("posts_seen", [this] { return static_cast<double>(detection_.sightings.size()); });
  r.Add("fix", [this] { return fix_.ok() ? 1.0 : 0.0; });
  r.AddGroup({"turn_dr", "turn_dphi_deg"}, [this](double* o) {
    if (!turn_valid_) return;
    o[0] = turn_.delta_r, o[1] = Deg(turn_.heading_error);
  });
  r.Add("slipping", [this] { return drive_->slipping() ? 1.0 : 0.0; });
  r.Add("progress", [this] { return progress_; });
  // Per-axis errors (estimate − truth).
  r.AddGroup({"raw_ex", "raw_ey"}, [this](double* o) {
    if (!raw_row_) return;
    const ins::PaperPose t = TruePose();
    o[0] = raw_.x - t.x, o[1] = raw_.y - t.y;
  });
  r.AddGroup({"classic_ex", "classic_ey"}, [this](double* o) {
    if (!classic_.has_value()) return;
    const ins::PaperPose t = TruePose();
    o[0] = classic_.value().x - t.x, o[1] = classic_.value().y - t.y;
  });
  r.AddGroup({"kf_ex", "kf_ey"}, [this](double* o) {
    const ins::PaperPose t = TruePose();
    o[0] = kf_.position().x - t.x, o[1] = kf_.position().y - t.y;
  });
  // The coordinates on the first straight only (the paper's Fig. 8-9 window; empty elsewhere
  // so the plots zoom onto it).
  r.AddGroup({"s1_raw_x", "s1_classic_x", "s1_kf_x", "s1_true_x", "s1_raw_y", "s1_classic_y", "s1_kf_y",
              "s1_true_y"},
             [this](double* o) {
               if (!OnFirstStraight()) return;
               const ins::PaperPose t = TruePose();
               if (raw_row_) o[0] = raw_.x, o[4] = raw_.y;
               if (classic_.has_value()) o[1] = classic_.value().x, o[5] = classic_.value().y;
               o[2] = kf_.position().x, o[6] = kf_.position().y;
               o[3] = t.x, o[7] = t.y;
             });
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

void InspectionExperiment::Control(double t) {
  if (!control_rate_.Due(steps())) return;
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
  // One event per entry into a stretch where no rule fires.
  events_.Update(no_rule_, t, !fz_.ok, [&] {
    return Sprintf("no fuzzy rule fired at s = %.2f m, dphi = %.1f deg: stopping", s_ctrl_,
                   Deg(dphi_ctrl_));
  });
  if (!fz_.ok) {
    ++no_rule_steps_;
    drive_->SetCommand(0.0, 0.0, cfg_.drive.servo_center);
    return;
  }
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
  fault_ = Fault::kNone;
  // Encoders every step: dead reckoning (eq. 1) and the Kalman time update with the filtered
  // heading at the start of the step, then the heading follows the encoder increment.
  const ins::OdometryIncrement inc =
      odometry_.Read(drive_->wheel_distance_left(), drive_->wheel_distance_right());
  dr_.Step(inc);
  if (!kf_.Predict(inc.ds, heading_.value(), setup_.dt)) {
    ++kf_faults_;
    fault_ = Fault::kPredict;
  }
  classic_nav_ = ins::DeadReckonStep(classic_nav_, inc.ds, heading_.value());
  raw_nav_ = ins::DeadReckonStep(raw_nav_, inc.ds, heading_.value());
  heading_.Propagate(inc.dtheta);
  if (drive_->slipping()) ++slip_steps_;

  ScoreTracking(t);
  if (laser_rate_.Due(steps())) ScanAndFix(t);
  if (steps() % 10 == 0) {
    trail_true_.push_back(TruePose().p());
    trail_kf_.push_back(kf_.position());
  }
  // One event per entry into a run of steps with a Kalman fault; every fault is counted.
  events_.Update(filter_fault_, t, fault_ != Fault::kNone, [&] {
    const std::string when = FormatSimTime(t);
    return fault_ == Fault::kPredict
               ? "Kalman prediction at " + when + " gave a non-finite state; step skipped"
               : "Kalman update at " + when + " gave a non-finite state; fix ignored";
  });
  // The row recorded after this step (if any) shows the fixes that arrived since the last row.
  if (steps() % setup_.record_every == 0) {
    raw_row_ = raw_new_;
    raw_new_ = false;
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
  if (pr.on_arc) lateral_turn_.Add(s_true_);
}

void InspectionExperiment::ScanAndFix(double t) {
  ++scans_;
  scan_pose_ = SensorPose();
  const ins::Scan scan = laser_.Sample(world_, scan_pose_, robot_, &scan_endpoints_, &pool());
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
      if (fault_ == Fault::kNone) fault_ = Fault::kUpdate;
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

}  // namespace formsim::sim::inspection
