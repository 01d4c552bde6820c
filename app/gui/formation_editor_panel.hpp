#pragma once
/// \file The formation kind's own panel, the Formation editor: add a follower (pick its leaders
/// in the world view, then where it goes), remove one, re-attach one to other leaders, switch
/// its law, drag desired slots, and named shapes in one click. The window creates it only when
/// the experiment exposes formation::FormationEditing (MakeKindPanel); it owns the editor's
/// state and registers the Formation menu's rows. Every change is a command of the session
/// (Session::Restructure, or live edits for a slot), checked by the scenario loader like a
/// file: a refused change is shown with its reason and the run goes on as it was.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"
#include "control/common/geometry.hpp"

namespace formsim::sim::formation {
struct StructureChange;
}  // namespace formsim::sim::formation

namespace formsim::app {

class FormationEditorPanel : public Panel {
 public:
  /// What a left click in the world view does.
  enum class EditMode { kOff, kAdd, kRemove, kAttach, kSwitchLaw, kSlots };

  explicit FormationEditorPanel(const PanelContext& ctx) : ctx_(ctx) {}
  /// The Formation menu's rows: editor, formation, shape, slot, click, switch-formation.
  static std::vector<Command> Rows();

  const char* Name() const override { return "Formation"; }
  /// The "Formation" section of the control panel (open while the editor is on).
  void Draw(const Fonts& fonts) override;
  bool Dismissable() const override { return mode_ != EditMode::kOff; }
  std::string Dismiss() override { return CmdEditor("off"); }
  bool WorldMouse(const View& view) override;
  /// A ring around each robot picked so far (and the follower whose slot is dragged).
  void DrawOverWorld(const sim::Experiment& shown, const View& view) override;

  /// A structural change of the formation (Session::Restructure): "add LAW LEADERS X Y
  /// [NAME]", "remove NAME", "attach NAME LAW LEADERS", "shape KIND [SPACING]".
  std::string CmdFormation(const std::string& command);
  /// The same change typed (the editor's clicks); recorded under its text form.
  std::string CmdFormationChange(const sim::formation::StructureChange& change);
  /// Puts `robot`'s desired slot (its control point) at world point (x, y): live edits of its
  /// l_des and φ_des, or of its two distances. `continues_drag`: one undo step per drag.
  std::string CmdSlot(const std::string& robot, double x, double y, bool continues_drag = false);
  /// The editor's mode: "off", "add l_phi|l_l", "remove", "attach l_phi|l_l", "law", "slots".
  std::string CmdEditor(const std::string& mode);
  /// A left click in the world view at world point `p` as the editor's mode takes it (the
  /// mouse and the script action `click X Y`).
  std::string EditorClick(Vec2 p);

  EditMode mode() const { return mode_; }

 private:
  /// Restructures the session by `restructure` (label: the change's text form) and reports.
  std::string RunRestructure(const std::string& label,
                             const std::function<std::string()>& restructure);
  /// The robot nearest world point `p` within a few pixels of its body ("" none).
  std::string RobotAt(Vec2 p, const View& view) const;

  const PanelContext& ctx_;
  EditMode mode_ = EditMode::kOff;
  int law_ = 0;                     ///< 0 l_phi, 1 l_l (add and attach)
  std::vector<std::string> picks_;  ///< robots picked so far (follower and/or leaders)
  int shape_index_ = 2;             ///< into control::formation::ShapeNames()
  float shape_spacing_ = 0.5f;      ///< m
  std::string slot_drag_;           ///< follower whose slot is being dragged
};

/// The experiment kind's own panel for the session's experiment, found by its capabilities
/// (the Formation editor for one exposing formation::FormationEditing), or null.
std::unique_ptr<Panel> MakeKindPanel(const PanelContext& ctx, const sim::Experiment& exp);
/// True when `panel` (may be null) is the kind panel MakeKindPanel would make for `exp`.
bool IsKindPanelFor(const Panel* panel, const sim::Experiment& exp);

}  // namespace formsim::app
