#pragma once
/// \file The formation kind's capability (Experiment::As<FormationEditing>()): structural
/// changes as typed commands, each follower's leaders and the live edits of a dragged slot. The
/// window's formation editor and menu, the `formation` script action and the tests use it; the
/// base Experiment knows nothing of formations.
///
/// A change has a text form, kept only at the edges (the `formation` script action, the session
/// record's `restructure` key, the undo text); names as in the scenario, LEADERS
/// comma-separated, coordinates in metres:
///   add LAW LEADERS X Y [NAME]   AddFollower
///   remove NAME                  RemoveRobot
///   attach NAME LAW LEADERS      AttachFollower
///   shape KIND [SPACING]         ApplyShape
/// What each does to the scenario text: sim/formation/formation_edit.hpp.

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "control/common/geometry.hpp"
#include "control/formation/formation_graph.hpp"
#include "control/formation/formation_shapes.hpp"
#include "sim/core/structure_editing.hpp"

namespace formsim::sim {
class Experiment;
class Session;
}  // namespace formsim::sim

namespace formsim::sim::formation {

/// A follower at (x, y), heading as its first leader, whose desired slot is where it is placed.
struct AddFollower {
  control::formation::FormationLaw law = control::formation::FormationLaw::kLPhi;
  std::vector<std::string> leaders;
  double x = 0.0, y = 0.0;  ///< m
  std::string name;         ///< empty: the next free "R<k>"
};
/// The robot goes (refused by the loader while others follow it).
struct RemoveRobot {
  std::string name;
};
/// New leaders and law for a follower; its desired slot is where it is now.
struct AttachFollower {
  std::string name;
  control::formation::FormationLaw law = control::formation::FormationLaw::kLPhi;
  std::vector<std::string> leaders;
};
/// The whole graph and slots of a named shape for the robots there are.
struct ApplyShape {
  control::formation::ShapeKind kind = control::formation::ShapeKind::kWedge;
  std::optional<double> spacing;  ///< m between neighbours; none: kDefaultShapeSpacing
};
/// Spacing of a shape when none is given, m.
inline constexpr double kDefaultShapeSpacing = 0.5;

/// One structural change of a formation.
struct StructureChange {
  std::variant<AddFollower, RemoveRobot, AttachFollower, ApplyShape> what;
};

/// The change's text form ("add l_phi R1 0.5 -0.3"; numbers as FormatDouble writes them).
std::string StructureChangeText(const StructureChange& change);
/// A change from its text form. Throws std::runtime_error naming what is wrong (unknown
/// command, law or shape, missing words, malformed numbers).
StructureChange ParseStructureChange(const std::string& text);

/// What a formation experiment can do beyond every kind.
class FormationEditing : public StructureEditing {
 public:
  /// The scenario `text` with `change` applied and every robot that stays placed where it is
  /// now. Throws std::runtime_error naming what is wrong (unknown robot, bad spacing...).
  virtual std::string Restructured(const std::string& text,
                                   const StructureChange& change) const = 0;
  /// Why no structural change can apply to this scenario ("" when they can): the window greys
  /// out its structural commands with it, and Restructured refuses with it.
  virtual std::string StructureLocked() const { return ""; }
  /// The leaders `robot` follows, in order (none for a root or an unknown robot).
  virtual std::vector<std::string> LeadersOf(const std::string& robot) const = 0;
  /// The tunable edits (key, value) that put `robot`'s desired place at world point `p`,
  /// measured from the state now (a slot dragged in the world view). Throws
  /// std::runtime_error with the reason (not a follower, unknown robot).
  virtual std::vector<std::pair<std::string, std::string>> SlotEdits(const std::string& robot,
                                                                     Vec2 p) const = 0;
};

/// The formation capability of `exp`, or null when its kind has none.
const FormationEditing* EditingOf(const Experiment& exp);

/// Applies `change` to the formation of the session's run (Session::Restructure), recorded
/// under its text form. Returns "" or why it was refused (then nothing changed).
std::string Restructure(Session& session, const StructureChange& change,
                        const std::string& origin = "GUI edit");
/// The same from the text form (the `formation` script action): the text is what the record
/// keeps; an empty text only places the robots where they are now.
std::string Restructure(Session& session, const std::string& command,
                        const std::string& origin = "GUI edit");

}  // namespace formsim::sim::formation
