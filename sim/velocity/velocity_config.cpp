#include "sim/velocity/velocity_config.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "control/common/angle.hpp"
#include "sim/core/multirate.hpp"

namespace formsim::sim::velocity {

namespace {

constexpr double kDeg = control::kPi / 180.0;
// Magnitude bounds that keep the run finite and Box2D's assertions quiet.
constexpr double kMinLength = 1e-3, kMaxLength = 1e3;  // sizes, radii, m
constexpr double kMaxCoordinate = 1e4;                 // positions, m
constexpr double kMaxHeading = 1e3;                    // rad
constexpr double kMaxSpeed = 10.0;                     // commanded |v|, m/s
constexpr double kMaxYawRate = 20.0;                   // commanded |ω|, rad/s
constexpr double kMaxGain = 1e3;                       // PID gains, V per m/s
constexpr double kMaxTime = 1e6;                       // s


// A sampling rate in Hz as world steps per sample (rounded; at least one step per sample). A
// rate not given is the nominal one, or one sample per world step when the step is longer.
int RateOrNominalSteps(YamlReader& m, const std::string& key, double* rate, double dt) {
  if (!m.Has(key)) *rate = std::min(*rate, 1.0 / dt);
  *rate = m.Double(key, *rate, Tune().Above(0).AtMost(1e6));
  return sim::RateSteps(m, key, *rate, dt);
}

Tune Length() {
  return Tune().In(kMinLength, kMaxLength);
}
Tune Coordinate() {
  return Tune().In(-kMaxCoordinate, kMaxCoordinate);
}

void CheckPoint(YamlReader& m, const std::string& key, Vec2 p) {
  if (!Coordinate().Check(p.x).empty() || !Coordinate().Check(p.y).empty())
    m.Fail(key, "coordinates must be " + Coordinate().ValidityText() + " m");
}

RobotDef ReadBody(YamlReader& b) {
  RobotDef def = DefaultRobotDef();
  def.half_length = 0.22;
  def.half_width = 0.17;
  def.mass = 10.0;
  def.collide_with_robots = false;
  ReadRobotBody(b, def);
  return def;
}

// ---- this kind's blocks ----

TerrainDef ReadTerrain(YamlReader& m, TerrainDef t, const std::string& group,
                       const std::string& prefix) {
  t.rolling_resistance =
      m.Real("rolling_resistance", t.rolling_resistance,
             Tune(prefix + "rolling resistance").In(0, 1).Slider(0.0, 0.2).Group(group));
  t.shear_slip =
      m.Real("shear_slip", t.shear_slip,
             Tune(prefix + "shear slip κ0").In(1e-4, 10).Slider(0.005, 0.5, kLog).Group(group));
  m.Finish();
  return t;
}

void ReadDrive(YamlReader& m, DiffDriveDef& d) {
  d.wheel_radius = m.Double("wheel_radius", d.wheel_radius, Length());
  d.track_width = m.Double("track_width", d.track_width, Length());
  d.wheel_inertia = m.Double("wheel_inertia", d.wheel_inertia, Tune().In(1e-6, 1e3));
  d.caster_load = m.Double("caster_load", d.caster_load, Tune().AtLeast(0).Below(1));
  d.caster_x = m.Double("caster_x", d.caster_x, Tune().In(-kMaxLength, kMaxLength));
  d.slip_speed_floor =
      m.Double("slip_speed_floor", d.slip_speed_floor, Tune().Above(0).AtMost(100));
  d.substeps = m.Int("substeps", d.substeps, Tune().In(1, 1000));
  YamlReader mo = m.Map("motor");
  DcMotorDef& x = d.motor;
  x.resistance = mo.Double("resistance", x.resistance, Tune().In(1e-4, 1e4));
  x.torque_constant = mo.Double("torque_constant", x.torque_constant, Tune().In(1e-5, 10));
  x.gear_ratio = mo.Double("gear_ratio", x.gear_ratio, Tune().In(1e-2, 1e4));
  x.voltage_max = mo.Double("voltage_max", x.voltage_max, Tune().In(1e-3, 1e4));
  x.current_max = mo.Double("current_max", x.current_max, Tune().In(1e-3, 1e4));
  x.viscous_friction = mo.Double("viscous_friction", x.viscous_friction, Tune().In(0, 1e3));
  mo.Finish();
  m.Finish();
}

void ReadSensors(YamlReader& m, VelocityConfig& c, double dt) {
  YamlReader e = m.Map("encoders");
  EncoderDef& enc = c.encoders;
  const std::string ge = "Noise/encoders";
  c.every.encoders = RateOrNominalSteps(e, "rate", &enc.rate, dt);
  // At most 2^20 counts per turn: tick counts stay far from overflowing over any run.
  enc.ticks_per_rev = e.Int("ticks_per_rev", enc.ticks_per_rev, Tune().In(1, 1 << 20));
  enc.angle_noise = e.Real("angle_noise", enc.angle_noise,
                           Tune("angle jitter", "rad").In(0, 1).Slider(0.0, 0.01).Group(ge));
  enc.radius_error =
      e.Real("radius_error", enc.radius_error,
             Tune("radius error").Above(-0.5).Below(0.5).Slider(-0.1, 0.1).Group(ge));
  enc.track_error = e.Real("track_error", enc.track_error,
                           Tune("track error").Above(-0.5).Below(0.5).Slider(-0.1, 0.1).Group(ge));
  e.Finish();

  YamlReader i = m.Map("imu");
  ImuDef& d = c.imu;
  const std::string gi = "Noise/IMU";
  c.every.imu = RateOrNominalSteps(i, "rate", &d.rate, dt);
  d.gyro_noise_density =
      i.Real("gyro_noise_density", d.gyro_noise_density,
             Tune("gyro noise", "rad/s/√Hz").In(0, 10).Slider(1e-5, 1e-1, kLog).Group(gi));
  d.accel_noise_density =
      i.Real("accel_noise_density", d.accel_noise_density,
             Tune("accel noise", "m/s²/√Hz").In(0, 100).Slider(1e-4, 1.0, kLog).Group(gi));
  d.gyro_bias = i.Real("gyro_bias", d.gyro_bias,
                       Tune("gyro bias", "rad/s").In(-10, 10).Slider(-0.1, 0.1).Group(gi));
  const auto ba = i.Doubles("accel_bias", {d.accel_bias_x, d.accel_bias_y}, 2);
  const Tune accel_bias = Tune().In(-100, 100);
  if (!accel_bias.Check(ba[0]).empty() || !accel_bias.Check(ba[1]).empty())
    i.Fail("accel_bias", "each component must be " + accel_bias.ValidityText() + " m/s²");
  d.accel_bias_x = ba[0];
  d.accel_bias_y = ba[1];
  d.gyro_bias_rw =
      i.Real("gyro_bias_rw", d.gyro_bias_rw,
             Tune("gyro bias walk", "rad/s²/√Hz").In(0, 1).Slider(1e-6, 1e-2, kLog).Group(gi));
  d.accel_bias_rw =
      i.Real("accel_bias_rw", d.accel_bias_rw,
             Tune("accel bias walk", "m/s³/√Hz").In(0, 10).Slider(1e-5, 1e-1, kLog).Group(gi));
  i.Finish();

  YamlReader k = m.Map("camera");
  CameraDef& cam = c.camera;
  const std::string gc = "Noise/camera";
  c.every.camera = RateOrNominalSteps(k, "rate", &cam.rate, dt);
  cam.bearing_noise =
      k.Real("bearing_noise", cam.bearing_noise,
             Tune("bearing σ", "rad").In(1e-6, 1).Slider(1e-4, 0.05, kLog).Group(gc));
  cam.fov = k.Real("fov_deg", cam.fov / kDeg,
                   Tune("field of view", "°").Above(0).Below(360).Slider(20.0, 180.0).Group(gc)) *
            kDeg;
  cam.range = k.Real("range", cam.range,
                     Tune("range", "m").In(kMinLength, kMaxLength).Slider(1.0, 20.0).Group(gc));
  cam.max_features = k.Integer("max_features", cam.max_features,
                               Tune("features per frame").In(1, 1000).Slider(4, 100).Group(gc));
  cam.offset = k.Double("offset", cam.offset, Tune().In(-kMaxLength, kMaxLength));
  k.Finish();
  m.Finish();
}

void ReadEstimator(YamlReader& m, EstimatorSettings& e) {
  cv::SlidingWindowDef& w = e.window;
  YamlReader o = m.Map("odometry");
  cv::OdometryNoise& n = w.odometry;
  const std::string go = "Estimation/odometry model", gw = "Estimation/window";
  n.speed_noise_density =
      o.Real("speed_noise_density", n.speed_noise_density,
             Tune("speed noise", "m/s/√Hz").In(1e-6, 10).Slider(1e-4, 0.1, kLog).Group(go));
  n.yaw_rate_noise_density =
      o.Real("yaw_rate_noise_density", n.yaw_rate_noise_density,
             Tune("yaw-rate noise", "rad/s/√Hz").In(1e-6, 10).Slider(1e-4, 0.5, kLog).Group(go));
  n.speed_bias_rw =
      o.Real("speed_bias_rw", n.speed_bias_rw,
             Tune("speed bias walk", "m/s²/√Hz").In(1e-6, 10).Slider(1e-4, 1.0, kLog).Group(go));
  n.yaw_rate_bias_rw = o.Real(
      "yaw_rate_bias_rw", n.yaw_rate_bias_rw,
      Tune("yaw-rate bias walk", "rad/s²/√Hz").In(1e-6, 10).Slider(1e-4, 1.0, kLog).Group(go));
  o.Finish();
  w.nonholonomic_sigma =
      m.Real("nonholonomic_sigma", w.nonholonomic_sigma,
             Tune("side-slip σ", "m/s").In(1e-6, 10).Slider(1e-3, 1.0, kLog).Group(gw));
  w.min_parallax =
      m.Real("min_parallax_deg", w.min_parallax / kDeg,
             Tune("min parallax", "°").Above(0).AtMost(90).Slider(0.5, 20.0).Group(gw)) *
      kDeg;
  w.window_size = m.Integer("window_size", w.window_size,
                            Tune("keyframes").In(2, 50).Slider(2, 20).Group(gw).OnReset());
  e.keyframe_every =
      m.Integer("keyframe_every", e.keyframe_every,
                Tune("frames per keyframe").In(1, 1000).Slider(1, 20).Group(gw).OnReset());
  w.landmarks = static_cast<cv::LandmarkParam>(
      m.Pick("landmarks", {"inverse_depth", "world_point", "inverse_depth_1d"},
             static_cast<int>(w.landmarks), Tune("landmark parameterisation").Group(gw).OnReset()));
  w.max_iterations = m.Int("max_iterations", w.max_iterations, Tune().In(1, 1000));
  // The no-side-slip constraint is ours (the paper has none): switchable to measure its effect.
  w.use_nonholonomic =
      m.Flag("nonholonomic", w.use_nonholonomic, Tune("no-side-slip constraint (ours)").Group(gw));
  e.vi_baseline = m.Bool("vi_baseline", e.vi_baseline);
  m.Finish();
}

void ReadCommand(YamlReader& m, CommandSettings& c) {
  c.type = m.Choice("type", {"constant", "steps"}, c.type);
  const Tune v_rule = Tune().In(-kMaxSpeed, kMaxSpeed),
             w_rule = Tune().In(-kMaxYawRate, kMaxYawRate);
  if (c.type == 0) {
    // A constant command (or a circle) is tuned live; steps are a script.
    c.v = m.Real("v", c.v,
                 Tune("v", "m/s").In(-kMaxSpeed, kMaxSpeed).Slider(-1.0, 1.0).Group("Command"));
    c.omega =
        m.Real("omega", c.omega,
               Tune("ω", "rad/s").In(-kMaxYawRate, kMaxYawRate).Slider(-2.0, 2.0).Group("Command"));
  } else {
    c.v = m.Double("v", c.v, v_rule);
    c.omega = m.Double("omega", c.omega, w_rule);
  }
  c.accel_limit = m.Double("accel_limit", c.accel_limit, Tune().Above(0).AtMost(1e12));
  c.angular_accel_limit =
      m.Double("angular_accel_limit", c.angular_accel_limit, Tune().Above(0).AtMost(1e12));
  c.start_delay = m.Double("start_delay", c.start_delay, Tune().In(0, kMaxTime));
  std::vector<YamlReader> steps = m.MapList("steps");
  if (c.type == 1 && steps.empty()) m.Fail("steps", "type steps needs a list of {t, v, omega}");
  if (c.type == 0 && !steps.empty()) m.Fail("steps", "only used with type: steps");
  double last_t = -1.0;
  for (YamlReader& s : steps) {
    cv::CommandStep st;
    st.t = s.RequiredDouble("t");
    if (st.t < 0.0 || st.t <= last_t) s.Fail("t", "step times must be >= 0 and increasing");
    if (st.t > kMaxTime)
      s.Fail("t", "must be <= " + std::to_string(static_cast<long>(kMaxTime)) + " s");
    last_t = st.t;
    st.v = s.Double("v", 0.0, v_rule);
    st.omega = s.Double("omega", 0.0, w_rule);
    s.Finish();
    c.steps.push_back(st);
  }
  m.Finish();
}

void ReadLandmarks(YamlReader& l, LandmarkDef& d) {
  d.count = l.Int("count", d.count, Tune().In(0, 100000));
  const auto area = l.Doubles("area", {d.area[0], d.area[1], d.area[2], d.area[3]}, 4);
  for (double a : area)
    if (!Coordinate().Check(a).empty())
      l.Fail("area", "coordinates must be " + Coordinate().ValidityText() + " m");
  if (!(area[2] > area[0] && area[3] > area[1])) l.Fail("area", "needs x0 < x1 and y0 < y1");
  for (int i = 0; i < 4; ++i) d.area[i] = area[i];
  d.points = l.Points("points", 0);
  for (const Vec2& p : d.points) CheckPoint(l, "points", p);
  l.Finish();
}

void ReadRobots(YamlReader& root, std::vector<RobotSpec>& out) {
  std::vector<YamlReader> robots = root.MapList("robots");
  std::set<std::string> names;
  int index = 0;
  for (YamlReader& r : robots) {
    RobotSpec spec;
    spec.name = r.String("name", "R" + std::to_string(++index));
    if (!names.insert(spec.name).second) r.Fail("name", "robot names must be unique");
    if (spec.name.empty() || spec.name.find_first_of(".,") != std::string::npos)
      r.Fail("name",
             "a robot name must be non-empty without '.' or ',' (names address keys and events)");
    const auto pose = r.Doubles("pose", {0.0, 0.0, 0.0}, 3);
    CheckPoint(r, "pose", {pose[0], pose[1]});
    if (!Tune().In(-kMaxHeading, kMaxHeading).Check(pose[2]).empty())
      r.Fail("pose",
             "the heading must be " + Tune().In(-kMaxHeading, kMaxHeading).ValidityText() + " rad");
    spec.pose = {pose[0], pose[1], pose[2]};
    spec.feedback = r.Pick("feedback", FeedbackNames(), spec.feedback,
                           Tune(spec.name).Group("Localisation/speed feedback"));
    r.Finish();
    out.push_back(spec);
  }
  if (out.empty()) out.push_back(RobotSpec{});
}

}  // namespace

const std::vector<std::string>& FeedbackNames() {
  static const std::vector<std::string> names{"odometry", "fused"};
  return names;
}

cv::CommandProfile CommandSettings::Profile() const {
  // Zero until start_delay, then the steps shifted by it (or the constant command).
  std::vector<cv::CommandStep> s{{0.0, 0.0, 0.0}};
  if (type == 1) {
    for (cv::CommandStep st : steps) {
      st.t += start_delay;
      s.push_back(st);
    }
  } else {
    s.push_back({start_delay, v, omega});
  }
  return cv::CommandProfile(s, accel_limit, angular_accel_limit);
}

VelocityConfig ReadVelocityConfig(YamlReader& root, double dt) {
  VelocityConfig c;
  // Read in the order the GUI lists the tunables: gains, feedback, command, noise, floor,
  // estimation; then the fixed parts.
  {
    YamlReader k = root.Map("control");
    const std::string g = "Gains/speed PID";
    c.every.control = RateOrNominalSteps(k, "rate", &c.control.rate, dt);
    c.control.kp =
        k.Real("kp", c.control.kp, Tune("kp", "V·s/m").In(0, kMaxGain).Slider(0.0, 20.0).Group(g));
    c.control.ki =
        k.Real("ki", c.control.ki,
               Tune("ki (per sample)", "V·s/m").In(0, kMaxGain).Slider(0.0, 10.0).Group(g));
    c.control.kd =
        k.Real("kd", c.control.kd,
               Tune("kd (per sample)", "V·s/m").In(0, kMaxGain).Slider(0.0, 10.0).Group(g));
    k.Finish();
  }
  ReadRobots(root, c.robots);
  {
    YamlReader cmd = root.Map("command");
    ReadCommand(cmd, c.command);
  }
  {
    YamlReader s = root.Map("sensors");
    ReadSensors(s, c, dt);
  }
  {
    YamlReader w = root.Map("world");
    c.world = ReadWorldDef(w, true);
  }
  {
    // Terrain beyond friction, by patch name ("floor" where no patch lies). Every patch gets an
    // entry (and its tunables); one not given behaves like the floor, whose values it takes.
    YamlReader t = root.Map("terrain");
    YamlReader floor = t.Map("floor");
    c.drive.floor_terrain = ReadTerrain(floor, c.drive.floor_terrain, "Floor", "floor ");
    c.patches = ReadPatches(root);
    for (std::size_t i = 0; i < c.patches.size(); ++i) {
      PatchDef& p = c.patches[i];
      YamlReader tm = t.Map(p.name);
      c.drive.terrain[p.name] = ReadTerrain(tm, c.drive.floor_terrain, "Floor/" + p.name, "");
    }
    t.Finish();
  }
  {
    YamlReader e = root.Map("estimator");
    ReadEstimator(e, c.estimator);
  }
  c.obstacles = ReadObstacles(root);
  {
    YamlReader l = root.Map("landmarks");
    ReadLandmarks(l, c.landmarks);
  }
  {
    YamlReader b = root.Map("body");
    c.body = ReadBody(b);
  }
  {
    YamlReader d = root.Map("drive");
    ReadDrive(d, c.drive);
  }
  {
    YamlReader met = root.Map("metrics");
    c.settle_time = met.Double("settle_time", c.settle_time, Tune().In(0, kMaxTime));
    met.Finish();
  }
  return c;
}

}  // namespace formsim::sim::velocity
