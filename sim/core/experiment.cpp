#include "sim/core/experiment.hpp"

#include <algorithm>
#include <map>

namespace formsim::sim {

Experiment::Experiment(const ExperimentSetup& setup) : setup_(setup), rng_(setup.seed) {
  recorder_.Add("t", [this] { return time_; });
}
Experiment::~Experiment() = default;

void Experiment::Start() {
  Sense(0.0);
  recorder_.Sample();
}

void Experiment::Step() {
  Control(time_);
  world_.Step(setup_.dt);
  ++steps_;
  // Integer step count times dt, so time does not drift by accumulated rounding.
  time_ = static_cast<double>(steps_) * setup_.dt;
  for (const auto& c : world_.new_collisions())
    events_.Add(time_, event::kCollision, c.a + "," + c.b, c.a + " hit " + c.b);
  Sense(time_);
  if (steps_ % setup_.record_every == 0) recorder_.Sample();
}

std::string Experiment::Move(const std::string& name, Vec2 p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return "cannot move '" + name + "' to a non-finite position";
  if (Robot* r = world_.FindRobot(name)) {
    Pose2 pose = r->pose();
    pose.x = p.x;
    pose.y = p.y;
    r->SetPose(pose);
    return "";
  }
  if (world_.MoveObstacle(name, p)) return "";
  return "nothing named '" + name + "' to move";
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
  if (!(lo.x <= hi.x) || !(lo.y <= hi.y)) {
    lo = {-1, -1};
    hi = {1, 1};
  }
}

Json Experiment::Summary() const {
  Json j = Json::Object();
  const ExperimentSetup& s = setup_;
  j["scenario"] = s.name;
  j["file"] = s.file;
  j["type"] = s.type;
  j["seed"] = static_cast<unsigned long long>(s.seed);
  j["dt"] = s.dt;
  j["steps"] = static_cast<long long>(steps_);
  j["time"] = time_;
  j["provenance"] = s.provenance.ToJson();
  j["results"] = Results().ToJson();
  Json counts = Json::Object();
  for (const auto& [kind, n] : events_.counts()) counts[kind] = static_cast<long long>(n);
  j["event_counts"] = counts;
  Json list = Json::Array();
  constexpr std::size_t kMaxListed = 200;
  const auto& events = events_.list();
  for (std::size_t i = 0; i < events.size() && i < kMaxListed; ++i) {
    const Event& e = events[i];
    Json ev = Json::Object();
    ev["t"] = e.time;
    ev["kind"] = e.kind;
    ev["robots"] = e.robots;
    if (!e.subject.empty()) ev["subject"] = e.subject;
    ev["message"] = e.message;
    list.Push(ev);
  }
  j["events"] = list;
  return j;
}

std::string Experiment::SummaryText() const {
  std::string out = Results().Text();
  if (!events_.counts().empty()) {
    out += "events:";
    for (const auto& [kind, n] : events_.counts()) out += " " + kind + " " + std::to_string(n);
    out += "\n";
  }
  return out;
}

// ---- registry ----

namespace {
std::map<std::string, ExperimentKind>& Kinds() {
  static std::map<std::string, ExperimentKind> k;
  return k;
}
}  // namespace

bool ExperimentRegistry::Register(const ExperimentKind& kind) {
  Kinds()[kind.type] = kind;
  return true;
}

std::vector<std::string> ExperimentRegistry::Types() {
  std::vector<std::string> out;
  for (const auto& kv : Kinds()) out.push_back(kv.first);
  return out;
}

const ExperimentKind* ExperimentRegistry::Find(const std::string& type) {
  auto it = Kinds().find(type);
  return it == Kinds().end() ? nullptr : &it->second;
}

}  // namespace formsim::sim
