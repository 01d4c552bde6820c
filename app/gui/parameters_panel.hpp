#pragma once
/// \file The Parameters panel: every tunable of the scenario's ParamTable (declared once, where
/// the scenario reader reads it) grouped by its group path, with the experiment's action
/// buttons; the value entry that a double-click, Ctrl+click or the palette opens on a number
/// (applied on Enter only, refused with the loader's reason); undo and redo of edits. Widgets
/// never write the experiment: they ask the session for an edit, checked against the whole
/// scenario and applied between steps. It owns the value entry and the tunable the palette asked
/// for, and registers edit, revert, the field-* actions, action, undo and redo.

#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"
#include "app/gui/value_entry.hpp"

namespace formsim::sim {
struct Param;
struct ActionSpec;
}  // namespace formsim::sim

namespace formsim::app {

class ParametersPanel : public Panel {
 public:
  explicit ParametersPanel(const PanelContext& ctx) : ctx_(ctx) {}
  /// edit, revert, field-open/type/enter/escape/wheel, action (Run menu).
  static std::vector<Command> Rows();
  /// undo, redo (Compare menu; in the table after the History panel's rows).
  static std::vector<Command> UndoRows();

  const char* Name() const override { return "Parameters"; }
  /// The tunables' sections of the control panel.
  void Draw(const Fonts& fonts) override;

  /// `continues_drag`: the same slider is still held since its last edit (one undo step).
  std::string CmdEdit(const std::string& key, const std::string& value,
                      bool continues_drag = false);
  /// Runs an action the scenario offers (between two steps).
  std::string CmdAction(const std::string& id);
  /// Undo / redo the last edit (Ctrl+Z / Ctrl+Y), through the normal edit path.
  std::string CmdUndo();
  std::string CmdRedo();
  /// Edits `key` back to its value in the file (with the command line's --set).
  std::string CmdRevert(const std::string& key);
  /// The value entry of tunable `key` (a number), as a double-click on its slider opens it: its
  /// section opens and the field takes the keyboard on the next frame.
  std::string CmdFieldOpen(const std::string& key);
  /// Types `text` into the open field, character by character as the keyboard does (through
  /// ImGui's input queue: taken by the field that has the keyboard in the next frame).
  std::string CmdFieldType(const std::string& text);
  /// Enter (`commit`: the text typed is applied, or refused with the loader's reason and the
  /// field stays open, red) or Esc (closed, nothing applied) in the open field.
  std::string CmdFieldKey(bool commit);
  /// `steps` notches of the mouse wheel over tunable `key`'s slider (a fine adjustment).
  std::string CmdFieldWheel(const std::string& key, int steps);

  /// Opens the way to tunable `key`'s field on the next frame and gives it the keyboard (the
  /// palette).
  void Focus(const std::string& key) { focus_param_ = key; }
  /// A tunable asked for by Focus() has not been drawn yet.
  bool FocusPending() const { return !focus_param_.empty(); }
  /// The value entry was drawn this frame (its keys are not shortcuts).
  bool EntryDrawnThisFrame() const { return value_entry_.DrawnThisFrame(); }
  /// The key whose value entry is open ("" none).
  const std::string& EntryKey() const { return value_entry_.key(); }
  /// Another scenario: the open field closes.
  void Clear() { value_entry_.Close(); }

 private:
  /// The tunables and actions grouped as the panel shows them: heads in order of first
  /// appearance, each with its sub-groups likewise. Rebuilt only when the groups change (a
  /// thousand robots declare tens of thousands of tunables; grouping them anew each frame took
  /// most of the panel's 3 ms).
  struct Grouping {
    struct Sub {
      std::string tail, group, label, table_id;  ///< label: the tree node's ("" for none)
      std::vector<std::size_t> params, actions;  ///< indices into the tables drawn from
      mutable unsigned id = 0, id_seed = 0;      ///< the tree node's ImGuiID and its seed
    };
    struct Head {
      std::string head, header;  ///< header: the collapsing header's label
      std::vector<Sub> subs;
    };
    std::uint64_t params_revision = 0;       ///< the tunables' table it was built from
    std::vector<std::string> action_groups;  ///< and the actions' groups
    std::vector<Head> heads;
  };
  /// grouping_, rebuilt when the tunables' table (its revision) or the actions' groups differ
  /// from what it was built from.
  const Grouping& Groups(const sim::ParamTable& table, const std::vector<sim::ActionSpec>& actions);

  const PanelContext& ctx_;
  Grouping grouping_;
  /// The height a closed sub-group's row takes (spacing included) at a font size, as last
  /// measured: rows far outside the view are left out as a gap of that height.
  struct ClosedRow {
    float font_size = 0.0f, step = 0.0f;
  } closed_row_;
  std::string focus_param_;  ///< a tunable whose field takes the keyboard once
  ValueEntry value_entry_;   ///< the tunable whose value is being typed
};

}  // namespace formsim::app
