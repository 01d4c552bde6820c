#include "sim/formation/formation_config.hpp"

#include <map>
#include <set>

#include "sim/core/multirate.hpp"
#include "sim/core/number_format.hpp"

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
    v = {m.Real(kv, 0.0, Tune(name + " variance", angle ? "rad²" : "m²").AtLeast(0).Slider(0.0, 1e-2).Group(group)),
         true, true};
  } else if (has_s || !inherit) {
    m.Double(kv, 0.0);
    v = {m.Real(ks, 0.0, Tune(name + " σ", angle ? "rad" : "m").AtLeast(0).Slider(0.0, 0.1).Group(group)), false,
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
  u.alpha = m.Real("alpha", u.alpha, Tune("sigma spread a").Above(0).Slider(1e-3, 1.0).Group(g).OnReset());
  u.beta = m.Real("beta", u.beta, Tune("b").AtLeast(0).Slider(0.0, 4.0).Group(g).OnReset());
  u.kappa = m.Real("kappa", u.kappa, Tune("κ").Above(-3).Slider(-2.0, 3.0).Group(g).OnReset());
  if (u.alpha * u.alpha * (3.0 + u.kappa) <= 0.0)
    m.Fail("kappa", "alpha² (3 + kappa) must be > 0 (sigma point spread)");
  u.q_l = m.Real("q_l", u.q_l, Tune("Q l", "m²").AtLeast(0).Slider(1e-12, 1e-2, kLog).Group(g));
  u.q_phi = m.Real("q_phi", u.q_phi, Tune("Q φ", "rad²").AtLeast(0).Slider(1e-12, 1e-2, kLog).Group(g));
  u.q_alpha = m.Real("q_alpha", u.q_alpha, Tune("Q α", "rad²").AtLeast(0).Slider(1e-12, 1e-2, kLog).Group(g));
  // R defaults to the sensor variance; given explicitly it is a tunable of its own.
  auto r = [&](const std::string& key, const std::string& label, const std::string& unit) {
    if (!m.Has(key)) return m.Double(key, -1.0);
    return m.Real(key, 1.0, Tune(label, unit).Above(0).Slider(1e-12, 1e-2, kLog).Group(g));
  };
  u.r_l = r("r_l", "R l", "m²");
  u.r_phi = r("r_phi", "R φ", "rad²");
  u.r_alpha = r("r_alpha", "R α", "rad²");
  u.p0_l = m.Real("p0_l", u.p0_l, Tune("P0 l", "m²").Above(0).Slider(1e-12, 1.0, kLog).Group(g).OnReset());
  u.p0_phi = m.Real("p0_phi", u.p0_phi, Tune("P0 φ", "rad²").Above(0).Slider(1e-12, 1.0, kLog).Group(g).OnReset());
  u.p0_alpha =
      m.Real("p0_alpha", u.p0_alpha, Tune("P0 α", "rad²").Above(0).Slider(1e-12, 1.0, kLog).Group(g).OnReset());
  u.l0_error = m.Double("l0_error", u.l0_error);
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
      d.r0 = m.Real("r0", d.r0, Tune("spiral R0", "m").Above(0).Slider(0.2, 10.0).Group(group));
      d.r_rate = m.Real("r_rate", d.r_rate, Tune("spiral dR/dt", "m/s").AtLeast(0).Slider(0.0, 2.0).Group(group));
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

void ReadFollow(YamlReader& f, FormationRobotDef& r) {
  cf::FormationNodeDef& n = r.node;
  const std::string gains = "Gains/" + r.body.name;
  const int law = f.Choice("law", {"l_phi", "l_l"}, -1);
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
    r.follow.k2 = f.Real("k_phi", r.follow.k2, Tune("k φ").Above(0).Slider(1e-3, 1.0, kLog).Group(gains));
  } else {
    n.l2_des = f.Real("l2_des", n.l2_des, Tune("l2 desired", "m").Above(0).Slider(0.1, 2.0).Group(gains));
    r.follow.k2 = f.Real("k_l2", r.follow.k2, Tune("k l2").Above(0).Slider(1e-3, 1.0, kLog).Group(gains));
  }
  r.follow.estimator = static_cast<EstimatorMode>(
      f.Pick("estimator", EstimatorModeNames(), 0, Tune("estimator").Group("Estimation/" + r.body.name)));
  r.follow.measure = ReadMeasure(f);
  YamlReader nm = f.Map("noise");
  r.follow.noise = ReadNoise(nm, "Noise/" + r.body.name, true);
  f.Finish();
}

}  // namespace

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
                             Tune("settle time", "s").AtLeast(0).Slider(0.0, 10.0).Group(g).OnReset());
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
  return cfg;
}

}  // namespace formsim::sim::formation
