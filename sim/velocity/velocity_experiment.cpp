#include "sim/velocity/velocity_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sim/core/number_format.hpp"

namespace formsim::sim::velocity {

FORMSIM_REGISTER_EXPERIMENT("velocity", VelocityExperiment);

namespace {

cv::KeyframeState StartState(const Pose2& pose) {
  cv::KeyframeState k;
  k.set_p({pose.x, pose.y});
  k.set_theta(pose.theta);
  return k;
}

/// The pose the camera sees from. Box2D moves a body by dt·v_new in a step (velocity jumps at
/// the start of the step), while the IMU samples describe a velocity linear in time; the
/// trajectory consistent with the IMU passes through the middle of the last step,
/// p - ½·dt·v. Without this the start-up acceleration would bias the visual scale by ~1 %.
Pose2 CameraPose(const Robot& robot, double dt) {
  Pose2 p = robot.pose();
  const Vec2 v = robot.world_velocity();
  p.x -= 0.5 * dt * v.x;
  p.y -= 0.5 * dt * v.y;
  return p;
}

}  // namespace

VelocityExperiment::VelocityExperiment(const ExperimentSetup& setup, const VelocityConfig& config)
    : ExperimentOf(setup, config) {
  world_.SetDef(cfg_.world);
  for (const ObstacleDef& o : cfg_.obstacles) world_.CreateObstacle(o);
  for (const PatchDef& p : cfg_.patches) world_.CreatePatch(p);
  command_ = cfg_.command.Profile();
  BuildLandmarks();

  const cv::SpeedLoopDef loop = LoopDef();
  for (std::size_t i = 0; i < cfg_.robots.size(); ++i) {
    auto u = std::make_unique<RobotUnit>();
    u->spec = cfg_.robots[i];
    u->index = static_cast<int>(i);
    RobotDef def = cfg_.body;
    def.name = u->spec.name;
    def.pose = u->spec.pose;
    def.color_index = u->index;
    u->robot = &world_.CreateRobot(def);
    auto drive = std::make_unique<DiffDrive>(cfg_.drive);
    u->drive = drive.get();
    u->robot->SetDrive(std::move(drive));
    // One random stream per robot and sensor, stable under reordering of the code.
    const std::uint64_t base = 16 * (i + 1);
    u->odometry.Reset(cfg_.encoders, cfg_.drive, rng_.Fork(base + 1), *u->drive);
    u->imu.Reset(cfg_.imu, rng_.Fork(base + 2), *u->robot);
    u->camera.Reset(cfg_.camera, rng_.Fork(base + 3));
    u->fused = cv::SlidingWindowEstimator(EstimatorDef(true));
    u->vi = cv::SlidingWindowEstimator(EstimatorDef(false));
    u->loop.SetDef(loop);
    u->last_feedback = u->spec.feedback;
    const std::string& n = u->spec.name;
    u->slip = events_.DeclareCondition("slip", n);
    u->fused_fault = events_.DeclareCondition(event::kFilterFault, n, n + ".fused");
    u->vi_fault = events_.DeclareCondition(event::kFilterFault, n, n + ".vi_only");
    units_.push_back(std::move(u));
  }
  DeclareChannels();
  Start();
}

void VelocityExperiment::BuildLandmarks() {
  Rng rng = rng_.Fork(1000);
  const auto& a = cfg_.landmarks.area;
  int id = 0;
  for (int i = 0; i < cfg_.landmarks.count; ++i) {
    const double x = rng.Uniform(a[0], a[2]);
    const double y = rng.Uniform(a[1], a[3]);
    landmarks_.push_back({id++, {x, y}});
  }
  for (const Vec2& p : cfg_.landmarks.points) landmarks_.push_back({id++, p});
}

cv::SlidingWindowDef VelocityExperiment::EstimatorDef(bool use_odometry) const {
  cv::SlidingWindowDef d = cfg_.estimator.window;
  // The estimator knows its sensors' data sheets: IMU and camera noise come from them.
  d.imu.gyro_noise_density = std::max(cfg_.imu.gyro_noise_density, 1e-6);
  d.imu.accel_noise_density = std::max(cfg_.imu.accel_noise_density, 1e-5);
  d.imu.gyro_bias_rw = std::max(cfg_.imu.gyro_bias_rw, 1e-6);
  d.imu.accel_bias_rw = std::max(cfg_.imu.accel_bias_rw, 1e-5);
  d.bearing_sigma = cfg_.camera.bearing_noise;
  d.camera_offset = cfg_.camera.offset;
  d.max_landmark_range = 2.0 * cfg_.camera.range;
  d.use_odometry = use_odometry;
  // Visual-inertial only is the VINS-Mono baseline: it knows nothing of wheels.
  if (!use_odometry) d.use_nonholonomic = false;
  return d;
}

cv::SpeedLoopDef VelocityExperiment::LoopDef() const {
  cv::SpeedLoopDef loop;
  loop.track_width = cfg_.drive.track_width;  // the controller's nominal geometry
  loop.gains.kp = cfg_.control.kp;
  loop.gains.ki = cfg_.control.ki;
  loop.gains.kd = cfg_.control.kd;
  loop.gains.out_min = -cfg_.drive.motor.voltage_max;
  loop.gains.out_max = cfg_.drive.motor.voltage_max;
  return loop;
}

void VelocityExperiment::ApplyTunables(const VelocityConfig& next) {
  cfg_ = next;
  world_.SetDef(cfg_.world);
  command_ = cfg_.command.Profile();
  const cv::SpeedLoopDef loop = LoopDef();
  for (std::size_t i = 0; i < units_.size(); ++i) {
    RobotUnit& u = *units_[i];
    u.spec = cfg_.robots[i];
    u.drive->def() = cfg_.drive;  // terrain; the rest is fixed
    u.odometry.SetDef(cfg_.encoders);
    u.imu.SetDef(cfg_.imu);  // a new configured bias moves the current one by the difference
    u.camera.SetDef(cfg_.camera);
    // Noise edits reach the factors built from now on; the window keeps its size and its
    // landmark parameterisation (both apply on reset).
    for (auto* est : {&u.fused, &u.vi}) {
      const int window = est->def().window_size;
      const cv::LandmarkParam landmarks = est->def().landmarks;
      est->def() = EstimatorDef(est == &u.fused);
      est->def().window_size = window;
      est->def().landmarks = landmarks;
    }
    u.loop.SetDef(loop);  // gains only: the PID state (last output, errors) is kept
  }
}

void VelocityExperiment::DeclareChannels() {
  for (const auto& up : units_) {
    const RobotUnit* u = up.get();
    const std::string p = u->spec.name + ".";
    const bool vi = cfg_.estimator.vi_baseline;  // fixed for the run
    auto add = [&](const char* name, std::function<double()> get) {
      recorder_.Add(p + name, std::move(get));
    };
    recorder_.AddGroup({p + "x", p + "y", p + "theta"}, [u](double* o) {
      const Pose2 pose = u->robot->pose();
      o[0] = pose.x, o[1] = pose.y, o[2] = pose.theta;
    });
    add("v_true", [u] { return u->robot->forward_speed(); });
    add("w_true", [u] { return u->robot->yaw_rate(); });
    add("v_cmd", [u] { return u->v_cmd; });
    add("w_cmd", [u] { return u->w_cmd; });
    add("v_odo", [u] { return u->odo.speed; });
    add("w_odo", [u] { return u->odo.yaw_rate; });
    add("v_fused", [u] { return u->est_fused.v; });
    add("w_fused", [u] { return u->est_fused.omega; });
    add("v_vi", [u, vi] { return vi ? u->est_vi.v : NotSampled(); });
    add("w_vi", [u, vi] { return vi ? u->est_vi.omega : NotSampled(); });
    add("v_feedback", [u] { return u->est_feedback.v; });
    add("err_odo", [u] { return u->odo.speed - u->robot->forward_speed(); });
    add("err_fused", [u] { return u->est_fused.v - u->robot->forward_speed(); });
    add("err_vi", [u, vi] { return vi ? u->est_vi.v - u->robot->forward_speed() : NotSampled(); });
    add("slip_l", [u] { return u->drive->slip_ratio(DiffDrive::kLeft); });
    add("slip_r", [u] { return u->drive->slip_ratio(DiffDrive::kRight); });
    add("mu_l", [u] { return u->drive->friction(DiffDrive::kLeft); });
    add("mu_r", [u] { return u->drive->friction(DiffDrive::kRight); });
    add("u_l", [u] { return u->drive->voltage(DiffDrive::kLeft); });
    add("u_r", [u] { return u->drive->voltage(DiffDrive::kRight); });
    add("i_l", [u] { return u->drive->current(DiffDrive::kLeft); });
    add("i_r", [u] { return u->drive->current(DiffDrive::kRight); });
    add("bv", [u] { return u->fused.latest().bv(); });
    add("bw", [u] { return u->fused.latest().bw(); });
    add("bg", [u] { return u->fused.latest().bg(); });
    add("bg_true", [u] { return u->imu.gyro_bias(); });
    add("ba_x", [u] { return u->fused.latest().ba().x(); });
    add("ba_y", [u] { return u->fused.latest().ba().y(); });
    add("landmarks", [u] {
      int n = 0;
      for (const auto& l : u->fused.Landmarks()) n += l.initialized ? 1 : 0;
      return static_cast<double>(n);
    });
    add("feedback", [u] { return static_cast<double>(u->spec.feedback); });
    add("slipping", [u] { return u->drive->slipping() || u->drive->skidding() ? 1.0 : 0.0; });
  }
}

void VelocityExperiment::UpdateEstimators(double t) {
  // Tasks: 2u is unit u's fused window, 2u + 1 its VI-only baseline; each touches only its own.
  pool().ParallelFor(2 * units_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t task = begin; task < end; ++task) {
      RobotUnit& u = *units_[task / 2];
      if (!u.keyframe_now) continue;
      if (task % 2 == 0) {
        const auto t0 = std::chrono::steady_clock::now();
        u.fused_report = u.fused.AddKeyframe(t, u.last_obs);
        u.fused_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      } else if (cfg_.estimator.vi_baseline) {
        u.vi_report = u.vi.AddKeyframe(t, u.last_obs);
      }
    }
  });
}

void VelocityExperiment::AfterUpdate(RobotUnit& u, double t) {
  u.update_ms_sum += u.fused_ms;
  u.update_ms_max = std::max(u.update_ms_max, u.fused_ms);
  ++u.updates;
  // One event per run of faults; every fault is counted.
  auto fault = [&](EventLog::ConditionId id, const cv::UpdateReport& rep, const char* which) {
    if (!rep.ok) ++u.faults;
    events_.Update(id, t, !rep.ok, [&] {
      return Sprintf("%s estimator fault at t=%.3f s: %s (window restarted)", which, t,
                     rep.message.c_str());
    });
  };
  fault(u.fused_fault, u.fused_report, "fused");
  // The estimate the speed loop used before this update (the fused speed is not touched by
  // the window's update), then after it: the jump the Δv_s compensation removes.
  const cv::BodyTwist before = u.fused_speed.Peek(u.odo.speed, u.odo.yaw_rate);
  const cv::KeyframeState& k = u.fused.latest();
  u.fused_speed.OnUpdate(k.body_velocity().x(), k.bv(), k.bw());
  const cv::BodyTwist after = u.fused_speed.Peek(u.odo.speed, u.odo.yaw_rate);
  u.jump_v += after.v - before.v;
  u.jump_w += after.omega - before.omega;

  if (cfg_.estimator.vi_baseline) fault(u.vi_fault, u.vi_report, "VI-only");
}

void VelocityExperiment::Estimate(RobotUnit& u) {
  u.est_fused = u.fused_speed.Estimate(u.odo.speed, u.odo.yaw_rate);
  if (cfg_.estimator.vi_baseline && u.vi.initialized()) {
    const cv::KeyframeState s = u.vi.Propagated();
    u.est_vi = {s.body_velocity().x(), u.last_gyro - s.bg()};
  }
}

void VelocityExperiment::Score(RobotUnit& u) {
  const double t = time();
  if (t < cfg_.settle_time - 1e-9) return;
  const double v = u.robot->forward_speed(), w = u.robot->yaw_rate();
  const double period = cfg_.every.control * dt();
  FloorStats& f = u.floors[world_.PatchNameAt(u.robot->pose().p())];
  for (FloorStats* s : {&u.total, &f}) {
    s->odo.Add(u.odo.speed - v);
    s->fused.Add(u.est_fused.v - v);
    s->w_odo.Add(u.odo.yaw_rate - w);
    s->w_fused.Add(u.est_fused.omega - w);
    if (cfg_.estimator.vi_baseline) {
      s->vi.Add(u.est_vi.v - v);
      s->w_vi.Add(u.est_vi.omega - w);
    }
    s->v_ctrl.Add(v - u.v_cmd);
    s->w_ctrl.Add(w - u.w_cmd);
    s->distance += v * period;
    s->turn += w * period;
    s->time += period;
    s->v_cmd_int += u.v_cmd * period;
    s->w_cmd_int += u.w_cmd * period;
  }
}

void VelocityExperiment::Sense(double t) {
  const long k = steps();
  const SampleSteps& every = cfg_.every;
  // The sensors of every unit, in unit order (their noise streams are drawn in that order).
  bool any_keyframe = false;
  for (auto& up : units_) {
    RobotUnit& u = *up;
    u.keyframe_now = false;
    if (k == 0) {
      u.last_obs = u.camera.Observe(u.robot->pose(), landmarks_, world_);
      // The robot starts at rest at a known pose: the window starts there.
      u.fused.Initialize(StartState(u.robot->pose()), u.last_obs);
      u.vi.Initialize(StartState(u.robot->pose()), u.last_obs);
      continue;
    }
    if (k % every.imu == 0) {
      ImuReading r = u.imu.Sample(*u.robot, every.imu * dt());
      u.last_gyro = r.gyro;
      if (u.imu_offset != 0.0) r.accel.x() += u.imu_offset;
      u.fused.AddImu(r.dt, r.gyro, r.accel);
      u.vi.AddImu(r.dt, r.gyro, r.accel);
    }
    if (k % every.encoders == 0) {
      u.odo = u.odometry.Sample(*u.drive, every.encoders * dt());
      u.fused.AddOdometry(u.odo.dt, u.odo.speed, u.odo.yaw_rate);
    }
    if (k % every.camera == 0) {
      u.last_obs = u.camera.Observe(CameraPose(*u.robot, dt()), landmarks_, world_);
      u.keyframe_now = ++u.camera_frames % cfg_.estimator.keyframe_every == 0;
      any_keyframe = any_keyframe || u.keyframe_now;
    }
  }
  if (k == 0) return;
  // The sliding-window updates (most of a run's time) in parallel.
  if (any_keyframe) UpdateEstimators(t);
  // Then, unit by unit as before: what the updates change, the estimates, events, trails.
  for (auto& up : units_) {
    RobotUnit& u = *up;
    if (u.keyframe_now) AfterUpdate(u, t);
    if (k % every.control == 0) {
      Estimate(u);
      Score(u);
    }
    // One slip event on each entry into slipping or skidding.
    const bool slipping = u.drive->slipping() || u.drive->skidding();
    events_.Update(u.slip, t, slipping, [&] {
      return Sprintf("%s at t=%.2f s on '%s' (μ=%.2f)",
                     u.drive->skidding() ? "side skid" : "wheel slip", t,
                     world_.PatchNameAt(u.robot->pose().p()).c_str(),
                     world_.FrictionAt(u.robot->pose().p()));
    });
    if (k % 10 == 0) {
      u.trail.push_back(u.robot->pose().p());
      if (u.trail.size() > 2000) u.trail.pop_front();
    }
  }
}

void VelocityExperiment::Control(double t) {
  if (steps() % cfg_.every.control != 0) return;
  for (auto& up : units_) {
    RobotUnit& u = *up;
    command_.At(t, u.v_cmd, u.w_cmd);
    const bool fused = u.spec.feedback == static_cast<int>(Feedback::kFused);
    const cv::BodyTwist est = fused ? u.est_fused : cv::BodyTwist{u.odo.speed, u.odo.yaw_rate};
    // Δv_s compensation: an estimator update (or a switch of the feedback source) moves the
    // estimate without the robot moving differently; the PIDs must not kick on it.
    if (u.last_feedback >= 0 && u.last_feedback != u.spec.feedback) {
      u.loop.CompensateEstimateJump(est.v - u.est_feedback.v, est.omega - u.est_feedback.omega);
    } else if (fused) {
      u.loop.CompensateEstimateJump(u.jump_v, u.jump_w);
    }
    u.jump_v = u.jump_w = 0.0;
    u.last_feedback = u.spec.feedback;
    u.est_feedback = est;
    u.ctrl = u.loop.Step(u.v_cmd, u.w_cmd, est.v, est.omega);
    u.drive->SetVoltages(u.ctrl.u_left, u.ctrl.u_right);
  }
}

}  // namespace formsim::sim::velocity
