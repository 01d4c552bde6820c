#include "sim/agv/agv_config.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"
#include "sim/core/multirate.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::sim::agv {
namespace {

using control::kPi;

// Hard validity of the numbers that are not tunables (Tune::Check gives the message).
const Tune kLength = Tune().In(1e-3, 1e3);      // lengths and radii, m
const Tune kCoordinate = Tune().In(-1e3, 1e3);  // positions in the world, m
const Tune kSigma = Tune().In(0.0, 100.0);      // noise and covariance settings
// (0, max]
Tune Positive(double max) {
  return Tune().Above(0).AtMost(max);
}

// A number that is not a tunable, refused outside `valid`.

// A pose [x, y, θ]: x and y inside the world's bounds, θ any finite angle (wrapped).
Pose2 ReadPose(YamlReader& r, const std::string& key) {
  const std::vector<double> v = r.Doubles(key, {}, 3);
  for (int i = 0; i < 2; ++i) {
    const std::string err = kCoordinate.Check(v[i]);
    if (!err.empty()) r.Fail(key, std::string(i == 0 ? "x " : "y ") + err);
  }
  return {v[0], v[1], control::WrapToPi(v[2])};
}

control::PidGains ReadPid(YamlReader& m, control::PidGains g, const std::string& group) {
  g.kp = m.Real("kp", g.kp, Tune("kp").In(0, 1e4).Slider(0.0, 10.0).Group(group));
  g.ki = m.Real("ki", g.ki, Tune("ki").In(0, 1e4).Slider(0.0, 5.0).Group(group));
  g.kd = m.Real("kd", g.kd, Tune("kd").In(0, 1e4).Slider(0.0, 2.0).Group(group));
  const double limit = m.Double("limit", g.out_max, Positive(1e3));
  g.out_min = -limit;
  g.out_max = limit;
  g.integral_limit = m.Double("integral_limit", g.integral_limit, Tune().In(0, 1e3));
  m.Finish();
  return g;
}

ca::Path ReadPath(YamlReader& p) {
  const int type = p.Choice("type", {"rounded_rectangle", "polyline", "segments"}, 0);
  try {
    if (type == 0) {
      const auto c = p.Doubles("center", {0.0, 0.0}, kCoordinate);
      const auto size = p.Doubles("size", {6.0, 4.0}, kLength);
      const double r = p.Double("corner_radius", 0.5, kLength);
      const double r_max = 0.5 * std::min(size[0], size[1]);
      if (r > r_max)
        p.Fail("corner_radius", "must be in [0.001, min(size)/2 = " + FormatDouble(r_max) + "]");
      const int dir = p.Choice("direction", {"ccw", "cw"}, 0);
      p.Finish();
      return ca::Path::RoundedRectangle({c[0], c[1]}, size[0], size[1], r, dir == 0);
    }
    if (type == 1) {
      const std::vector<Vec2> pts = p.Points("points", 2);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const std::string err = kCoordinate.Check(std::max(std::abs(pts[i].x), std::abs(pts[i].y)));
        if (!err.empty()) p.Fail("points", "point " + std::to_string(i) + ": x and y " + err);
      }
      const double r = p.Double("corner_radius", 0.3, kLength);
      const bool closed = p.Bool("closed", false);
      p.Finish();
      try {
        return ca::Path::Polyline(pts, r, closed);
      } catch (const ca::PathError& e) {
        p.Fail("points", e.what());
      }
    }
    const Pose2 start = p.Has("start") ? ReadPose(p, "start") : Pose2{};
    const bool closed = p.Bool("closed", false);
    ca::Path path(start);
    std::vector<YamlReader> segs = p.MapList("segments");
    if (segs.empty()) p.Fail("segments", "needs at least one {line: L} or {arc: [R, angle_deg]}");
    for (YamlReader& s : segs) {
      try {
        if (s.Has("line")) {
          path.AddLine(s.Double("line", 0.0, kLength));
        } else if (s.Has("arc")) {
          const auto a = s.Doubles("arc", {}, 2);
          if (const std::string err = kLength.Check(a[0]); !err.empty())
            s.Fail("arc", "radius " + err);
          if (const std::string err = Tune().In(-360, 360).Check(a[1]); !err.empty())
            s.Fail("arc", "angle (deg) " + err);
          path.AddArc(a[0], a[1] * kPi / 180.0);
        } else {
          s.Fail("line", "a segment is {line: length} or {arc: [radius, angle_deg]}");
        }
      } catch (const ca::PathError& e) {
        s.Fail(s.Has("line") ? "line" : "arc", e.what());
      }
      s.Finish();
    }
    if (closed) {
      try {
        path.Close();
      } catch (const ca::PathError& e) {
        p.Fail("closed", e.what());
      }
    }
    p.Finish();
    return path;
  } catch (const ca::PathError& e) {
    p.Fail("type", e.what());
  }
}

MecanumDriveDef ReadWheels(YamlReader& w) {
  MecanumDriveDef def = DefaultMecanumDriveDef();
  def.geometry.wheel_radius = w.Double("radius", def.geometry.wheel_radius, kLength);
  def.geometry.half_wheelbase = w.Double("half_wheelbase", def.geometry.half_wheelbase, kLength);
  def.geometry.half_track = w.Double("half_track", def.geometry.half_track, kLength);
  // Each radius error is a tunable when the list is in the file: list items are addressed by
  // index, which only works when the list exists (an edit would otherwise create a map).
  const Tune error =
      Tune("radius error").Above(-0.5).Below(0.5).Slider(-0.05, 0.05).Group("Noise/wheels");
  std::vector<double> e;
  if (w.Has("radius_error")) {
    std::vector<std::string> labels;
    for (const char* n : ca::kWheelNames) labels.push_back(std::string("radius error ") + n);
    e = w.Reals("radius_error", {0, 0, 0, 0}, error, labels);
  } else {
    e = w.Doubles("radius_error", {0, 0, 0, 0}, error);
  }
  for (int i = 0; i < control::agv::kMecanumWheels; ++i) def.radius_error[i] = e[i];
  def.wheel_speed_max = w.Double("speed_max", def.wheel_speed_max, Positive(1e4));
  def.motor_time_constant =
      w.Double("motor_time_constant", def.motor_time_constant, Tune().In(0, 100));
  def.wheel_accel_max = w.Double("accel_max", def.wheel_accel_max, Positive(1e6));
  def.slip_damping = w.Double("slip_damping", def.slip_damping, Positive(1e9));
  w.Finish();
  return def;
}

BeaconDef ReadBeacon(YamlReader& b, double dt) {
  const std::string g = "Noise/beacon";
  BeaconDef def;
  def.period = b.Real("period", def.period,
                      Tune("period Ts", "s").In(0.005, 3600).Slider(0.02, 1.0).Group(g));
  int steps = 1;
  if (const std::string err = StepsPerPeriod(def.period, dt, false, &steps); !err.empty())
    b.Fail("period", err);
  def.sigma_xy = b.Real("sigma_xy", def.sigma_xy,
                        Tune("σ x,y", "m").In(0, 100).Slider(1e-4, 0.5, kLog).Group(g));
  def.sigma_theta = b.Real("sigma_theta", def.sigma_theta,
                           Tune("σ θ", "rad").In(0, 10).Slider(1e-4, 0.5, kLog).Group(g));
  def.outlier_probability = b.Real("outlier_probability", def.outlier_probability,
                                   Tune("outlier rate").In(0, 1).Slider(0.0, 0.5).Group(g));
  def.outlier_size = b.Real("outlier_size", def.outlier_size,
                            Tune("outlier size", "m").In(0, 1e3).Slider(0.0, 3.0).Group(g));
  def.outlier_heading =
      b.Real("outlier_heading", def.outlier_heading,
             Tune("outlier heading", "rad").In(0, 2 * kPi).Slider(0.0, 3.14).Group(g));
  def.dropout_probability = b.Real("dropout_probability", def.dropout_probability,
                                   Tune("dropout rate").In(0, 1).Slider(0.0, 0.9).Group(g));
  b.Finish();
  return def;
}

WheelEncoderDef ReadEncoders(YamlReader& e) {
  const std::string g = "Noise/encoders";
  WheelEncoderDef def;
  def.speed_noise = e.Real("speed_noise", def.speed_noise,
                           Tune("speed σ", "rad/s").In(0, 100).Slider(0.0, 1.0).Group(g));
  def.ticks_per_rev = e.Integer("ticks_per_rev", def.ticks_per_rev,
                                Tune("ticks/rev").In(0, 1e6).Slider(0, 20000).Group(g).OnReset());
  e.Finish();
  return def;
}

ca::PoseFilterDef ReadFilter(YamlReader& e) {
  ca::PoseFilterDef f;
  const std::string q = "Estimation/Q", r = "Estimation/R", gate = "Estimation/gate",
                    adaptive = "Estimation/adaptive R";
  f.q_xy =
      e.Real("q_xy", f.q_xy, Tune("q x,y", "m/√s").In(0, 100).Slider(1e-5, 1.0, kLog).Group(q));
  f.q_theta = e.Real("q_theta", f.q_theta,
                     Tune("q θ", "rad/√s").In(0, 100).Slider(1e-5, 1.0, kLog).Group(q));
  f.r_xy = e.Real("r_xy", f.r_xy, Tune("r x,y", "m").In(0, 100).Slider(1e-4, 1.0, kLog).Group(r));
  f.r_theta =
      e.Real("r_theta", f.r_theta, Tune("r θ", "rad").In(0, 100).Slider(1e-4, 1.0, kLog).Group(r));
  f.p0_xy = e.Double("p0_xy", f.p0_xy, Tune().In(0, 1e3));
  f.p0_theta = e.Double("p0_theta", f.p0_theta, Tune().In(0, 1e3));
  f.gate = e.Flag("gate", f.gate, Tune("innovation gate").Group(gate));
  f.gate_probability =
      e.Real("gate_probability", f.gate_probability,
             Tune("χ² probability").Above(0).Below(1).Slider(0.9, 0.99999).Group(gate));
  f.gate_reset_after =
      e.Integer("gate_reset_after", f.gate_reset_after,
                Tune("re-init after rejections").In(0, 1e6).Slider(0, 50).Group(gate));
  f.adaptive_r = e.Flag("adaptive_r", f.adaptive_r, Tune("adaptive R").Group(adaptive));
  f.adaptive_window = e.Integer("adaptive_window", f.adaptive_window,
                                Tune("window").In(2, 1e6).Slider(2, 300).Group(adaptive));
  f.adaptive_min_xy = e.Double("adaptive_min_xy", f.adaptive_min_xy, kSigma);
  f.adaptive_min_theta = e.Double("adaptive_min_theta", f.adaptive_min_theta, kSigma);
  e.Finish();
  return f;
}

}  // namespace

const std::vector<std::string>& LocalisationModeNames() {
  static const std::vector<std::string> names = {"odometry", "beacon", "fused"};
  return names;
}

AgvConfig ReadAgvConfig(YamlReader& root, double dt) {
  AgvConfig cfg;
  // Read in the order the GUI lists the tunables.
  {
    YamlReader l = root.Map("localisation");
    cfg.mode = static_cast<LocalisationMode>(
        l.Pick("mode", LocalisationModeNames(), 2, Tune("pose for control").Group("Localisation")));
    l.Finish();
  }
  {
    YamlReader e = root.Map("estimation");
    cfg.filter = ReadFilter(e);
  }
  {
    YamlReader b = root.Map("beacon");
    cfg.beacon = ReadBeacon(b, dt);
  }

  YamlReader robot = root.Map("robot");
  cfg.body.name = robot.String("name", "AGV");
  if (cfg.body.name.empty() || cfg.body.name.find_first_of(".,") != std::string::npos)
    robot.Fail("name", "must be non-empty without '.' or ',' (names address keys and events)");
  cfg.body.shape = RobotDef::Shape::kBox;
  cfg.body.half_length = 0.35;
  cfg.body.half_width = 0.28;
  cfg.body.mass = 30.0;
  const bool pose_given = robot.Has("pose");
  if (pose_given) cfg.body.pose = ReadPose(robot, "pose");
  {
    YamlReader b = robot.Map("body");
    ReadRobotBody(b, cfg.body);
  }
  {
    YamlReader e = robot.Map("encoders");
    cfg.encoders = ReadEncoders(e);
  }
  {
    YamlReader w = robot.Map("wheels");
    cfg.drive = ReadWheels(w);
  }
  robot.Finish();

  YamlReader c = root.Map("control");
  ca::PathTrackerDef& t = cfg.tracker;
  t.v_ref = c.Real("v_ref", t.v_ref,
                   Tune("v_ref", "m/s").Above(0).AtMost(100).Slider(0.05, 1.0).Group("Gains/path"));
  {
    YamlReader m = c.Map("along");
    t.along = ReadPid(m, t.along, "Gains/along-track es");
  }
  {
    YamlReader m = c.Map("cross");
    t.cross = ReadPid(m, t.cross, "Gains/cross-track ed");
  }
  {
    YamlReader m = c.Map("heading_pid");
    t.heading = ReadPid(m, t.heading, "Gains/heading eθ");
  }
  cfg.control_rate = c.Double("rate", cfg.control_rate, Tune().Above(0).AtMost(1e6));
  if (const std::string err = StepsPerPeriod(1.0 / cfg.control_rate, dt, true, &cfg.control_every);
      !err.empty())
    c.Fail("rate",
           "the control period 1/rate = " + FormatDouble(1.0 / cfg.control_rate) + " s " + err +
               (err.find("multiple") != std::string::npos ? " (e.g. rate 15 Hz with dt = 1/300 s)"
                                                          : ""));
  t.accel = c.Double("accel", t.accel, Positive(1e3));
  t.v_max = c.Double("v_max", t.v_max, Positive(100));
  t.omega_max = c.Double("omega_max", t.omega_max, Positive(1e3));
  t.heading_mode =
      static_cast<ca::PathTrackerDef::HeadingMode>(c.Choice("heading", {"tangent", "fixed"}, 0));
  t.fixed_heading = c.Double("fixed_heading", t.fixed_heading);
  t.laps = c.Int("laps", t.laps, Tune().In(0, 1e6));
  t.projection_window = c.Double("window", t.projection_window, kLength);
  c.Finish();

  {
    YamlReader p = root.Map("path");
    cfg.path = ReadPath(p);
  }
  {
    YamlReader w = root.Map("world");
    cfg.world = ReadWorldDef(w);
  }
  cfg.obstacles = ReadObstacles(root);
  cfg.patches = ReadPatches(root);
  {
    YamlReader m = root.Map("metrics");
    cfg.completion_tolerance =
        m.Double("completion_tolerance", cfg.completion_tolerance, Positive(1e3));
    cfg.jump_threshold = m.Double("jump_threshold", cfg.jump_threshold, Positive(1e3));
    m.Finish();
  }

  if (!pose_given) {
    // Start on the path, facing along it (or at the fixed heading).
    const ca::PathPoint s = cfg.path.At(0.0);
    const bool tangent = t.heading_mode == ca::PathTrackerDef::HeadingMode::kTangent;
    cfg.body.pose = {s.p.x, s.p.y, tangent ? s.heading : control::WrapToPi(t.fixed_heading)};
  }
  return cfg;
}

}  // namespace formsim::sim::agv
