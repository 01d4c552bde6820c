#include "sim/velocity/velocity_config.hpp"

#include <cmath>
#include <set>

#include "sim/core/yaml_reader.hpp"

namespace formsim::sim::vio {

namespace {

double Positive(YamlReader& m, const std::string& key, double def) {
  const double v = m.Double(key, def);
  if (!(v > 0.0)) m.Fail(key, "must be positive");
  return v;
}

double NonNegative(YamlReader& m, const std::string& key, double def) {
  const double v = m.Double(key, def);
  if (!(v >= 0.0)) m.Fail(key, "must be >= 0");
  return v;
}

TerrainDef ReadTerrain(YamlReader& m, TerrainDef t) {
  t.rolling_resistance = NonNegative(m, "rolling_resistance", t.rolling_resistance);
  t.shear_slip = Positive(m, "shear_slip", t.shear_slip);
  m.Finish();
  return t;
}

void ReadDrive(YamlReader& m, DiffDriveDef& d) {
  d.wheel_radius = Positive(m, "wheel_radius", d.wheel_radius);
  d.track_width = Positive(m, "track_width", d.track_width);
  d.wheel_inertia = Positive(m, "wheel_inertia", d.wheel_inertia);
  d.caster_load = m.Double("caster_load", d.caster_load);
  if (!(d.caster_load >= 0.0 && d.caster_load < 1.0)) m.Fail("caster_load", "must be in [0, 1)");
  d.caster_x = m.Double("caster_x", d.caster_x);
  d.slip_speed_floor = Positive(m, "slip_speed_floor", d.slip_speed_floor);
  d.substeps = m.Int("substeps", d.substeps);
  if (d.substeps < 1 || d.substeps > 1000) m.Fail("substeps", "must be in [1, 1000]");
  YamlReader mo = m.Map("motor");
  DcMotorDef& x = d.motor;
  x.resistance = Positive(mo, "resistance", x.resistance);
  x.torque_constant = Positive(mo, "torque_constant", x.torque_constant);
  x.gear_ratio = Positive(mo, "gear_ratio", x.gear_ratio);
  x.voltage_max = Positive(mo, "voltage_max", x.voltage_max);
  x.current_max = Positive(mo, "current_max", x.current_max);
  x.viscous_friction = NonNegative(mo, "viscous_friction", x.viscous_friction);
  mo.Finish();
  m.Finish();
}

void ReadSensors(YamlReader& m, VelocityConfig& c) {
  YamlReader e = m.Map("encoders");
  c.encoders.rate = Positive(e, "rate", c.encoders.rate);
  c.encoders.ticks_per_rev = e.Int("ticks_per_rev", c.encoders.ticks_per_rev);
  if (c.encoders.ticks_per_rev < 1) e.Fail("ticks_per_rev", "must be >= 1");
  c.encoders.angle_noise = NonNegative(e, "angle_noise", c.encoders.angle_noise);
  c.encoders.radius_error = e.Double("radius_error", c.encoders.radius_error);
  c.encoders.track_error = e.Double("track_error", c.encoders.track_error);
  if (std::abs(c.encoders.radius_error) >= 0.5) e.Fail("radius_error", "must be in (-0.5, 0.5)");
  if (std::abs(c.encoders.track_error) >= 0.5) e.Fail("track_error", "must be in (-0.5, 0.5)");
  e.Finish();

  YamlReader i = m.Map("imu");
  ImuDef& d = c.imu;
  d.rate = Positive(i, "rate", d.rate);
  d.gyro_noise_density = NonNegative(i, "gyro_noise_density", d.gyro_noise_density);
  d.accel_noise_density = NonNegative(i, "accel_noise_density", d.accel_noise_density);
  d.gyro_bias = i.Double("gyro_bias", d.gyro_bias);
  const auto ba = i.Doubles("accel_bias", {d.accel_bias_x, d.accel_bias_y}, 2);
  d.accel_bias_x = ba[0];
  d.accel_bias_y = ba[1];
  d.gyro_bias_rw = NonNegative(i, "gyro_bias_rw", d.gyro_bias_rw);
  d.accel_bias_rw = NonNegative(i, "accel_bias_rw", d.accel_bias_rw);
  i.Finish();

  YamlReader k = m.Map("camera");
  CameraDef& cam = c.camera;
  cam.rate = Positive(k, "rate", cam.rate);
  cam.fov = k.Double("fov_deg", cam.fov * 180.0 / M_PI) * M_PI / 180.0;
  if (!(cam.fov > 0.0 && cam.fov < 2.0 * M_PI)) k.Fail("fov_deg", "must be in (0, 360)");
  cam.range = Positive(k, "range", cam.range);
  cam.bearing_noise = Positive(k, "bearing_noise", cam.bearing_noise);
  cam.offset = k.Double("offset", cam.offset);
  cam.max_features = k.Int("max_features", cam.max_features);
  if (cam.max_features < 1) k.Fail("max_features", "must be >= 1");
  k.Finish();
  m.Finish();
}

void ReadEstimator(YamlReader& m, EstimatorSettings& e) {
  control::vio::SlidingWindowDef& w = e.window;
  w.window_size = m.Int("window_size", w.window_size);
  if (w.window_size < 2 || w.window_size > 50) m.Fail("window_size", "must be in [2, 50]");
  e.keyframe_every = m.Int("keyframe_every", e.keyframe_every);
  if (e.keyframe_every < 1) m.Fail("keyframe_every", "must be >= 1");
  w.max_iterations = m.Int("max_iterations", w.max_iterations);
  if (w.max_iterations < 1) m.Fail("max_iterations", "must be >= 1");
  w.use_nonholonomic = m.Bool("nonholonomic", w.use_nonholonomic);
  w.nonholonomic_sigma = Positive(m, "nonholonomic_sigma", w.nonholonomic_sigma);
  w.min_parallax = m.Double("min_parallax_deg", w.min_parallax * 180.0 / M_PI) * M_PI / 180.0;
  if (!(w.min_parallax > 0.0)) m.Fail("min_parallax_deg", "must be positive");
  e.vi_baseline = m.Bool("vi_baseline", e.vi_baseline);
  YamlReader o = m.Map("odometry");
  control::vio::OdometryNoise& n = w.odometry;
  n.speed_noise_density = Positive(o, "speed_noise_density", n.speed_noise_density);
  n.yaw_rate_noise_density = Positive(o, "yaw_rate_noise_density", n.yaw_rate_noise_density);
  n.speed_bias_rw = Positive(o, "speed_bias_rw", n.speed_bias_rw);
  n.yaw_rate_bias_rw = Positive(o, "yaw_rate_bias_rw", n.yaw_rate_bias_rw);
  o.Finish();
  m.Finish();
}

void ReadCommand(YamlReader& m, CommandSettings& c) {
  c.type = m.Choice("type", {"constant", "steps"}, c.type);
  c.v = m.Double("v", c.v);
  c.omega = m.Double("omega", c.omega);
  c.accel_limit = Positive(m, "accel_limit", c.accel_limit);
  c.angular_accel_limit = Positive(m, "angular_accel_limit", c.angular_accel_limit);
  c.start_delay = NonNegative(m, "start_delay", c.start_delay);
  std::vector<YamlReader> steps = m.MapList("steps");
  if (c.type == 1 && steps.empty()) m.Fail("steps", "type steps needs a list of {t, v, omega}");
  if (c.type == 0 && !steps.empty()) m.Fail("steps", "only used with type: steps");
  double last_t = -1.0;
  for (YamlReader& s : steps) {
    control::vio::CommandStep st;
    st.t = s.RequiredDouble("t");
    if (st.t < 0.0 || st.t <= last_t) s.Fail("t", "step times must be >= 0 and increasing");
    last_t = st.t;
    st.v = s.Double("v", 0.0);
    st.omega = s.Double("omega", 0.0);
    s.Finish();
    c.steps.push_back(st);
  }
  m.Finish();
}

}  // namespace

control::vio::CommandProfile CommandSettings::Profile() const {
  // Zero until start_delay, then the steps shifted by it (or the constant command).
  std::vector<control::vio::CommandStep> s{{0.0, 0.0, 0.0}};
  if (type == 1) {
    for (control::vio::CommandStep st : steps) {
      st.t += start_delay;
      s.push_back(st);
    }
  } else {
    s.push_back({start_delay, v, omega});
  }
  return control::vio::CommandProfile(s, accel_limit, angular_accel_limit);
}

VelocityConfig ReadVelocityConfig(YamlReader& root) {
  VelocityConfig c;
  YamlReader w = root.Map("world");
  c.world = ReadWorldDef(w);
  c.obstacles = ReadObstacles(root);
  c.patches = ReadPatches(root);

  // Terrain beyond friction, by patch name ("floor" where no patch lies). Patches without an
  // entry behave like the floor; the floor is read first so that they inherit its values.
  YamlReader t = root.Map("terrain");
  if (t.Has("floor")) {
    YamlReader tm = t.Map("floor");
    c.drive.floor_terrain = ReadTerrain(tm, c.drive.floor_terrain);
  }
  std::set<std::string> names;
  for (const PatchDef& p : c.patches) names.insert(p.name);
  for (const std::string& name : names)
    if (t.Has(name) && name != "floor") {
      YamlReader tm = t.Map(name);
      c.drive.terrain[name] = ReadTerrain(tm, c.drive.floor_terrain);
    }
  t.Finish();

  YamlReader l = root.Map("landmarks");
  c.landmarks.count = l.Int("count", c.landmarks.count);
  if (c.landmarks.count < 0) l.Fail("count", "must be >= 0");
  const auto area = l.Doubles(
      "area", {c.landmarks.area[0], c.landmarks.area[1], c.landmarks.area[2], c.landmarks.area[3]},
      4);
  if (!(area[2] > area[0] && area[3] > area[1])) l.Fail("area", "needs x0 < x1 and y0 < y1");
  for (int i = 0; i < 4; ++i) c.landmarks.area[i] = area[i];
  c.landmarks.points = l.Points("points", 0);
  l.Finish();

  c.body = DefaultRobotDef();
  c.body.half_length = 0.22;
  c.body.half_width = 0.17;
  c.body.mass = 10.0;
  c.body.collide_with_robots = false;
  YamlReader b = root.Map("body");
  ReadRobotBody(b, c.body);
  YamlReader d = root.Map("drive");
  ReadDrive(d, c.drive);
  YamlReader s = root.Map("sensors");
  ReadSensors(s, c);
  YamlReader e = root.Map("estimator");
  ReadEstimator(e, c.estimator);

  YamlReader k = root.Map("control");
  c.control.rate = Positive(k, "rate", c.control.rate);
  c.control.kp = NonNegative(k, "kp", c.control.kp);
  c.control.ki = NonNegative(k, "ki", c.control.ki);
  c.control.kd = NonNegative(k, "kd", c.control.kd);
  k.Finish();

  YamlReader cmd = root.Map("command");
  ReadCommand(cmd, c.command);
  YamlReader met = root.Map("metrics");
  c.settle_time = NonNegative(met, "settle_time", c.settle_time);
  met.Finish();

  std::vector<YamlReader> robots = root.MapList("robots");
  std::set<std::string> robot_names;
  int index = 0;
  for (YamlReader& r : robots) {
    RobotSpec spec;
    spec.name = r.String("name", "R" + std::to_string(++index));
    if (!robot_names.insert(spec.name).second) r.Fail("name", "robot names must be unique");
    const auto pose = r.Doubles("pose", {0.0, 0.0, 0.0}, 3);
    spec.pose = {pose[0], pose[1], pose[2]};
    spec.feedback = r.Choice("feedback", FeedbackNames(), spec.feedback);
    r.Finish();
    c.robots.push_back(spec);
  }
  if (c.robots.empty()) c.robots.push_back(RobotSpec{});
  return c;
}

}  // namespace formsim::sim::vio
