#pragma once
/// \file Named formation shapes for N robots (column, line abreast, wedge, diamond, V, grid):
/// the desired slots in the root's frame and a graph that holds them, every l-l triangle kept
/// well away from the triangle condition's limits.
///
/// Slots are robot centres in the root's frame (x forward, y left, every heading 0), R1 (the
/// root) at the origin, neighbours `spacing` apart. The graph is built front to back: every
/// robot after the second is l-l to the two robots already placed that give the best-shaped
/// triangle (both distances within 2·spacing, |sin| of the apex angle ≥ kMinApexSin, the
/// triangle inequality held with a slack of kMinTriangleSlack·separation); when no pair
/// qualifies (the second robot, a column) it is l-φ to the nearest robot ahead. The l-l law
/// places a follower from its leaders' positions only, so deep shapes do not amplify heading
/// disturbances as chains of l-φ links do (see sim/formation/cascade_generator.hpp).

#include <string>
#include <vector>

#include "control/formation/formation_graph.hpp"

namespace formsim::control::formation {

/// Shapes offered by name.
enum class ShapeKind { kColumn, kLineAbreast, kWedge, kDiamond, kV, kGrid };

/// "column", "line_abreast", "wedge", "diamond", "v", "grid", in ShapeKind order.
const std::vector<std::string>& ShapeNames();
/// The kind named `name`; false when there is none.
bool ShapeFromName(const std::string& name, ShapeKind* kind);

/// l-l triangles of generated shapes: the least |sin| of the angle at the follower's control
/// point, and the least slack of the triangle inequality as a fraction of the leaders'
/// separation.
constexpr double kMinApexSin = 0.45;
constexpr double kMinTriangleSlack = 0.1;

/// A generated shape: one node per robot (names R1 ... as given), slots in the root's frame.
struct FormationShape {
  std::vector<FormationNodeDef> nodes;  ///< law, leaders, l_des, phi_des, l2_des, L
  std::vector<Vec2> slots;              ///< robot centres in the root's frame, m
};

/// The slots of `kind` for `n` robots (n ≥ 1) `spacing` apart, front to back.
std::vector<Vec2> ShapeSlots(ShapeKind kind, int n, double spacing);

/// The shape with its graph for the robots `names` (the first is the root), control point
/// offset `L`. Every node's initial_pose is its slot (heading 0), so BuildFormationGraph of the
/// result reproduces `slots`. Throws std::invalid_argument for no robots or spacing ≤ 2 L.
FormationShape MakeFormationShape(ShapeKind kind, const std::vector<std::string>& names,
                                  double spacing, double L);

/// The graph for given slots (front to back, slot 0 the root) as described in the file comment.
FormationShape GraphForSlots(const std::vector<Vec2>& slots, const std::vector<std::string>& names,
                             double L);

}  // namespace formsim::control::formation
