#include "sim/agv/agv_config.hpp"

#include <cmath>

#include "control/common/angle.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {
namespace {

using control::kPi;

control::PidGains ReadPid(YamlReader& m, control::PidGains g) {
  g.kp = m.Double("kp", g.kp);
  g.ki = m.Double("ki", g.ki);
  g.kd = m.Double("kd", g.kd);
  if (g.kp < 0.0) m.Fail("kp", "gains must be >= 0");
  if (g.ki < 0.0) m.Fail("ki", "gains must be >= 0");
  if (g.kd < 0.0) m.Fail("kd", "gains must be >= 0");
  const double limit = m.Double("limit", g.out_max);
  if (!(limit > 0.0)) m.Fail("limit", "must be positive");
  g.out_min = -limit;
  g.out_max = limit;
  g.integral_limit = m.Double("integral_limit", g.integral_limit);
  if (!(g.integral_limit >= 0.0)) m.Fail("integral_limit", "must be >= 0");
  m.Finish();
  return g;
}

control::Path ReadPath(YamlReader& p) {
  const int type = p.Choice("type", {"rounded_rectangle", "polyline", "segments"}, 0);
  try {
    if (type == 0) {
      const auto c = p.Doubles("center", {0.0, 0.0}, 2);
      const auto size = p.Doubles("size", {6.0, 4.0}, 2);
      if (size[0] <= 0 || size[1] <= 0) p.Fail("size", "must be positive");
      const double r = p.Double("corner_radius", 0.5);
      if (!(r > 0.0) || r > 0.5 * std::min(size[0], size[1]))
        p.Fail("corner_radius", "must be in (0, min(size)/2]");
      const int dir = p.Choice("direction", {"ccw", "cw"}, 0);
      p.Finish();
      return control::Path::RoundedRectangle({c[0], c[1]}, size[0], size[1], r, dir == 0);
    }
    if (type == 1) {
      const std::vector<Vec2> pts = p.Points("points", 2);
      const double r = p.Double("corner_radius", 0.3);
      const bool closed = p.Bool("closed", false);
      p.Finish();
      try {
        return control::Path::Polyline(pts, r, closed);
      } catch (const control::PathError& e) {
        p.Fail("points", e.what());
      }
    }
    const auto start = p.Doubles("start", {0.0, 0.0, 0.0}, 3);
    const bool closed = p.Bool("closed", false);
    control::Path path({start[0], start[1], start[2]});
    std::vector<YamlReader> segs = p.MapList("segments");
    if (segs.empty()) p.Fail("segments", "needs at least one {line: L} or {arc: [R, angle_deg]}");
    for (YamlReader& s : segs) {
      try {
        if (s.Has("line")) {
          path.AddLine(s.Double("line", 0.0));
        } else if (s.Has("arc")) {
          const auto a = s.Doubles("arc", {}, 2);
          path.AddArc(a[0], a[1] * kPi / 180.0);
        } else {
          s.Fail("line", "a segment is {line: length} or {arc: [radius, angle_deg]}");
        }
      } catch (const control::PathError& e) {
        s.Fail(s.Has("line") ? "line" : "arc", e.what());
      }
      s.Finish();
    }
    if (closed) {
      try {
        path.Close();
      } catch (const control::PathError& e) {
        p.Fail("closed", e.what());
      }
    }
    p.Finish();
    return path;
  } catch (const control::PathError& e) {
    p.Fail("type", e.what());
  }
}

}  // namespace

AgvConfig ReadAgvConfig(YamlReader& root, double dt) {
  AgvConfig cfg;
  {
    YamlReader w = root.Map("world");
    cfg.world = ReadWorldDef(w);
  }
  cfg.obstacles = ReadObstacles(root);
  cfg.patches = ReadPatches(root);

  {
    YamlReader p = root.Map("path");
    cfg.path = ReadPath(p);
  }

  YamlReader robot = root.Map("robot");
  cfg.body.name = robot.String("name", "AGV");
  cfg.body.shape = RobotDef::Shape::kBox;
  cfg.body.half_length = 0.35;
  cfg.body.half_width = 0.28;
  cfg.body.mass = 30.0;
  cfg.pose_given = robot.Has("pose");
  if (cfg.pose_given) {
    const auto pose = robot.Doubles("pose", {0, 0, 0}, 3);
    cfg.body.pose = {pose[0], pose[1], control::WrapToPi(pose[2])};
  }
  {
    YamlReader b = robot.Map("body");
    ReadRobotBody(b, cfg.body);
  }
  {
    YamlReader w = robot.Map("wheels");
    cfg.radius_error_given = w.Has("radius_error");
    cfg.drive = ReadMecanumDrive(w);
  }
  {
    YamlReader e = robot.Map("encoders");
    cfg.encoders.ticks_per_rev = e.Int("ticks_per_rev", cfg.encoders.ticks_per_rev);
    if (cfg.encoders.ticks_per_rev < 0) e.Fail("ticks_per_rev", "must be >= 0 (0: ideal)");
    cfg.encoders.speed_noise = e.Double("speed_noise", cfg.encoders.speed_noise);
    if (cfg.encoders.speed_noise < 0) e.Fail("speed_noise", "must be >= 0");
    e.Finish();
  }
  robot.Finish();

  {
    YamlReader b = root.Map("beacon");
    cfg.beacon = ReadBeacon(b);
  }

  YamlReader c = root.Map("control");
  cfg.control_rate = c.Double("rate", cfg.control_rate);
  if (!(cfg.control_rate > 0.0)) c.Fail("rate", "must be positive");
  const double steps = 1.0 / (cfg.control_rate * dt);
  cfg.control_every = static_cast<int>(std::lround(steps));
  if (cfg.control_every < 1 || std::abs(steps - cfg.control_every) > 1e-3 * steps)
    c.Fail("rate", "the control period 1/rate must be a whole number of world steps dt = " +
                       std::to_string(dt) + " s (e.g. rate 15 Hz with dt = 1/300 s)");
  control::PathTrackerDef& t = cfg.tracker;
  t.v_ref = c.Double("v_ref", t.v_ref);
  if (!(t.v_ref > 0.0)) c.Fail("v_ref", "must be positive");
  t.accel = c.Double("accel", t.accel);
  if (!(t.accel > 0.0)) c.Fail("accel", "must be positive");
  t.v_max = c.Double("v_max", t.v_max);
  if (!(t.v_max > 0.0)) c.Fail("v_max", "must be positive");
  t.omega_max = c.Double("omega_max", t.omega_max);
  if (!(t.omega_max > 0.0)) c.Fail("omega_max", "must be positive");
  t.heading_mode = static_cast<control::PathTrackerDef::HeadingMode>(
      c.Choice("heading", {"tangent", "fixed"}, 0));
  t.fixed_heading = c.Double("fixed_heading", t.fixed_heading);
  t.laps = c.Int("laps", t.laps);
  if (t.laps < 0) c.Fail("laps", "must be >= 0 (0: keep going)");
  t.projection_window = c.Double("window", t.projection_window);
  if (!(t.projection_window > 0.0)) c.Fail("window", "must be positive");
  {
    YamlReader m = c.Map("along");
    t.along = ReadPid(m, t.along);
  }
  {
    YamlReader m = c.Map("cross");
    t.cross = ReadPid(m, t.cross);
  }
  {
    YamlReader m = c.Map("heading_pid");
    t.heading = ReadPid(m, t.heading);
  }
  c.Finish();

  {
    YamlReader l = root.Map("localisation");
    cfg.mode = static_cast<LocalisationMode>(l.Choice("mode", LocalisationModeNames(), 2));
    l.Finish();
  }

  YamlReader e = root.Map("estimation");
  control::PoseFilterDef& f = cfg.filter;
  auto non_negative = [&e](const char* key, double def) {
    const double v = e.Double(key, def);
    if (v < 0.0) e.Fail(key, "must be >= 0");
    return v;
  };
  f.q_xy = non_negative("q_xy", f.q_xy);
  f.q_theta = non_negative("q_theta", f.q_theta);
  f.r_xy = non_negative("r_xy", f.r_xy);
  f.r_theta = non_negative("r_theta", f.r_theta);
  f.p0_xy = non_negative("p0_xy", f.p0_xy);
  f.p0_theta = non_negative("p0_theta", f.p0_theta);
  f.gate = e.Bool("gate", f.gate);
  f.gate_probability = e.Double("gate_probability", f.gate_probability);
  if (!(f.gate_probability > 0.0 && f.gate_probability < 1.0))
    e.Fail("gate_probability", "must be in (0, 1), e.g. 0.999");
  f.gate_reset_after = e.Int("gate_reset_after", f.gate_reset_after);
  if (f.gate_reset_after < 0) e.Fail("gate_reset_after", "must be >= 0 (0: never)");
  f.adaptive_r = e.Bool("adaptive_r", f.adaptive_r);
  f.adaptive_window = e.Int("adaptive_window", f.adaptive_window);
  if (f.adaptive_window < 2) e.Fail("adaptive_window", "must be >= 2");
  f.adaptive_min_xy = non_negative("adaptive_min_xy", f.adaptive_min_xy);
  f.adaptive_min_theta = non_negative("adaptive_min_theta", f.adaptive_min_theta);
  e.Finish();

  {
    YamlReader m = root.Map("metrics");
    cfg.completion_tolerance = m.Double("completion_tolerance", cfg.completion_tolerance);
    if (!(cfg.completion_tolerance > 0.0)) m.Fail("completion_tolerance", "must be positive");
    cfg.jump_threshold = m.Double("jump_threshold", cfg.jump_threshold);
    if (!(cfg.jump_threshold > 0.0)) m.Fail("jump_threshold", "must be positive");
    m.Finish();
  }

  if (!cfg.pose_given) {
    // Start on the path, facing along it (or at the fixed heading).
    const control::PathPoint s = cfg.path.At(0.0);
    const bool tangent = t.heading_mode == control::PathTrackerDef::HeadingMode::kTangent;
    cfg.body.pose = {s.p.x, s.p.y, tangent ? s.heading : t.fixed_heading};
  }
  return cfg;
}

}  // namespace formsim::sim
