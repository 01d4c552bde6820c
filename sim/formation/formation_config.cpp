#include "sim/formation/formation_config.hpp"

#include <algorithm>
#include <map>
#include <set>

namespace formsim::sim {
namespace {

using control::FormationLaw;
using control::LeaderScheduleDef;

// Reads `<name>_sigma` or `<name>_variance` (not both) into v.
void ReadNoiseValue(YamlReader& m, const std::string& name, NoiseValue& v) {
  const std::string ks = name + "_sigma", kv = name + "_variance";
  const bool has_s = m.Has(ks), has_v = m.Has(kv);
  if (has_s && has_v) m.Fail(kv, "give either " + ks + " or " + kv + ", not both");
  if (has_s) {
    v = {m.Double(ks, 0.0), false, true};
    if (v.value < 0) m.Fail(ks, "must be >= 0");
  } else if (has_v) {
    v = {m.Double(kv, 0.0), true, true};
    if (v.value < 0) m.Fail(kv, "must be >= 0");
  } else {
    // Mark both as read so Finish() accepts an absent pair.
    m.Double(ks, 0.0);
    m.Double(kv, 0.0);
  }
}

NoiseDef ReadNoise(YamlReader& m) {
  NoiseDef n;
  ReadNoiseValue(m, "l", n.l);
  ReadNoiseValue(m, "phi", n.phi);
  ReadNoiseValue(m, "alpha", n.alpha);
  m.Finish();
  return n;
}

double Positive(YamlReader& m, const std::string& key, double def) {
  const double v = m.Double(key, def);
  if (!(v > 0.0)) m.Fail(key, "must be > 0");
  return v;
}
double NonNegative(YamlReader& m, const std::string& key, double def) {
  const double v = m.Double(key, def);
  if (v < 0.0) m.Fail(key, "must be >= 0");
  return v;
}

UkfDef ReadUkf(YamlReader& m) {
  UkfDef u;
  u.alpha = Positive(m, "alpha", u.alpha);
  u.beta = NonNegative(m, "beta", u.beta);
  u.kappa = m.Double("kappa", u.kappa);
  if (u.alpha * u.alpha * (3.0 + u.kappa) <= 0.0)
    m.Fail("kappa", "alpha² (3 + kappa) must be > 0 (sigma point spread)");
  u.q_l = NonNegative(m, "q_l", u.q_l);
  u.q_phi = NonNegative(m, "q_phi", u.q_phi);
  u.q_alpha = NonNegative(m, "q_alpha", u.q_alpha);
  u.r_l = m.Has("r_l") ? Positive(m, "r_l", 1.0) : m.Double("r_l", -1.0);
  u.r_phi = m.Has("r_phi") ? Positive(m, "r_phi", 1.0) : m.Double("r_phi", -1.0);
  u.r_alpha = m.Has("r_alpha") ? Positive(m, "r_alpha", 1.0) : m.Double("r_alpha", -1.0);
  u.p0_l = Positive(m, "p0_l", u.p0_l);
  u.p0_phi = Positive(m, "p0_phi", u.p0_phi);
  u.p0_alpha = Positive(m, "p0_alpha", u.p0_alpha);
  u.l0_error = m.Double("l0_error", u.l0_error);
  m.Finish();
  return u;
}

LeaderScheduleDef ReadSchedule(YamlReader& m) {
  LeaderScheduleDef d;
  d.kind = static_cast<LeaderScheduleDef::Kind>(
      m.Choice("kind", control::ScheduleKindNames(), static_cast<int>(d.kind)));
  if (d.kind == LeaderScheduleDef::Kind::kFigureEight) d.omega = control::kPi / 3.0;
  if (d.kind == LeaderScheduleDef::Kind::kSegments) {
    if (!m.Has("segments")) m.Fail("segments", "kind: segments needs a segments list");
    double last = -1e300;
    for (YamlReader& s : m.MapList("segments")) {
      control::ScheduleSegment seg;
      seg.until = s.RequiredDouble("until");
      seg.v = s.Double("v", 0.0);
      seg.w = s.Double("w", 0.0);
      if (seg.until <= last) s.Fail("until", "segment end times must increase");
      last = seg.until;
      s.Finish();
      d.segments.push_back(seg);
    }
    if (d.segments.empty()) m.Fail("segments", "needs at least one segment");
  } else {
    d.v = m.Double("v", d.v);
    if (d.kind == LeaderScheduleDef::Kind::kSpiral) {
      d.accel = m.Double("accel", d.accel);
      d.r0 = Positive(m, "r0", d.r0);
      d.r_rate = NonNegative(m, "r_rate", d.r_rate);
    } else {
      d.omega = m.Double("omega", d.omega);
    }
  }
  m.Finish();
  return d;
}

control::MeasurementSet ReadMeasure(YamlReader& m) {
  const auto items = m.Strings("measure", {"phi", "alpha"});
  const std::set<std::string> s(items.begin(), items.end());
  if (s.size() != items.size()) m.Fail("measure", "a component is listed twice");
  if (s == std::set<std::string>{"phi", "alpha"}) return control::MeasurementSet::kPhiAlpha;
  if (s == std::set<std::string>{"l", "phi", "alpha"}) return control::MeasurementSet::kLPhiAlpha;
  if (s == std::set<std::string>{"alpha"}) return control::MeasurementSet::kAlpha;
  m.Fail("measure", "must be one of [phi, alpha], [l, phi, alpha], [alpha]");
}

void ReadFollow(YamlReader& f, FormationRobotDef& r) {
  control::FormationNodeDef& n = r.node;
  const int law = f.Choice("law", {"l_phi", "l_l"}, -1);
  if (law < 0) f.Fail("law", "required: l_phi (one leader) or l_l (two leaders)");
  n.law = law == 0 ? FormationLaw::kLPhi : FormationLaw::kLL;
  if (!f.Has("leaders")) f.Fail("leaders", "required list of leader names");
  n.leaders = f.Strings("leaders", {});
  n.l_des = f.Double("l_des", n.l_des);
  r.follow.k1 = Positive(f, "k_l", r.follow.k1);
  if (n.law == FormationLaw::kLPhi) {
    n.phi_des = f.Double("phi_des", n.phi_des);
    r.follow.k2 = Positive(f, "k_phi", r.follow.k2);
  } else {
    n.l2_des = f.Double("l2_des", n.l2_des);
    r.follow.k2 = Positive(f, "k_l2", r.follow.k2);
  }
  r.follow.estimator =
      static_cast<EstimatorMode>(f.Choice("estimator", {"truth", "raw", "ukf"}, 0));
  r.follow.measure = ReadMeasure(f);
  YamlReader nm = f.Map("noise");
  r.follow.noise = ReadNoise(nm);
  f.Finish();
}

}  // namespace

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
    cfg.L = Positive(f, "L", cfg.L);
    cfg.bearing =
        static_cast<control::BearingConvention>(f.Choice("bearing", {"das", "printed"}, 0));
    cfg.gain_reading =
        static_cast<control::GainReading>(f.Choice("gain_reading", {"printed", "per_sample"}, 0));
    cfg.control_period = Positive(f, "control_period", cfg.control_period);
    const double ratio = cfg.control_period / dt;
    if (std::abs(ratio - std::round(ratio)) > 1e-9 || ratio < 1.0 - 1e-9)
      f.Fail("control_period", "must be a whole multiple of dt");
    cfg.settle_time = NonNegative(f, "settle_time", cfg.settle_time);
    cfg.singular_threshold = Positive(f, "singular_threshold", cfg.singular_threshold);
    if (cfg.singular_threshold >= 1.0) f.Fail("singular_threshold", "must be < 1 (a |sine|)");
    f.Finish();
  }
  {
    YamlReader n = root.Map("noise");
    cfg.noise = ReadNoise(n);
  }
  {
    YamlReader u = root.Map("ukf");
    cfg.ukf = ReadUkf(u);
  }
  {
    YamlReader d = root.Map("draw");
    cfg.trail_length = d.Int("trail_length", cfg.trail_length);
    cfg.trail_every = d.Int("trail_every", cfg.trail_every);
    if (cfg.trail_length < 0) d.Fail("trail_length", "must be >= 0");
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
    names[r.body.name] = static_cast<int>(i);
    r.body.pose = m.Pose("pose", Pose2{});
    r.body.color_index = static_cast<int>(i);
    YamlReader b = m.Map("body");
    ReadRobotBody(b, r.body);
    YamlReader dr = m.Map("drive");
    r.drive = ReadUnicycleDrive(dr);
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
      r.schedule = ReadSchedule(s);
    }
    m.Finish();
    cfg.robots.push_back(std::move(r));
  }

  std::vector<control::FormationNodeDef> nodes;
  for (const auto& r : cfg.robots) nodes.push_back(r.node);
  try {
    cfg.graph = control::BuildFormationGraph(nodes, cfg.singular_threshold);
  } catch (const control::FormationGraphError& e) {
    // Re-locate the error at the robot's follow block key.
    YAML::Node follow = items[e.robot()].node()["follow"];
    YamlReader at(follow, items[e.robot()].file(), items[e.robot()].KeyPath("follow"));
    at.Fail(e.key(), e.what());
  }
  return cfg;
}

}  // namespace formsim::sim
