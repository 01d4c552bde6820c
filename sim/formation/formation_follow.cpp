#include "sim/formation/formation_follow.hpp"

#include <stdexcept>

#include "sim/core/number_format.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim::formation {
namespace {

YAML::Node FlowList(const std::vector<std::string>& items) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (const auto& s : items) n.push_back(s);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

}  // namespace

void WriteFollow(YAML::Node& follow, const FollowBlock& b) {
  if (!follow || !follow.IsMap()) follow = YAML::Node(YAML::NodeType::Map);
  const bool lphi = b.law == cf::FormationLaw::kLPhi;
  follow["law"] = cf::LawName(b.law);
  follow["leaders"] = FlowList(b.leaders);
  follow["l_des"] = NumberNode(b.l_des);
  follow.remove(lphi ? "l2_des" : "phi_des");
  follow.remove(lphi ? "k_l2" : "k_phi");
  follow[lphi ? "phi_des" : "l2_des"] = NumberNode(b.second_des);
  if (b.k1) follow["k_l"] = NumberNode(*b.k1);
  if (b.k2) follow[lphi ? "k_phi" : "k_l2"] = NumberNode(*b.k2);
  if (!b.estimator.empty()) follow["estimator"] = b.estimator;
  if (!b.measure.empty()) follow["measure"] = FlowList(b.measure);
  follow.SetStyle(YAML::EmitterStyle::Flow);
}

std::string FollowText(const FollowBlock& block) {
  YAML::Node n;
  WriteFollow(n, block);
  YAML::Emitter out;
  out << n;
  if (!out.good())
    throw std::runtime_error("a follow block cannot be written: " + out.GetLastError());
  return out.c_str();
}

}  // namespace formsim::sim::formation
