#include "sim/core/experiment.hpp"

#include <algorithm>
#include <map>

namespace formsim::sim {

Experiment::Experiment(const ExperimentSetup& setup) : setup_(setup), rng_(setup.seed) {}
Experiment::~Experiment() = default;

void Experiment::Start() {
  Sense(0.0);
  RecordRow();
}

void Experiment::Step() {
  Control(time_);
  world_.Step(setup_.dt);
  ++steps_;
  // Integer step count times dt, so time does not drift by accumulated rounding.
  time_ = static_cast<double>(steps_) * setup_.dt;
  for (const auto& c : world_.new_collisions())
    AddEvent("collision", c.a + "," + c.b, c.a + " hit " + c.b);
  Sense(time_);
  if (steps_ % setup_.record_every == 0) RecordRow();
}

void Experiment::RecordRow() {
  recorder_.BeginRow();
  Record(recorder_);
}

std::vector<std::string> Experiment::Apply(const PendingChanges& changes) {
  std::vector<std::string> errors;
  bool changed = false;
  for (const auto& e : changes.edits) {
    Param* p = params_.Find(e.key);
    if (!p) {
      errors.push_back("unknown parameter '" + e.key + "'");
      continue;
    }
    const std::string err = ParamTable::SetFromString(*p, e.value);
    if (!err.empty()) errors.push_back(err);
    else changed = true;
  }
  for (const auto& m : changes.moves) {
    if (Robot* r = world_.FindRobot(m.name)) {
      Pose2 pose = r->pose();
      pose.x = m.x;
      pose.y = m.y;
      r->SetPose(pose);
    } else if (!world_.MoveObstacle(m.name, {m.x, m.y})) {
      errors.push_back("nothing named '" + m.name + "' to move");
    }
  }
  if (changed) OnParamsChanged();
  return errors;
}

void Experiment::Draw(DrawSink& draw) const {
  world_.Draw(draw);
  DrawScene(draw);
}

void Experiment::Bounds(Vec2& lo, Vec2& hi) const {
  lo = {1e300, 1e300};
  hi = {-1e300, -1e300};
  auto grow = [&](Vec2 p, double r) {
    lo.x = std::min(lo.x, p.x - r);
    lo.y = std::min(lo.y, p.y - r);
    hi.x = std::max(hi.x, p.x + r);
    hi.y = std::max(hi.y, p.y + r);
  };
  for (const auto& r : world_.robots()) grow(r->pose().p(), 0.3);
  for (const auto& o : world_.obstacles()) {
    if (o.shape == ObstacleDef::Shape::kWall) {
      for (const Vec2& v : o.vertices) grow(v, 0.0);
    } else {
      grow(o.pose.p(), std::max({o.radius, std::hypot(o.half_x, o.half_y)}));
    }
  }
  for (const auto& p : world_.patches())
    for (const Vec2& v : p.polygon) grow(v, 0.0);
  if (lo.x > hi.x) {
    lo = {-1, -1};
    hi = {1, 1};
  }
}

void Experiment::AddEvent(const std::string& kind, const std::string& robots,
                          const std::string& message) {
  events_.push_back({time_, kind, robots, message});
}

// ---- registry ----

namespace {
std::map<std::string, ExperimentFactory>& Factories() {
  static std::map<std::string, ExperimentFactory> f;
  return f;
}
}  // namespace

bool ExperimentRegistry::Register(const std::string& type, ExperimentFactory factory) {
  Factories()[type] = std::move(factory);
  return true;
}

std::vector<std::string> ExperimentRegistry::Types() {
  std::vector<std::string> out;
  for (const auto& kv : Factories()) out.push_back(kv.first);
  return out;
}

const ExperimentFactory* ExperimentRegistry::Find(const std::string& type) {
  auto it = Factories().find(type);
  return it == Factories().end() ? nullptr : &it->second;
}

std::unique_ptr<Experiment> LoadExperimentFromNode(YAML::Node root, const std::string& file,
                                                   long long seed_override) {
  if (!root.IsMap()) throw ScenarioError(file, 0, 0, "", "a scenario must be a YAML map");
  YamlReader r(root, file);
  ExperimentSetup s;
  s.file = file;
  s.type = r.RequiredString("type");
  const ExperimentFactory* factory = ExperimentRegistry::Find(s.type);
  if (!factory) {
    std::string known;
    for (const auto& t : ExperimentRegistry::Types()) known += (known.empty() ? "" : ", ") + t;
    r.Fail("type", "unknown experiment type '" + s.type + "' (known: " + known + ")");
  }
  s.name = r.String("name", file);
  s.description = r.String("description", "");
  const double seed = r.Double("seed", 1.0);
  if (seed < 0 || seed != static_cast<double>(static_cast<long long>(seed)))
    r.Fail("seed", "must be a non-negative integer");
  s.seed = seed_override >= 0 ? static_cast<std::uint64_t>(seed_override) : static_cast<std::uint64_t>(seed);
  s.dt = r.Double("dt", s.dt);
  if (s.dt <= 0 || s.dt > 0.1) r.Fail("dt", "must be in (0, 0.1] s");
  s.duration = r.Double("duration", s.duration);
  if (s.duration <= 0) r.Fail("duration", "must be positive");
  s.record_every = r.Int("record_every", 1);
  if (s.record_every < 1) r.Fail("record_every", "must be >= 1");
  s.scenario = YAML::Clone(root);
  if (seed_override >= 0) s.scenario["seed"] = static_cast<long long>(s.seed);
  std::unique_ptr<Experiment> exp = (*factory)(s, r);
  r.Finish();
  return exp;
}

std::unique_ptr<Experiment> LoadExperiment(const std::string& file,
                                           const std::vector<std::string>& sets,
                                           long long seed_override) {
  YAML::Node root = LoadYamlFile(file);
  for (const auto& a : sets) {
    const std::string err = ApplySet(root, a);
    if (!err.empty()) throw ScenarioError(file, 0, 0, "", err);
  }
  return LoadExperimentFromNode(root, file, seed_override);
}

}  // namespace formsim::sim
