#include "sim/formation/formation_edit.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <variant>
#include <vector>

#include "control/common/angle.hpp"
#include "control/formation/formation_shapes.hpp"
#include "control/formation/link_kinematics.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/yaml_reader.hpp"
#include "sim/formation/formation_experiment.hpp"
#include "sim/formation/formation_follow.hpp"

namespace formsim::sim::formation {
namespace {

namespace cf = control::formation;

[[noreturn]] void Fail(const std::string& why) { throw std::runtime_error(why); }

YAML::Node PoseNode(const Pose2& p) {
  YAML::Node n(YAML::NodeType::Sequence);
  n.push_back(NumberNode(p.x));
  n.push_back(NumberNode(p.y));
  n.push_back(NumberNode(control::WrapToPi(p.theta)));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

std::string NameOf(const YAML::Node& robot) {
  return robot.IsMap() && robot["name"] ? robot["name"].as<std::string>() : "";
}

int Find(const YAML::Node& robots, const std::string& name) {
  for (std::size_t i = 0; i < robots.size(); ++i)
    if (NameOf(robots[i]) == name) return static_cast<int>(i);
  return -1;
}

const Pose2& PoseOf(const FormationState& st, const std::string& name) {
  const auto it = st.poses.find(name);
  if (it == st.poses.end()) Fail("no robot '" + name + "' in the formation");
  return it->second;
}

// A follow block's law, leaders and desired slot for a control point at `m`, measured from the
// leaders as they are now. Keys of the other law go; the rest (gains, estimator, noise) stay.
void SetFollow(YAML::Node robot, cf::FormationLaw law, const std::vector<std::string>& leaders,
               const Vec2& m, const FormationState& st) {
  const std::size_t want = cf::LeadersOfLaw(law);
  if (leaders.size() != want)
    Fail(std::string("law ") + cf::LawName(law) + " needs " + std::to_string(want) + " leader" +
         (want == 1 ? "" : "s") + ", got " + std::to_string(leaders.size()));
  robot.remove("schedule");
  const Pose2& p1 = PoseOf(st, leaders[0]);
  const Vec2 r = m - p1.p();
  FollowBlock b;
  b.law = law;
  b.leaders = leaders;
  b.l_des = r.Norm();
  b.second_des = law == cf::FormationLaw::kLPhi
                     ? control::WrapTo2Pi(std::atan2(r.y, r.x) - p1.theta)
                     : (m - PoseOf(st, leaders[1]).p()).Norm();
  YAML::Node f = robot["follow"];
  WriteFollow(f, b);
  robot["follow"] = f;
}

std::string NextName(const YAML::Node& robots) {
  for (int k = static_cast<int>(robots.size()) + 1;; ++k) {
    const std::string n = "R" + std::to_string(k);
    if (Find(robots, n) < 0) return n;
  }
}

// The comment lines before the first key (the scenario's description) stay at the top.
std::string Header(const std::string& text) {
  std::string out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] != '#') break;
    out += line + "\n";
  }
  return out;
}

void Shape(YAML::Node robots, const ApplyShape& change, const FormationState& st) {
  const double spacing = change.spacing.value_or(kDefaultShapeSpacing);
  if (!(spacing > 2.0 * st.L) || spacing > 10.0)
    Fail("shape spacing must lie in (2 L, 10] m = (" + FormatDouble(2.0 * st.L) + ", 10]");
  // The first robot without a follow block is the root; every other robot follows.
  int root = -1;
  for (std::size_t i = 0; i < robots.size() && root < 0; ++i)
    if (!robots[i]["follow"]) root = static_cast<int>(i);
  if (root < 0) Fail("shape: the formation has no root leader (a robot without follow:)");
  std::vector<std::string> names = {NameOf(robots[root])};
  std::vector<int> index = {root};
  for (std::size_t i = 0; i < robots.size(); ++i)
    if (static_cast<int>(i) != root) names.push_back(NameOf(robots[i])), index.push_back(static_cast<int>(i));
  const cf::FormationShape shape = cf::MakeFormationShape(change.kind, names, spacing, st.L);
  const Pose2& r = PoseOf(st, names[0]);
  const double c = std::cos(r.theta), s = std::sin(r.theta);
  // Every follower on its slot, seen from the root as it is now, heading as the root.
  FormationState placed = st;
  for (std::size_t k = 1; k < names.size(); ++k) {
    const Vec2 q = shape.slots[k];
    placed.poses[names[k]] = {r.x + c * q.x - s * q.y, r.y + s * q.x + c * q.y, r.theta};
  }
  for (std::size_t k = 1; k < names.size(); ++k) {
    YAML::Node robot = robots[index[k]];
    const cf::FormationNodeDef& n = shape.nodes[k];
    const Pose2& p = placed.poses[names[k]];
    robot["pose"] = PoseNode(p);
    SetFollow(robot, n.law, n.leaders, cf::ControlPoint(p, st.L), placed);
  }
}

void CheckLeaders(const YAML::Node& robots, const std::vector<std::string>& leaders) {
  for (const auto& l : leaders)
    if (Find(robots, l) < 0) Fail("leader '" + l + "' is not a robot of this scenario");
}

void Add(YAML::Node robots, const AddFollower& c, const FormationState& st) {
  CheckLeaders(robots, c.leaders);
  const std::string name = c.name.empty() ? NextName(robots) : c.name;
  if (Find(robots, name) >= 0) Fail("a robot named '" + name + "' exists already");
  const Pose2 p{c.x, c.y, c.leaders.empty() ? 0.0 : PoseOf(st, c.leaders[0]).theta};
  YAML::Node robot(YAML::NodeType::Map);
  robot["name"] = name;
  robot["pose"] = PoseNode(p);
  FormationState with = st;
  with.poses[name] = p;
  SetFollow(robot, c.law, c.leaders, cf::ControlPoint(p, st.L), with);
  robots.push_back(robot);
}

void Remove(YAML::Node root, const RemoveRobot& c) {
  YAML::Node robots = root["robots"];
  const int i = Find(robots, c.name);
  if (i < 0) Fail("no robot '" + c.name + "' in the formation");
  if (robots.size() == 1) Fail("the last robot cannot be removed");
  YAML::Node kept(YAML::NodeType::Sequence);
  for (std::size_t k = 0; k < robots.size(); ++k)
    if (static_cast<int>(k) != i) kept.push_back(robots[k]);
  root["robots"] = kept;
}

void Attach(YAML::Node robots, const AttachFollower& c, const FormationState& st) {
  const int i = Find(robots, c.name);
  if (i < 0) Fail("no robot '" + c.name + "' in the formation");
  CheckLeaders(robots, c.leaders);
  SetFollow(robots[i], c.law, c.leaders, cf::ControlPoint(PoseOf(st, c.name), st.L), st);
}

// `text` with the robots where they are now and then `change` (none: nothing else).
std::string Rewrite(const std::string& text, const StructureChange* change,
                    const FormationState& st) {
  YAML::Node root;
  try {
    root = LoadYamlText(text, "the scenario text");  // aliases and nesting bounded
  } catch (const std::exception& e) {
    Fail(std::string("the scenario text does not parse: ") + e.what());
  }
  YAML::Node robots = root["robots"];
  if (!robots || !robots.IsSequence()) Fail("the scenario has no robots list");
  // The robots stay where they are now (written first: a change may place some elsewhere).
  if (st.carry_poses)
    for (std::size_t i = 0; i < robots.size(); ++i) {
      const auto it = st.poses.find(NameOf(robots[i]));
      if (it != st.poses.end()) robots[i]["pose"] = PoseNode(it->second);
    }
  if (change != nullptr) {
    struct Apply {
      YAML::Node root, robots;
      const FormationState& st;
      void operator()(const AddFollower& c) { Add(robots, c, st); }
      void operator()(const RemoveRobot& c) { Remove(root, c); }
      void operator()(const AttachFollower& c) { Attach(robots, c, st); }
      void operator()(const ApplyShape& c) { Shape(robots, c, st); }
    };
    std::visit(Apply{root, robots, st}, change->what);
  }
  YAML::Emitter out;
  out.SetIndent(2);
  out << root;
  if (!out.good()) Fail(std::string("the edited scenario cannot be written: ") + out.GetLastError());
  return Header(text) + out.c_str() + "\n";
}

}  // namespace

std::string RestructureFormationText(const std::string& text, const StructureChange& change,
                                     const FormationState& st) {
  return Rewrite(text, &change, st);
}

std::string PlacedFormationText(const std::string& text, const FormationState& st) {
  return Rewrite(text, nullptr, st);
}

FormationState FormationExperiment::EditState() const {
  FormationState st;
  st.L = cfg_.L;
  st.carry_poses = steps() > 0;
  for (const Agent& a : agents_) st.poses[a.robot->name()] = a.robot->pose();
  return st;
}

std::string FormationExperiment::Restructured(const std::string& text,
                                              const StructureChange& change) const {
  if (const std::string why = StructureLocked(); !why.empty()) throw std::runtime_error(why);
  return RestructureFormationText(text, change, EditState());
}

// The switching: block names every follower's law and slots in each of its shapes; a structural
// change would leave them naming robots and keys that are no longer there.
std::string FormationExperiment::StructureLocked() const {
  if (cfg_.switching.shapes.empty()) return "";
  return "this scenario switches between the shapes of its switching: block, which give every "
         "follower's law and slot; switch with switch-formation, drag slots, or edit a copy "
         "of the file without the block";
}

std::string FormationExperiment::PlacedText(const std::string& text) const {
  return PlacedFormationText(text, EditState());
}

std::vector<std::string> FormationExperiment::LeadersOf(const std::string& robot) const {
  std::vector<std::string> out;
  for (std::size_t j = 0; j < agents_.size(); ++j)
    if (agents_[j].robot->name() == robot)
      for (int li : agents_[j].links) out.push_back(agents_[links_[li].leader].robot->name());
  return out;
}

std::vector<std::pair<std::string, std::string>> FormationExperiment::SlotEdits(
    const std::string& robot, Vec2 p) const {
  for (std::size_t j = 0; j < agents_.size(); ++j) {
    if (agents_[j].robot->name() != robot) continue;
    const cf::FormationNodeDef& n = cfg_.robots[j].node;
    if (n.law == cf::FormationLaw::kRoot)
      throw std::runtime_error(robot + " is a root leader: it has no desired slot");
    const std::string key = "robots." + robot + ".follow.";
    const Pose2 p1 = agents_[links_[agents_[j].links[0]].leader].robot->pose();
    const Vec2 r = p - p1.p();
    std::vector<std::pair<std::string, std::string>> out = {{key + "l_des", FormatDouble(r.Norm())}};
    if (n.law == cf::FormationLaw::kLPhi) {
      out.push_back({key + "phi_des",
                     FormatDouble(control::WrapTo2Pi(std::atan2(r.y, r.x) - p1.theta))});
    } else {
      const Pose2 p2 = agents_[links_[agents_[j].links[1]].leader].robot->pose();
      out.push_back({key + "l2_des", FormatDouble((p - p2.p()).Norm())});
    }
    return out;
  }
  throw std::runtime_error("no robot '" + robot + "' in the formation");
}

}  // namespace formsim::sim::formation
