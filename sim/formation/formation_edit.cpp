#include "sim/formation/formation_edit.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "control/common/angle.hpp"
#include "control/formation/formation_shapes.hpp"
#include "control/formation/link_kinematics.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/yaml_reader.hpp"
#include "sim/formation/formation_experiment.hpp"

namespace formsim::sim::formation {
namespace {

namespace cf = control::formation;

constexpr double kDefaultSpacing = 0.5;  // m, between neighbours of a generated shape

[[noreturn]] void Fail(const std::string& why) { throw std::runtime_error(why); }

std::vector<std::string> Words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::vector<std::string> SplitNames(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s + ",") {
    if (c == ',') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  return out;
}

double Number(const std::string& s, const std::string& what) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || !std::isfinite(v)) Fail(what + " must be a number, got '" + s + "'");
  return v;
}

YAML::Node Num(double v) { return YAML::Node(FormatDouble(v + 0.0)); }

YAML::Node PoseNode(const Pose2& p) {
  YAML::Node n(YAML::NodeType::Sequence);
  n.push_back(Num(p.x));
  n.push_back(Num(p.y));
  n.push_back(Num(control::WrapToPi(p.theta)));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

YAML::Node NamesNode(const std::vector<std::string>& names) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (const auto& s : names) n.push_back(s);
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

cf::FormationLaw Law(const std::string& s) {
  if (s == "l_phi") return cf::FormationLaw::kLPhi;
  if (s == "l_l") return cf::FormationLaw::kLL;
  Fail("law must be l_phi (one leader) or l_l (two leaders), got '" + s + "'");
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
  const std::size_t want = law == cf::FormationLaw::kLPhi ? 1 : 2;
  if (leaders.size() != want)
    Fail(std::string(law == cf::FormationLaw::kLPhi ? "law l_phi" : "law l_l") + " needs " +
         std::to_string(want) + " leader" + (want == 1 ? "" : "s") + ", got " +
         std::to_string(leaders.size()));
  YAML::Node f = robot["follow"];
  if (!f || !f.IsMap()) f = YAML::Node(YAML::NodeType::Map);
  robot.remove("schedule");
  f["law"] = law == cf::FormationLaw::kLPhi ? "l_phi" : "l_l";
  f["leaders"] = NamesNode(leaders);
  const Pose2& p1 = PoseOf(st, leaders[0]);
  const Vec2 r = m - p1.p();
  f["l_des"] = Num(r.Norm());
  if (law == cf::FormationLaw::kLPhi) {
    f.remove("l2_des");
    f.remove("k_l2");
    f["phi_des"] = Num(control::WrapTo2Pi(std::atan2(r.y, r.x) - p1.theta));
  } else {
    f.remove("phi_des");
    f.remove("k_phi");
    f["l2_des"] = Num((m - PoseOf(st, leaders[1]).p()).Norm());
  }
  f.SetStyle(YAML::EmitterStyle::Flow);
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

void ApplyShape(YAML::Node robots, const std::vector<std::string>& w, const FormationState& st) {
  cf::ShapeKind kind;
  if (w.size() < 2 || !cf::ShapeFromName(w[1], &kind)) {
    std::string names;
    for (const auto& n : cf::ShapeNames()) names += (names.empty() ? "" : ", ") + n;
    Fail("shape: name one of " + names);
  }
  const double spacing = w.size() > 2 ? Number(w[2], "shape spacing") : kDefaultSpacing;
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
  const cf::FormationShape shape = cf::MakeFormationShape(kind, names, spacing, st.L);
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

}  // namespace

std::string RestructureFormationText(const std::string& text, const std::string& command,
                                     const FormationState& st) {
  YAML::Node root;
  try {
    root = LoadYamlText(text, "the scenario text");  // aliases and nesting bounded
  } catch (const std::exception& e) {
    Fail(std::string("the scenario text does not parse: ") + e.what());
  }
  YAML::Node robots = root["robots"];
  if (!robots || !robots.IsSequence()) Fail("the scenario has no robots list");
  // The robots stay where they are now (written first: a command may place some elsewhere).
  if (st.carry_poses)
    for (std::size_t i = 0; i < robots.size(); ++i) {
      const auto it = st.poses.find(NameOf(robots[i]));
      if (it != st.poses.end()) robots[i]["pose"] = PoseNode(it->second);
    }
  const std::vector<std::string> w = Words(command);
  if (w.empty()) {
    // Only the poses.
  } else if (w[0] == "add") {
    if (w.size() < 5 || w.size() > 6) Fail("add LAW LEADERS X Y [NAME]");
    const cf::FormationLaw law = Law(w[1]);
    const std::vector<std::string> leaders = SplitNames(w[2]);
    for (const auto& l : leaders)
      if (Find(robots, l) < 0) Fail("leader '" + l + "' is not a robot of this scenario");
    const std::string name = w.size() == 6 ? w[5] : NextName(robots);
    if (Find(robots, name) >= 0) Fail("a robot named '" + name + "' exists already");
    const Pose2 p{Number(w[3], "x"), Number(w[4], "y"), leaders.empty() ? 0.0 : PoseOf(st, leaders[0]).theta};
    YAML::Node robot(YAML::NodeType::Map);
    robot["name"] = name;
    robot["pose"] = PoseNode(p);
    FormationState with = st;
    with.poses[name] = p;
    SetFollow(robot, law, leaders, cf::ControlPoint(p, st.L), with);
    robots.push_back(robot);
  } else if (w[0] == "remove") {
    if (w.size() != 2) Fail("remove NAME");
    const int i = Find(robots, w[1]);
    if (i < 0) Fail("no robot '" + w[1] + "' in the formation");
    if (robots.size() == 1) Fail("the last robot cannot be removed");
    YAML::Node kept(YAML::NodeType::Sequence);
    for (std::size_t k = 0; k < robots.size(); ++k)
      if (static_cast<int>(k) != i) kept.push_back(robots[k]);
    root["robots"] = kept;
  } else if (w[0] == "attach") {
    if (w.size() != 4) Fail("attach NAME LAW LEADERS");
    const int i = Find(robots, w[1]);
    if (i < 0) Fail("no robot '" + w[1] + "' in the formation");
    const std::vector<std::string> leaders = SplitNames(w[3]);
    for (const auto& l : leaders)
      if (Find(robots, l) < 0) Fail("leader '" + l + "' is not a robot of this scenario");
    SetFollow(robots[i], Law(w[2]), leaders, cf::ControlPoint(PoseOf(st, w[1]), st.L), st);
  } else if (w[0] == "shape") {
    ApplyShape(robots, w, st);
  } else {
    Fail("unknown formation command '" + w[0] + "' (add, remove, attach, shape)");
  }
  YAML::Emitter out;
  out.SetIndent(2);
  out << root;
  if (!out.good()) Fail(std::string("the edited scenario cannot be written: ") + out.GetLastError());
  return Header(text) + out.c_str() + "\n";
}

std::string FormationExperiment::RestructuredText(const std::string& text,
                                                  const std::string& command) const {
  FormationState st;
  st.L = cfg_.L;
  st.carry_poses = steps() > 0;
  for (const Agent& a : agents_) st.poses[a.robot->name()] = a.robot->pose();
  return RestructureFormationText(text, command, st);
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
