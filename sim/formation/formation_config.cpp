#include "sim/formation/formation_config.hpp"

#include <map>
#include <set>

#include "sim/core/multirate.hpp"
#include "sim/core/number_format.hpp"
#include "sim/formation/formation_follow.hpp"

namespace formsim::sim::formation {
namespace {

using cf::FormationLaw;
using cf::LeaderScheduleDef;

// Reads `<name>_sigma` or `<name>_variance` (not both) into v. The one present (σ when
// neither is) becomes a tunable of GUI group `group`; `inherit` leaves an absent pair unset.
void ReadNoiseValue(YamlReader& m, const std::string& name, NoiseValue& v, const std::string& group,
                    bool inherit) {
  const std::string ks = name + "_sigma", kv = name + "_variance";
  const bool has_s = m.Has(ks), has_v = m.Has(kv);
  if (has_s && has_v) m.Fail(kv, "give either " + ks + " or " + kv + ", not both");
  const bool angle = name != "l";
  if (has_v) {
    m.Double(ks, 0.0);  // mark the other spelling as allowed
    v = {m.Real(kv, 0.0, Tune(name + " variance", angle ? "rad²" : "m²").In(0, 1e4).Slider(0.0, 1e-2).Group(group)),
         true, true};
  } else if (has_s || !inherit) {
    m.Double(kv, 0.0);
    v = {m.Real(ks, 0.0, Tune(name + " σ", angle ? "rad" : "m").In(0, 100).Slider(0.0, 0.1).Group(group)), false,
         has_s};
  } else {
    m.Double(ks, 0.0);
    m.Double(kv, 0.0);
  }
}

NoiseDef ReadNoise(YamlReader& m, const std::string& group, bool inherit) {
  NoiseDef n;
  ReadNoiseValue(m, "l", n.l, group, inherit);
  ReadNoiseValue(m, "phi", n.phi, group, inherit);
  ReadNoiseValue(m, "alpha", n.alpha, group, inherit);
  m.Finish();
  return n;
}

UkfDef ReadUkf(YamlReader& m) {
  const std::string g = "Estimation/UKF";
  UkfDef u;
  u.alpha = m.Real("alpha", u.alpha, Tune("sigma spread a").Above(0).AtMost(1).Slider(1e-3, 1.0).Group(g).OnReset());
  u.beta = m.Real("beta", u.beta, Tune("b").In(0, 100).Slider(0.0, 4.0).Group(g).OnReset());
  u.kappa = m.Real("kappa", u.kappa, Tune("κ").Above(-3).AtMost(100).Slider(-2.0, 3.0).Group(g).OnReset());
  if (u.alpha * u.alpha * (3.0 + u.kappa) <= 0.0)
    m.Fail("kappa", "alpha² (3 + kappa) must be > 0 (sigma point spread)");
  u.q_l = m.Real("q_l", u.q_l, Tune("Q l", "m²").In(0, 1e4).Slider(1e-12, 1e-2, kLog).Group(g));
  u.q_phi = m.Real("q_phi", u.q_phi, Tune("Q φ", "rad²").In(0, 1e4).Slider(1e-12, 1e-2, kLog).Group(g));
  u.q_alpha = m.Real("q_alpha", u.q_alpha, Tune("Q α", "rad²").In(0, 1e4).Slider(1e-12, 1e-2, kLog).Group(g));
  // R defaults to the sensor variance; given explicitly it is a tunable of its own.
  auto r = [&](const std::string& key, const std::string& label, const std::string& unit) {
    if (!m.Has(key)) return m.Double(key, -1.0);
    return m.Real(key, 1.0, Tune(label, unit).Above(0).AtMost(1e4).Slider(1e-12, 1e-2, kLog).Group(g));
  };
  u.r_l = r("r_l", "R l", "m²");
  u.r_phi = r("r_phi", "R φ", "rad²");
  u.r_alpha = r("r_alpha", "R α", "rad²");
  u.p0_l = m.Real("p0_l", u.p0_l, Tune("P0 l", "m²").Above(0).AtMost(1e6).Slider(1e-12, 1.0, kLog).Group(g).OnReset());
  u.p0_phi = m.Real("p0_phi", u.p0_phi, Tune("P0 φ", "rad²").Above(0).AtMost(1e6).Slider(1e-12, 1.0, kLog).Group(g).OnReset());
  u.p0_alpha =
      m.Real("p0_alpha", u.p0_alpha, Tune("P0 α", "rad²").Above(0).AtMost(1e6).Slider(1e-12, 1.0, kLog).Group(g).OnReset());
  u.l0_error = m.Double("l0_error", u.l0_error);
  // Ours: Euler substeps of the prediction (1 = the paper's single step per Tc).
  u.substeps = m.Integer("substeps", u.substeps,
                         Tune("prediction substeps").In(1, 1000).Slider(1, 50).Group(g));
  m.Finish();
  return u;
}

LeaderScheduleDef ReadSchedule(YamlReader& m, const std::string& group) {
  LeaderScheduleDef d;
  d.kind = static_cast<LeaderScheduleDef::Kind>(
      m.Choice("kind", cf::ScheduleKindNames(), static_cast<int>(d.kind)));
  if (d.kind == LeaderScheduleDef::Kind::kFigureEight) d.omega = control::kPi / 3.0;
  if (d.kind == LeaderScheduleDef::Kind::kSegments) {
    if (!m.Has("segments")) m.Fail("segments", "kind: segments needs a segments list");
    double last = -1e300;
    for (YamlReader& s : m.MapList("segments")) {
      cf::ScheduleSegment seg;
      seg.until = s.RequiredDouble("until");
      seg.v = s.Double("v", 0.0);
      seg.w = s.Double("w", 0.0);
      if (seg.until <= last) s.Fail("until", "segment end times must increase");
      last = seg.until;
      s.Finish();
      d.segments.push_back(seg);
    }
    if (d.segments.empty()) m.Fail("segments", "needs at least one segment");
    d.ramp = m.Double("ramp", 0.0);
    if (!(d.ramp >= 0.0)) m.Fail("ramp", "must be >= 0");
    for (std::size_t k = 1; k < d.segments.size(); ++k)
      if (d.ramp > d.segments[k].until - d.segments[k - 1].until)
        m.Fail("ramp", "must not exceed the length of any segment after the first (" +
                           Sprintf("%g", d.segments[k].until - d.segments[k - 1].until) + " s)");
  } else {
    d.v = m.Real("v", d.v, Tune("leader v", "m/s").AtLeast(-10).AtMost(10).Slider(0.0, 5.0).Group(group));
    if (d.kind == LeaderScheduleDef::Kind::kSpiral) {
      d.accel = m.Real("accel", d.accel, Tune("spiral dv/dt", "m/s²").In(-10, 10).Slider(-0.5, 0.5).Group(group));
      d.r0 = m.Real("r0", d.r0, Tune("spiral R0", "m").Above(0).AtMost(1e4).Slider(0.2, 10.0).Group(group));
      d.r_rate = m.Real("r_rate", d.r_rate, Tune("spiral dR/dt", "m/s").In(0, 100).Slider(0.0, 2.0).Group(group));
    } else {
      d.omega = m.Real("omega", d.omega,
                       Tune("leader ω amplitude", "rad/s").In(-20, 20).Slider(0.0, 3.0).Group(group));
    }
  }
  m.Finish();
  return d;
}

cf::MeasurementSet ReadMeasure(YamlReader& m) {
  const auto items = m.Strings("measure", {"phi", "alpha"});
  const std::set<std::string> s(items.begin(), items.end());
  if (s.size() != items.size()) m.Fail("measure", "a component is listed twice");
  if (s == std::set<std::string>{"phi", "alpha"}) return cf::MeasurementSet::kPhiAlpha;
  if (s == std::set<std::string>{"l", "phi", "alpha"}) return cf::MeasurementSet::kLPhiAlpha;
  if (s == std::set<std::string>{"alpha"}) return cf::MeasurementSet::kAlpha;
  m.Fail("measure", "must be one of [phi, alpha], [l, phi, alpha], [alpha]");
}

}  // namespace

void ReadFollow(YamlReader& f, FormationRobotDef& r) {
  cf::FormationNodeDef& n = r.node;
  const std::string gains = "Gains/" + r.body.name;
  const int law = f.Choice("law", cf::FollowerLawNames(), -1);
  if (law < 0) f.Fail("law", "required: l_phi (one leader) or l_l (two leaders)");
  n.law = law == 0 ? FormationLaw::kLPhi : FormationLaw::kLL;
  if (!f.Has("leaders")) f.Fail("leaders", "required list of leader names");
  n.leaders = f.Strings("leaders", {});
  const bool lphi = n.law == FormationLaw::kLPhi;
  n.l_des = f.Real("l_des", n.l_des,
                   Tune(lphi ? "l desired" : "l1 desired", "m").Above(0).Slider(0.1, 2.0).Group(gains));
  r.follow.k1 = f.Real("k_l", r.follow.k1, Tune(lphi ? "k l" : "k l1").Above(0).Slider(1e-3, 1.0, kLog).Group(gains));
  if (lphi) {
    n.phi_des = f.Real("phi_des", n.phi_des,
                       Tune("φ desired", "rad").In(-2 * control::kPi, 2 * control::kPi)
                           .Slider(-control::kPi, 2 * control::kPi).Group(gains));
    r.follow.k2 = f.Real("k_phi", r.follow.k2, Tune("k φ").Above(0).AtMost(1e4).Slider(1e-3, 1.0, kLog).Group(gains));
  } else {
    n.l2_des = f.Real("l2_des", n.l2_des, Tune("l2 desired", "m").Above(0).AtMost(1000).Slider(0.1, 2.0).Group(gains));
    r.follow.k2 = f.Real("k_l2", r.follow.k2, Tune("k l2").Above(0).AtMost(1e4).Slider(1e-3, 1.0, kLog).Group(gains));
  }
  r.follow.estimator = static_cast<EstimatorMode>(
      f.Pick("estimator", EstimatorModeNames(), 0, Tune("estimator").Group("Estimation/" + r.body.name)));
  r.follow.measure = ReadMeasure(f);
  YamlReader nm = f.Map("noise");
  r.follow.noise = ReadNoise(nm, "Noise/" + r.body.name, true);
  f.Finish();
}

namespace {

// A shape's slots: `slots: {ROBOT: {l_des, phi_des | l2_des}}`, over the follow: values.
ShapeDef ReadShape(YamlReader& s, const FormationConfig& cfg, const std::map<std::string, int>& names) {
  ShapeDef shape;
  shape.name = s.RequiredString("name");
  if (shape.name == "initial")
    s.Fail("name", "'initial' is reserved for the formation of the robots' follow: blocks");
  if (shape.name.find_first_of(".,: ") != std::string::npos)
    s.Fail("name", "a shape name must not contain '.', ',', ':' or spaces (names address keys and actions)");
  shape.slots = cfg.ShapeSlots(-1);
  const std::string group = "Switching/" + shape.name;
  if (!s.Has("slots")) s.Fail("slots", "required: the slots of the followers that move, by robot name");
  YamlReader sl = s.Map("slots");
  std::vector<std::string> keys;
  for (auto it = sl.node().begin(); it != sl.node().end(); ++it) keys.push_back(it->first.Scalar());
  for (const std::string& name : keys) {
    const auto at = names.find(name);
    if (at == names.end()) sl.Fail(name, "no robot '" + name + "' in this scenario");
    const FormationRobotDef& r = cfg.robots[static_cast<std::size_t>(at->second)];
    if (r.node.law == FormationLaw::kRoot) sl.Fail(name, "'" + name + "' is a root leader: it has no slot");
    YamlReader m = sl.Map(name);
    cf::SlotValues& v = shape.slots[static_cast<std::size_t>(at->second)];
    const bool lphi = r.node.law == FormationLaw::kLPhi;
    const std::string g = group + "/" + name;
    v.l_des = m.Real("l_des", v.l_des, Tune(lphi ? "l desired" : "l1 desired", "m").Above(0).Slider(0.1, 2.0).Group(g));
    if (lphi)
      v.phi_des = m.Real("phi_des", v.phi_des,
                         Tune("φ desired", "rad").In(-2 * control::kPi, 2 * control::kPi)
                             .Slider(-control::kPi, 2 * control::kPi).Group(g));
    else
      v.l2_des = m.Real("l2_des", v.l2_des, Tune("l2 desired", "m").Above(0).AtMost(1000).Slider(0.1, 2.0).Group(g));
    m.Finish();
  }
  sl.Finish();
  s.Finish();
  return shape;
}

// `switching:` (after the robots and the graph). Every transition the schedule makes, and every
// other one the GUI or a script could ask for, keeps the l-l triangles valid all the way.
void ReadSwitching(YamlReader& root, FormationConfig& cfg, const std::map<std::string, int>& names) {
  if (!root.Has("switching")) {
    root.Raw("switching");
    return;
  }
  YamlReader sw = root.Map("switching");
  SwitchingDef& d = cfg.switching;
  d.transition = sw.Real("transition", d.transition,
                         Tune("transition time", "s").Above(0).AtMost(1e4).Slider(0.1, 5.0).Group("Switching"));
  if (!sw.Has("shapes")) sw.Fail("shapes", "required: at least one named shape");
  std::vector<YamlReader> shapes = sw.MapList("shapes");
  if (shapes.empty()) sw.Fail("shapes", "needs at least one shape");
  for (YamlReader& s : shapes) {
    ShapeDef shape = ReadShape(s, cfg, names);
    if (d.Find(shape.name) != -2) s.Fail("name", "duplicate shape name '" + shape.name + "'");
    d.shapes.push_back(std::move(shape));
  }
  std::vector<YamlReader> entries = sw.MapList("schedule");
  double last_at = -1.0;
  int first_root = 0;
  while (cfg.robots[static_cast<std::size_t>(first_root)].node.law != FormationLaw::kRoot) ++first_root;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    YamlReader& e = entries[k];
    SwitchDef s;
    const std::string g = "Switching/schedule " + std::to_string(k);
    const bool has_at = e.Has("at"), has_wp = e.Has("waypoint");
    if (has_at == has_wp) e.Fail(has_at ? "waypoint" : "at", "give either at: (a time) or waypoint: [x, y]");
    if (has_at) {
      s.trigger = SwitchDef::Trigger::kTime;
      s.at = e.Real("at", 0.0, Tune("switch time", "s").AtLeast(0).AtMost(1e7).Slider(0.0, 60.0).Group(g).OnReset());
      if (s.at <= last_at) e.Fail("at", "switch times must increase along the schedule");
      last_at = s.at;
      e.Raw("waypoint"), e.Raw("radius"), e.Raw("robot");
    } else {
      s.trigger = SwitchDef::Trigger::kWaypoint;
      const std::vector<double> wp = e.Doubles("waypoint", {}, 2);
      s.waypoint = {wp[0], wp[1]};
      if (!(std::abs(s.waypoint.x) <= world_limits::kExtent && std::abs(s.waypoint.y) <= world_limits::kExtent))
        e.Fail("waypoint", "must lie inside the world (|x|, |y| <= 1e4 m)");
      s.radius = e.Real("radius", s.radius, Tune("waypoint radius", "m").Above(0).AtMost(1e3).Slider(0.05, 2.0).Group(g).OnReset());
      const std::string who = e.String("robot", cfg.robots[static_cast<std::size_t>(first_root)].body.name);
      const auto it = names.find(who);
      if (it == names.end()) e.Fail("robot", "no robot '" + who + "' in this scenario");
      s.robot = it->second;
      e.Raw("at");
    }
    const std::string to = e.RequiredString("to");
    s.shape = d.Find(to);
    if (s.shape == -2) {
      std::string known = "initial";
      for (const ShapeDef& sh : d.shapes) known += ", " + sh.name;
      e.Fail("to", "no shape '" + to + "' (shapes: " + known + ")");
    }
    s.transition = e.Real("transition", d.transition,
                          Tune("transition time", "s").Above(0).AtMost(1e4).Slider(0.1, 5.0).Group(g));
    e.Finish();
    d.schedule.push_back(s);
  }
  sw.Finish();

  // The triangle condition along every transition: the schedule's first (reported at the
  // entry), then every other pair of shapes (the GUI and scripts may switch between any two).
  std::vector<cf::FormationNodeDef> nodes;
  for (const auto& r : cfg.robots) nodes.push_back(r.node);
  const int n_shapes = static_cast<int>(d.shapes.size());
  std::vector<std::vector<bool>> checked(n_shapes + 1, std::vector<bool>(n_shapes + 1, false));
  auto check = [&](int a, int b) {
    checked[a + 1][b + 1] = checked[b + 1][a + 1] = true;
    return cf::CheckTransition(nodes, cfg.ShapeSlots(a), cfg.ShapeSlots(b), cfg.singular_threshold);
  };
  auto shape_name = [&](int s) { return s < 0 ? std::string("initial") : d.shapes[s].name; };
  int from = -1;
  for (std::size_t k = 0; k < d.schedule.size(); ++k) {
    const int to = d.schedule[k].shape;
    const std::string err = from == to || checked[from + 1][to + 1] ? "" : check(from, to);
    if (!err.empty())
      entries[k].Fail("to", "the transition '" + shape_name(from) + "' -> '" + shape_name(to) +
                                "' breaks the l-l triangle condition: " + err);
    from = to;
  }
  for (int a = -1; a < n_shapes; ++a)
    for (int b = a + 1; b < n_shapes; ++b) {
      if (checked[a + 1][b + 1]) continue;
      const std::string err = check(a, b);
      if (!err.empty())
        shapes[b].Fail("name", "switching between '" + shape_name(a) + "' and '" + shape_name(b) +
                                   "' (the GUI and scripts may ask for it) breaks the l-l triangle "
                                   "condition: " + err);
    }
}

AvoidanceConfig ReadAvoidance(YamlReader& root) {
  AvoidanceConfig a;
  if (!root.Has("avoidance")) {
    root.Raw("avoidance");
    return a;
  }
  YamlReader m = root.Map("avoidance");
  a.present = true;
  const std::string g = "Avoidance";
  a.enabled = m.Flag("enabled", true, Tune("obstacle avoidance").Group(g));
  a.def.safety_distance = m.Real("safety_distance", a.def.safety_distance,
                                 Tune("safety distance", "m").Above(0).AtMost(100).Slider(0.05, 1.0).Group(g));
  a.def.hysteresis = m.Real("hysteresis", a.def.hysteresis,
                            Tune("hysteresis", "m").AtLeast(0).AtMost(100).Slider(0.0, 0.5).Group(g));
  a.def.min_dwell = m.Real("min_dwell", a.def.min_dwell,
                           Tune("min time avoiding", "s").AtLeast(0).AtMost(1e3).Slider(0.0, 2.0).Group(g));
  a.k_obstacle = m.Real("k_obstacle", a.k_obstacle, Tune("k obstacle").Above(0).AtMost(1e4).Slider(1e-3, 1.0, kLog).Group(g));
  m.Finish();
  return a;
}

}  // namespace

std::vector<cf::SlotValues> FormationConfig::ShapeSlots(int shape) const {
  if (shape >= 0) return switching.shapes[static_cast<std::size_t>(shape)].slots;
  std::vector<cf::SlotValues> s;
  s.reserve(robots.size());
  for (const auto& r : robots) s.push_back(cf::SlotOf(r.node));
  return s;
}

const std::vector<std::string>& EstimatorModeNames() {
  static const std::vector<std::string> names = {"truth", "raw", "ukf"};
  return names;
}

NoiseDef EffectiveNoise(const FormationConfig& cfg, const FollowerDef& f) {
  NoiseDef n = cfg.noise;
  if (f.noise.l.present) n.l = f.noise.l;
  if (f.noise.phi.present) n.phi = f.noise.phi;
  if (f.noise.alpha.present) n.alpha = f.noise.alpha;
  return n;
}

FormationConfig ReadFormationConfig(YamlReader& root, double dt) {
  FormationConfig cfg;
  cfg.control_period = dt;
  {
    YamlReader f = root.Map("formation");
    const std::string g = "Gains";
    cfg.gain_reading = static_cast<cf::GainReading>(
        f.Pick("gain_reading", {"printed", "per_sample"}, 0, Tune("gain reading").Group(g)));
    cfg.bearing = static_cast<cf::BearingConvention>(
        f.Pick("bearing", {"das", "printed"}, 0, Tune("bearing convention").Group(g)));
    cfg.singular_threshold = f.Real("singular_threshold", cfg.singular_threshold,
                                    Tune("l-l singular |sin|").Above(0).Below(1).Slider(0.01, 0.5).Group(g));
    cfg.L = f.Real("L", cfg.L, Tune("control point L", "m").Above(0).Slider(0.05, 0.5).Group(g));
    cfg.settle_time = f.Real("settle_time", cfg.settle_time,
                             Tune("settle time", "s").In(0, 1e7).Slider(0.0, 10.0).Group(g).OnReset());
    cfg.control_period = f.Double("control_period", cfg.control_period);
    cfg.control_every = ReadPeriodSteps(f, "control_period", dt, dt, true);
    f.Finish();
  }
  {
    YamlReader n = root.Map("noise");
    cfg.noise = ReadNoise(n, "Noise/all links", false);
  }
  {
    YamlReader u = root.Map("ukf");
    cfg.ukf = ReadUkf(u);
  }
  {
    YamlReader d = root.Map("draw");
    cfg.trail_length = d.Int("trail_length", cfg.trail_length);
    cfg.trail_every = d.Int("trail_every", cfg.trail_every);
    if (cfg.trail_length < 0 || cfg.trail_length > 100000) d.Fail("trail_length", "must be in [0, 100000]");
    if (cfg.trail_every < 1) d.Fail("trail_every", "must be >= 1");
    d.Finish();
  }
  {
    YamlReader w = root.Map("world");
    cfg.world = ReadWorldDef(w);
  }
  cfg.obstacles = ReadObstacles(root);
  cfg.patches = ReadPatches(root);

  if (!root.Has("robots")) root.Fail("robots", "required list of robots");
  std::vector<YamlReader> items = root.MapList("robots");
  if (items.empty()) root.Fail("robots", "needs at least one robot");
  std::map<std::string, int> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    YamlReader& m = items[i];
    FormationRobotDef r;
    r.body = DefaultRobotDef();
    r.body.name = m.RequiredString("name");
    if (names.count(r.body.name)) m.Fail("name", "duplicate robot name '" + r.body.name + "'");
    if (r.body.name.find_first_of(".,") != std::string::npos)
      m.Fail("name", "a robot name must not contain '.' or ',' (names address keys and events)");
    names[r.body.name] = static_cast<int>(i);
    r.body.pose = m.Pose("pose", Pose2{});
    r.body.color_index = static_cast<int>(i);
    YamlReader b = m.Map("body");
    ReadRobotBody(b, r.body);
    YamlReader dr = m.Map("drive");
    r.drive = ReadUnicycleDrive(dr, "Drive/" + r.body.name);
    r.node.name = r.body.name;
    r.node.initial_pose = r.body.pose;
    r.node.L = cfg.L;
    const bool has_follow = m.Has("follow"), has_schedule = m.Has("schedule");
    if (has_follow && has_schedule)
      m.Fail("schedule", "a robot either follows (follow:) or has an open-loop schedule, not both");
    if (has_follow) {
      YamlReader f = m.Map("follow");
      ReadFollow(f, r);
    } else {
      YamlReader s = m.Map("schedule");
      r.schedule = ReadSchedule(s, "Gains/" + r.body.name);
    }
    m.Finish();
    cfg.robots.push_back(std::move(r));
  }

  std::vector<cf::FormationNodeDef> nodes;
  for (const auto& r : cfg.robots) nodes.push_back(r.node);
  try {
    cfg.graph = cf::BuildFormationGraph(nodes, cfg.singular_threshold);
  } catch (const cf::FormationGraphError& e) {
    // Re-locate the error at the robot's follow block key.
    YamlReader at(items[e.robot()].node()["follow"], items[e.robot()].shared_context(),
                  items[e.robot()].KeyPath("follow"));
    at.Fail(e.key(), e.what());
  }
  ReadSwitching(root, cfg, names);
  cfg.avoidance = ReadAvoidance(root);
  return cfg;
}

}  // namespace formsim::sim::formation
