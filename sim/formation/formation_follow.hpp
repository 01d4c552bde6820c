#pragma once
/// \file A follower's `follow:` block, read and written in one place: the scenario reader
/// (ReadFollow), the formation editor's structural changes and the cascade generator
/// (WriteFollow) all go through here.
///
///   follow: {law: l_phi, leaders: [R1], l_des: 0.5, phi_des: 3.93, k_l: 0.15, k_phi: 0.08,
///            estimator: ukf, measure: [l, phi, alpha], noise: {...}}
///   follow: {law: l_l, leaders: [R1, R2], l_des: 0.5, l2_des: 0.5, k_l: 0.15, k_l2: 0.15}

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <vector>

#include "sim/formation/formation_config.hpp"

namespace formsim::sim::formation {

/// What formsim writes into a follow block.
struct FollowBlock {
  cf::FormationLaw law = cf::FormationLaw::kLPhi;  ///< kLPhi or kLL
  std::vector<std::string> leaders;                ///< one (l-φ) or two (l-l)
  double l_des = 0.0;                              ///< m (l-l: to the first leader)
  double second_des = 0.0;                         ///< l-φ: phi_des, rad; l-l: l2_des, m
  std::optional<double> k1, k2;                    ///< k_l and k_phi | k_l2, when given
  std::string estimator;                           ///< when not empty
  std::vector<std::string> measure;                ///< when not empty
};

/// Reads robot `r`'s follow block `f` strictly into its graph node and follower settings
/// (every gain, desired value, estimator and noise declared as a tunable).
void ReadFollow(YamlReader& f, FormationRobotDef& r);

/// Writes `block` into `follow` (an existing map keeps its other keys where they are, e.g.
/// gains, estimator and noise; anything else becomes a new map), in flow style: law, leaders,
/// l_des, phi_des | l2_des, then the gains, estimator and measure given. The other law's keys
/// (phi_des, k_phi or l2_des, k_l2) go. Numbers as FormatDouble writes them.
void WriteFollow(YAML::Node& follow, const FollowBlock& block);

/// The block on its own as one line of flow YAML ("{law: l_phi, leaders: [R1], ...}").
std::string FollowText(const FollowBlock& block);

}  // namespace formsim::sim::formation
