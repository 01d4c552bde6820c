#include "sim/velocity/velocity_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "control/common/angle.hpp"

namespace formsim::sim::vio {

namespace {

constexpr double kDeg = control::kPi / 180.0;

/// World steps between two samples of a sensor running at `rate` Hz.
int StepsPer(double rate, double dt) {
  return std::max(1, static_cast<int>(std::lround(1.0 / (rate * dt))));
}

control::vio::KeyframeState StartState(const Pose2& pose) {
  control::vio::KeyframeState k;
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

VelocityExperiment::VelocityExperiment(const ExperimentSetup& setup, YamlReader& root)
    : Experiment(setup), cfg_(ReadVelocityConfig(root)) {
  world_.SetDef(cfg_.world);
  for (const ObstacleDef& o : cfg_.obstacles) world_.CreateObstacle(o);
  for (const PatchDef& p : cfg_.patches) world_.CreatePatch(p);
  // Every patch gets a terrain entry (a copy of the floor's unless given), so it can be tuned.
  for (const PatchDef& p : cfg_.patches)
    cfg_.drive.terrain.emplace(p.name, cfg_.drive.floor_terrain);
  command_ = cfg_.command.Profile();
  BuildLandmarks();

  const double dt = setup.dt;
  imu_every_ = StepsPer(cfg_.imu.rate, dt);
  enc_every_ = StepsPer(cfg_.encoders.rate, dt);
  cam_every_ = StepsPer(cfg_.camera.rate, dt);
  ctrl_every_ = StepsPer(cfg_.control.rate, dt);
  keyframe_every_ = cfg_.estimator.keyframe_every;
  fov_deg_ = cfg_.camera.fov / kDeg;
  parallax_deg_ = cfg_.estimator.window.min_parallax / kDeg;

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
    u->fused = control::vio::SlidingWindowEstimator(EstimatorDef(true));
    u->vi = control::vio::SlidingWindowEstimator(EstimatorDef(false));
    u->last_feedback = u->spec.feedback;
    units_.push_back(std::move(u));
  }
  ApplySettings();
  RegisterParams();
  DeclareColumns();
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

control::vio::SlidingWindowDef VelocityExperiment::EstimatorDef(bool use_odometry) const {
  control::vio::SlidingWindowDef d = cfg_.estimator.window;
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

void VelocityExperiment::ApplySettings() {
  world_.SetDef(cfg_.world);
  cfg_.camera.fov = fov_deg_ * kDeg;
  cfg_.estimator.window.min_parallax = parallax_deg_ * kDeg;
  command_ = cfg_.command.Profile();
  control::vio::SpeedLoopDef loop;
  loop.track_width = cfg_.drive.track_width;  // the controller's nominal geometry
  loop.gains.kp = cfg_.control.kp;
  loop.gains.ki = cfg_.control.ki;
  loop.gains.kd = cfg_.control.kd;
  loop.gains.out_min = -cfg_.drive.motor.voltage_max;
  loop.gains.out_max = cfg_.drive.motor.voltage_max;
  for (auto& u : units_) {
    u->drive->def().floor_terrain = cfg_.drive.floor_terrain;
    u->drive->def().terrain = cfg_.drive.terrain;
    u->odometry.SetDef(cfg_.encoders);
    u->imu.SetDef(cfg_.imu);
    u->camera.SetDef(cfg_.camera);
    // Noise edits reach the factors built from now on; the window keeps its size.
    for (auto* est : {&u->fused, &u->vi}) {
      const control::vio::SlidingWindowDef d = EstimatorDef(est == &u->fused);
      const int window = est->def().window_size;
      est->def() = d;
      est->def().window_size = window;
    }
    u->loop.SetDef(loop);  // gains only: the PID state (last output, errors) is kept
  }
}

void VelocityExperiment::RegisterParams() {
  ControlSettings& c = cfg_.control;
  params_.AddDouble("control.kp", "Gains/speed PID", "kp", &c.kp, 0.0, 20.0, "V·s/m");
  params_.AddDouble("control.ki", "Gains/speed PID", "ki (per sample)", &c.ki, 0.0, 10.0, "V·s/m");
  params_.AddDouble("control.kd", "Gains/speed PID", "kd (per sample)", &c.kd, 0.0, 10.0, "V·s/m");
  for (auto& u : units_)
    params_.AddChoice("robots." + u->spec.name + ".feedback", "Localisation/speed feedback",
                      u->spec.name, &u->spec.feedback, FeedbackNames());
  if (cfg_.command.type == 0) {
    params_.AddDouble("command.v", "Command", "v", &cfg_.command.v, -1.0, 1.0, "m/s");
    params_.AddDouble("command.omega", "Command", "ω", &cfg_.command.omega, -2.0, 2.0, "rad/s");
  }

  EncoderDef& e = cfg_.encoders;
  params_.AddDouble("sensors.encoders.angle_noise", "Noise/encoders", "angle jitter",
                    &e.angle_noise, 0.0, 0.01, "rad");
  params_.AddDouble("sensors.encoders.radius_error", "Noise/encoders", "radius error",
                    &e.radius_error, -0.1, 0.1);
  params_.AddDouble("sensors.encoders.track_error", "Noise/encoders", "track error", &e.track_error,
                    -0.1, 0.1);
  ImuDef& i = cfg_.imu;
  params_.AddDouble("sensors.imu.gyro_noise_density", "Noise/IMU", "gyro noise",
                    &i.gyro_noise_density, 1e-5, 1e-1, "rad/s/√Hz", true);
  params_.AddDouble("sensors.imu.accel_noise_density", "Noise/IMU", "accel noise",
                    &i.accel_noise_density, 1e-4, 1.0, "m/s²/√Hz", true);
  params_.AddDouble("sensors.imu.gyro_bias", "Noise/IMU", "gyro bias", &i.gyro_bias, -0.1, 0.1,
                    "rad/s");
  params_.AddDouble("sensors.imu.gyro_bias_rw", "Noise/IMU", "gyro bias walk", &i.gyro_bias_rw,
                    1e-6, 1e-2, "rad/s²/√Hz", true);
  params_.AddDouble("sensors.imu.accel_bias_rw", "Noise/IMU", "accel bias walk", &i.accel_bias_rw,
                    1e-5, 1e-1, "m/s³/√Hz", true);
  CameraDef& k = cfg_.camera;
  params_.AddDouble("sensors.camera.bearing_noise", "Noise/camera", "bearing σ", &k.bearing_noise,
                    1e-4, 0.05, "rad", true);
  params_.AddDouble("sensors.camera.fov_deg", "Noise/camera", "field of view", &fov_deg_, 20.0,
                    180.0, "°");
  params_.AddDouble("sensors.camera.range", "Noise/camera", "range", &k.range, 1.0, 20.0, "m");
  params_.AddInt("sensors.camera.max_features", "Noise/camera", "features per frame",
                 &k.max_features, 4, 100);

  params_.AddDouble("world.floor_friction", "Floor", "floor μ", &cfg_.world.floor_friction, 0.0,
                    1.5);
  params_.AddDouble("terrain.floor.rolling_resistance", "Floor", "floor rolling resistance",
                    &cfg_.drive.floor_terrain.rolling_resistance, 0.0, 0.2);
  params_.AddDouble("terrain.floor.shear_slip", "Floor", "floor shear slip κ0",
                    &cfg_.drive.floor_terrain.shear_slip, 0.005, 0.5, "", true);
  for (PatchDef& p : cfg_.patches) {
    // Patch friction lives in the world's patch list: it takes effect on reset.
    params_
        .AddDouble("patches." + p.name + ".friction", "Floor/" + p.name, "μ", &p.friction, 0.0, 1.5)
        .requires_reset = true;
    TerrainDef& t = cfg_.drive.terrain[p.name];
    params_.AddDouble("terrain." + p.name + ".rolling_resistance", "Floor/" + p.name,
                      "rolling resistance", &t.rolling_resistance, 0.0, 0.2);
    params_.AddDouble("terrain." + p.name + ".shear_slip", "Floor/" + p.name, "shear slip κ0",
                      &t.shear_slip, 0.005, 0.5, "", true);
  }

  control::vio::SlidingWindowDef& w = cfg_.estimator.window;
  params_.AddDouble("estimator.odometry.speed_noise_density", "Estimation/odometry model",
                    "speed noise", &w.odometry.speed_noise_density, 1e-4, 0.1, "m/s/√Hz", true);
  params_.AddDouble("estimator.odometry.yaw_rate_noise_density", "Estimation/odometry model",
                    "yaw-rate noise", &w.odometry.yaw_rate_noise_density, 1e-4, 0.5, "rad/s/√Hz",
                    true);
  params_.AddDouble("estimator.odometry.speed_bias_rw", "Estimation/odometry model",
                    "speed bias walk", &w.odometry.speed_bias_rw, 1e-4, 1.0, "m/s²/√Hz", true);
  params_.AddDouble("estimator.odometry.yaw_rate_bias_rw", "Estimation/odometry model",
                    "yaw-rate bias walk", &w.odometry.yaw_rate_bias_rw, 1e-4, 1.0, "rad/s²/√Hz",
                    true);
  params_.AddDouble("estimator.nonholonomic_sigma", "Estimation/window", "side-slip σ",
                    &w.nonholonomic_sigma, 1e-3, 1.0, "m/s", true);
  params_.AddDouble("estimator.min_parallax_deg", "Estimation/window", "min parallax",
                    &parallax_deg_, 0.5, 20.0, "°");
  params_.AddInt("estimator.window_size", "Estimation/window", "keyframes", &w.window_size, 2, 20)
      .requires_reset = true;
  params_
      .AddInt("estimator.keyframe_every", "Estimation/window", "frames per keyframe",
              &cfg_.estimator.keyframe_every, 1, 20)
      .requires_reset = true;
}

void VelocityExperiment::OnParamsChanged() {
  ApplySettings();
}

void VelocityExperiment::DeclareColumns() {
  recorder_.AddColumn("t");
  static const char* kCols[] = {
      "x",       "y",         "theta",   "v_true",    "w_true",   "v_cmd",   "w_cmd",
      "v_odo",   "w_odo",     "v_fused", "w_fused",   "v_vi",     "w_vi",    "v_feedback",
      "err_odo", "err_fused", "err_vi",  "slip_l",    "slip_r",   "mu_l",    "mu_r",
      "u_l",     "u_r",       "i_l",     "i_r",       "bv",       "bw",      "bg",
      "bg_true", "ba_x",      "ba_y",    "landmarks", "feedback", "slipping"};
  for (const auto& u : units_)
    for (const char* c : kCols) {
      const std::string name = u->spec.name + "." + c;
      columns_[name] = recorder_.AddColumn(name);
    }
}

void VelocityExperiment::CappedEvent(RobotUnit& u, const std::string& kind,
                                     const std::string& message) {
  // Slip and saturation can repeat every step on a slippery floor: keep the log readable.
  constexpr long kMaxEvents = 25;
  if (kind != "filter_fault" && u.events >= kMaxEvents) return;
  ++u.events;
  AddEvent(kind, u.spec.name, message);
}

void VelocityExperiment::UpdateEstimators(RobotUnit& u, double t) {
  // The estimate the speed loop would use without this update (for the Δv_s compensation).
  const control::vio::BodyTwist before = u.fused_speed.Peek(u.odo.speed, u.odo.yaw_rate);
  const auto t0 = std::chrono::steady_clock::now();
  const control::vio::UpdateReport r = u.fused.AddKeyframe(t, u.last_obs);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  u.update_ms_sum += ms;
  u.update_ms_max = std::max(u.update_ms_max, ms);
  ++u.updates;
  if (!r.ok) {
    ++u.faults;
    char buf[256];
    std::snprintf(buf, sizeof buf, "fused estimator fault at t=%.3f s: %s (window restarted)", t,
                  r.message.c_str());
    CappedEvent(u, "filter_fault", buf);
  }
  const control::vio::KeyframeState& k = u.fused.latest();
  u.fused_speed.OnUpdate(k.body_velocity().x(), k.bv(), k.bw());
  const control::vio::BodyTwist after = u.fused_speed.Peek(u.odo.speed, u.odo.yaw_rate);
  u.jump_v += after.v - before.v;
  u.jump_w += after.omega - before.omega;

  if (cfg_.estimator.vi_baseline) {
    const control::vio::UpdateReport rv = u.vi.AddKeyframe(t, u.last_obs);
    if (!rv.ok) {
      ++u.faults;
      char buf[256];
      std::snprintf(buf, sizeof buf, "VI-only estimator fault at t=%.3f s: %s (window restarted)",
                    t, rv.message.c_str());
      CappedEvent(u, "filter_fault", buf);
    }
  }
}

void VelocityExperiment::Estimate(RobotUnit& u) {
  u.est_fused = u.fused_speed.Estimate(u.odo.speed, u.odo.yaw_rate);
  if (cfg_.estimator.vi_baseline && u.vi.initialized()) {
    const control::vio::KeyframeState s = u.vi.Propagated();
    u.est_vi = {s.body_velocity().x(), u.last_gyro - s.bg()};
  }
}

void VelocityExperiment::Score(RobotUnit& u) {
  const double t = time();
  if (t < cfg_.settle_time - 1e-9) return;
  const double v = u.robot->forward_speed(), w = u.robot->yaw_rate();
  const double period = ctrl_every_ * dt();
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
  for (auto& up : units_) {
    RobotUnit& u = *up;
    if (k == 0) {
      u.last_obs = u.camera.Observe(u.robot->pose(), landmarks_, world_);
      // The robot starts at rest at a known pose: the window starts there.
      u.fused.Initialize(StartState(u.robot->pose()), u.last_obs);
      u.vi.Initialize(StartState(u.robot->pose()), u.last_obs);
      continue;
    }
    if (k % imu_every_ == 0) {
      const ImuReading r = u.imu.Sample(*u.robot, imu_every_ * dt());
      u.last_gyro = r.gyro;
      u.fused.AddImu(r.dt, r.gyro, r.accel);
      u.vi.AddImu(r.dt, r.gyro, r.accel);
    }
    if (k % enc_every_ == 0) {
      u.odo = u.odometry.Sample(*u.drive, enc_every_ * dt());
      u.fused.AddOdometry(u.odo.dt, u.odo.speed, u.odo.yaw_rate);
    }
    if (k % cam_every_ == 0) {
      u.last_obs = u.camera.Observe(CameraPose(*u.robot, dt()), landmarks_, world_);
      if (++u.camera_frames % keyframe_every_ == 0) UpdateEstimators(u, t);
    }
    if (k % ctrl_every_ == 0) {
      Estimate(u);
      Score(u);
    }
    // Slip events on the transition into slipping (capped).
    const bool slipping = u.drive->slipping() || u.drive->skidding();
    if (slipping && !u.was_slipping) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s at t=%.2f s on '%s' (μ=%.2f)",
                    u.drive->skidding() ? "side skid" : "wheel slip", t,
                    world_.PatchNameAt(u.robot->pose().p()).c_str(),
                    world_.FrictionAt(u.robot->pose().p()));
      CappedEvent(u, "slip", buf);
    }
    u.was_slipping = slipping;
    if (k % 10 == 0) {
      u.trail.push_back(u.robot->pose().p());
      if (u.trail.size() > 2000) u.trail.pop_front();
    }
  }
}

void VelocityExperiment::Control(double t) {
  const long k = steps();
  if (k % ctrl_every_ != 0) return;
  for (auto& up : units_) {
    RobotUnit& u = *up;
    command_.At(t, u.v_cmd, u.w_cmd);
    const bool fused = u.spec.feedback == static_cast<int>(Feedback::kFused);
    const control::vio::BodyTwist est =
        fused ? u.est_fused : control::vio::BodyTwist{u.odo.speed, u.odo.yaw_rate};
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

void VelocityExperiment::Record(Recorder& rec) {
  rec.Set(0, time());
  for (const auto& up : units_) {
    const RobotUnit& u = *up;
    const std::string& p = u.spec.name;
    auto set = [&](const char* c, double v) { rec.Set(columns_.at(p + "." + c), v); };
    const Pose2 pose = u.robot->pose();
    const double v = u.robot->forward_speed(), w = u.robot->yaw_rate();
    const control::vio::KeyframeState& k = u.fused.latest();
    set("x", pose.x);
    set("y", pose.y);
    set("theta", pose.theta);
    set("v_true", v);
    set("w_true", w);
    set("v_cmd", u.v_cmd);
    set("w_cmd", u.w_cmd);
    set("v_odo", u.odo.speed);
    set("w_odo", u.odo.yaw_rate);
    set("v_fused", u.est_fused.v);
    set("w_fused", u.est_fused.omega);
    set("v_vi", cfg_.estimator.vi_baseline ? u.est_vi.v : NAN);
    set("w_vi", cfg_.estimator.vi_baseline ? u.est_vi.omega : NAN);
    set("v_feedback", u.est_feedback.v);
    set("err_odo", u.odo.speed - v);
    set("err_fused", u.est_fused.v - v);
    set("err_vi", cfg_.estimator.vi_baseline ? u.est_vi.v - v : NAN);
    set("slip_l", u.drive->slip_ratio(DiffDrive::kLeft));
    set("slip_r", u.drive->slip_ratio(DiffDrive::kRight));
    set("mu_l", u.drive->friction(DiffDrive::kLeft));
    set("mu_r", u.drive->friction(DiffDrive::kRight));
    set("u_l", u.drive->voltage(DiffDrive::kLeft));
    set("u_r", u.drive->voltage(DiffDrive::kRight));
    set("i_l", u.drive->current(DiffDrive::kLeft));
    set("i_r", u.drive->current(DiffDrive::kRight));
    set("bv", k.bv());
    set("bw", k.bw());
    set("bg", k.bg());
    set("bg_true", u.imu.gyro_bias());
    set("ba_x", k.ba().x());
    set("ba_y", k.ba().y());
    int n = 0;
    for (const auto& l : u.fused.Landmarks()) n += l.initialized ? 1 : 0;
    set("landmarks", n);
    set("feedback", u.spec.feedback);
    set("slipping", (u.drive->slipping() || u.drive->skidding()) ? 1.0 : 0.0);
  }
}

FORMSIM_REGISTER_EXPERIMENT("velocity_control", VelocityExperiment);

}  // namespace formsim::sim::vio
