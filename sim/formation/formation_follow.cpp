#include "sim/formation/formation_follow.hpp"

#include <stdexcept>

#include "sim/core/number_format.hpp"

namespace formsim::sim::formation {
namespace {

YAML::Node Num(double v) {
  return YAML::Node(FormatDouble(v + 0.0));
}

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
  follow["l_des"] = Num(b.l_des);
  follow.remove(lphi ? "l2_des" : "phi_des");
  follow.remove(lphi ? "k_l2" : "k_phi");
  follow[lphi ? "phi_des" : "l2_des"] = Num(b.second_des);
  if (b.k1) follow["k_l"] = Num(*b.k1);
  if (b.k2) follow[lphi ? "k_phi" : "k_l2"] = Num(*b.k2);
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
