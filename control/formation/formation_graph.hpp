#pragma once
/// \file A formation as a graph: every robot is a root leader (open-loop schedule) or a follower
/// with the l-φ law (one leader) or the l-l law (two leaders), in any cascade depth.
/// BuildFormationGraph validates the graph and orders it so that every robot comes after its
/// leaders (followers then use their leaders' commands of the same step).

#include <stdexcept>
#include <string>
#include <vector>

#include "control/common/geometry.hpp"
#include "control/formation/formation_laws.hpp"

namespace formsim::control::formation {

enum class FormationLaw { kRoot, kLPhi, kLL };

/// A follower law's name in scenarios (`follow: {law: ...}`), results, the editor and the
/// `formation` commands: "l_phi" or "l_l" ("root" for a root leader).
const char* LawName(FormationLaw law);
/// The follower laws' names in FormationLaw order (l_phi, l_l): the scenario reader's choices.
const std::vector<std::string>& FollowerLawNames();
/// The follower law called `name` (l_phi or l_l). False for any other text (kRoot included).
bool ParseLaw(const std::string& name, FormationLaw* law);
/// Leaders a law takes: none (root), one (l-φ) or two (l-l).
std::size_t LeadersOfLaw(FormationLaw law);

/// One robot of a formation as far as the graph is concerned.
struct FormationNodeDef {
  std::string name;
  FormationLaw law = FormationLaw::kRoot;
  std::vector<std::string> leaders;  ///< names: none (root), one (l-φ) or two (l-l)
  double l_des = 0.3;                ///< l-φ: l; l-l: l to the first leader, m
  double phi_des = 5.0 * kPi / 4.0;  ///< l-φ only, rad
  double l2_des = 0.3;               ///< l-l only: l to the second leader, m
  double L = 0.15;                   ///< control point offset, m
  Pose2 initial_pose;                ///< used to pick the side of l-l triangles
};

/// A graph error located at a robot and one of its keys ("leaders", "l_des", "L", ...).
class FormationGraphError : public std::runtime_error {
 public:
  FormationGraphError(int robot, std::string key, const std::string& message)
      : std::runtime_error(message), robot_(robot), key_(std::move(key)) {}
  int robot() const { return robot_; }
  const std::string& key() const { return key_; }

 private:
  int robot_;
  std::string key_;
};

/// A validated formation.
struct FormationGraph {
  std::vector<int> order;                 ///< robot indices, leaders before followers
  std::vector<std::vector<int>> leaders;  ///< per robot: indices of its leaders
  std::vector<int> depth;                 ///< 0 for roots, 1 + max(depth of leaders) otherwise
  std::vector<int> root;                  ///< the root whose tree fixes the robot's desired place
                                          ///< (-1 when its leaders come from different roots)
  /// Desired position of each robot in its root's frame with every heading 0 (the steady
  /// straight-line formation); meaningful only when root[i] >= 0.
  std::vector<Vec2> shape;
  /// l-l followers: +1 when the control point sits left of the line first leader → second
  /// leader at the initial poses, −1 right.
  std::vector<int> side;
};

/// Validates and orders a formation. Throws FormationGraphError (robot index, key, message) for:
/// a non-positive L or desired distance, a wrong number of leaders for the law, a self-loop, a
/// leader listed twice, a missing leader, a cycle, and an l-l follower whose desired distances
/// cannot form a triangle with its leaders' desired separation (or one whose desired triangle is
/// within the singular band |sin| < singular_threshold).
FormationGraph BuildFormationGraph(const std::vector<FormationNodeDef>& nodes,
                                   double singular_threshold);

/// Desired control point of an l-l follower: the intersection of the circles of radius l1 around
/// p1 and l2 around p2 on `side` (+1 left of p1 → p2). Returns false when they do not intersect.
bool TriangleApex(const Vec2& p1, const Vec2& p2, double l1, double l2, int side, Vec2& apex);

}  // namespace formsim::control::formation
