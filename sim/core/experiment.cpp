#include "sim/core/experiment.hpp"
#include "sim/core/number_format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace formsim::sim {

Experiment::Experiment(const ExperimentSetup& setup)
    : setup_(setup),
      pool_(std::make_unique<ThreadPool>(ThreadPool::DefaultThreads())),
      rng_(setup.seed) {
  recorder_.Add("t", [this] { return time_; });
  recorder_.SetPool(pool_.get());
}

void Experiment::SetThreads(int threads) {
  if (threads == pool_->threads()) return;
  pool_ = std::make_unique<ThreadPool>(threads);
  recorder_.SetPool(pool_.get());
}
Experiment::~Experiment() = default;

void Experiment::Start() {
  // Row 0, one every record_every steps, and the last (a run may end between two).
  const double steps = std::ceil(setup_.duration / setup_.dt - 0.5);
  if (steps > 0 && steps < 1e12)
    recorder_.ExpectRows(static_cast<std::size_t>(steps) /
                             static_cast<std::size_t>(std::max(1, setup_.record_every)) +
                         2);
  Sense(0.0);
  recorder_.Sample();
}

void Experiment::Step() {
  if (finished()) return;
  Control(time_);
  pool_->ParallelForBeside([&] { world_.Step(setup_.dt); }, PredictItems(),
                           [&](std::size_t b, std::size_t e) { Predict(b, e); });
  ++steps_;
  // Integer step count times dt, so time does not drift by accumulated rounding.
  time_ = static_cast<double>(steps_) * setup_.dt;
  for (const auto& c : world_.new_collisions()) {
    // Into reused buffers: raising an event allocates nothing once they have grown.
    event_robots_.assign(c.a).append(",").append(c.b);
    event_message_.assign(c.a).append(" hit ").append(c.b);
    events_.Add(time_, event::kCollision, event_robots_, event_message_);
  }
  // A non-finite state goes no further (sensors would hand it to Box2D's ray casts): the row
  // of the fault is recorded and the run stops.
  if (!CheckRobots()) {
    recorder_.Sample();
    return;
  }
  Sense(time_);
  if (steps_ % setup_.record_every == 0 || !stop_reason_.empty()) {
    recorder_.Sample();
    CheckRow();
  }
}

namespace {
}  // namespace

bool Experiment::CheckRobots() {
  for (const auto& r : world_.robots()) {
    const Pose2 p = r->pose();
    const Vec2 v = r->world_velocity();
    const double w = r->yaw_rate();
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta) && std::isfinite(v.x) &&
        std::isfinite(v.y) && std::isfinite(w))
      continue;
    NumericalFault(r->name(), r->name() + "'s state became non-finite at t = " + FormatSignificant(time_) +
                                  " s (x = " + FormatSignificant(p.x) + ", y = " + FormatSignificant(p.y) +
                                  ", θ = " + FormatSignificant(p.theta) + ", v = (" + FormatSignificant(v.x) + ", " + FormatSignificant(v.y) +
                                  "), ω = " + FormatSignificant(w) + ")");
    return false;
  }
  return true;
}

void Experiment::CheckRow() {
  // The row just sampled (the bounded history may not keep it).
  const std::vector<double>& row = recorder_.last_sample();
  if (AllFiniteOrNotSampled(row.data(), row.size())) return;
  for (std::size_t c = 0; c < row.size(); ++c) {
    const double v = row[c];
    if (std::isfinite(v) || IsNotSampled(v)) continue;
    // The column's first part names the robot ("R2.x_est") or the link ("R1-R2.phi_est").
    const std::string& name = recorder_.names()[c];
    std::string robots = name.substr(0, name.find('.'));
    std::replace(robots.begin(), robots.end(), '-', ',');
    NumericalFault(robots, name + " = " + FormatSignificant(v) + " at t = " + FormatSignificant(time_) + " s");
    return;
  }
}

void Experiment::NumericalFault(const std::string& robots, const std::string& message) {
  if (!stop_reason_.empty()) return;
  events_.Add(time_, event::kNumericalFault, robots, message);
  stop_status_ = "numerical_fault";
  stop_reason_ = "numerical fault: " + message;
}

void Experiment::Interrupt(const std::string& why) {
  if (!stop_reason_.empty()) return;
  stop_status_ = "interrupted";
  stop_reason_ = why;
}

std::string Experiment::status() const {
  if (!stop_status_.empty()) return stop_status_;
  return finished() ? "completed" : "running";
}

std::string Experiment::Move(const std::string& name, Vec2 p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    return "cannot move '" + name + "' to a non-finite position";
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

void Experiment::FocusPoints(std::vector<Vec2>& bodies, std::vector<double>& radii,
                             std::vector<Vec2>& /*trails*/, double /*seconds*/) const {
  for (const auto& r : world_.robots()) {
    const RobotDef& d = r->def();
    bodies.push_back(r->pose().p());
    radii.push_back(d.shape == RobotDef::Shape::kCircle ? d.radius
                                                         : std::hypot(d.half_length, d.half_width));
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
  j["status"] = status();
  if (!stop_reason_.empty()) j["stop_reason"] = stop_reason_;
  j["provenance"] = s.provenance.ToJson();
  j["results"] = Results().ToJson();
  Json counts = Json::Object();
  for (const auto& [kind, n] : events_.counts()) counts[kind] = static_cast<long long>(n);
  j["event_counts"] = counts;
  Json list = Json::Array();
  constexpr std::size_t kMaxListed = 200;
  const auto& events = events_.list();
  j["events_stored"] = static_cast<long long>(events.size());
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
  if (!stop_reason_.empty())
    out += "run stopped at t = " + FormatSignificant(time_) + " s: " + stop_reason_ + "\n";
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
