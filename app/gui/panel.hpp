#pragma once
/// \file One panel of the window: it owns its state, draws itself where the window's layout
/// puts it and registers its command rows (each panel class has a static `Rows()`; the one
/// table is assembled from them in app/gui/command_rows.cpp). The window (AppUi) creates the
/// panels, hands each the shared context (app/gui/panel_context.hpp: the session and its
/// record, the view options and theme, the status line, the command runner, ReplaceRun, the
/// other panels) and wires them into its layout; it owns no panel's state.
///
/// The panels: Scenario, Run, Parameters, View, Plots, Tables, Compare, History, Timeline,
/// Lesson (app/gui/*_panel.hpp), and the Formation editor (app/gui/formation_editor_panel.hpp,
/// the formation kind's own panel, created only when the experiment exposes
/// formation::FormationEditing). docs/architecture.md has a table of what each owns.

#include <string>

namespace formsim::sim {
class Experiment;
}  // namespace formsim::sim

namespace formsim::app {

struct Fonts;
struct View;

class Panel {
 public:
  virtual ~Panel() = default;
  /// The panel's name ("Formation", "Lesson").
  virtual const char* Name() const = 0;
  /// Draws the panel where the window's layout puts it (a section of the control panel, a tab).
  virtual void Draw(const Fonts& fonts) = 0;
  /// True while the panel has something open that Esc (`dismiss`) closes.
  virtual bool Dismissable() const { return false; }
  /// Closes what Dismissable() says is open: "" or why it was refused.
  virtual std::string Dismiss() { return ""; }
  /// The world view's mouse in an interactive frame (the view's item is the last ImGui item):
  /// true when the panel took the left button (then the window's own picking and dragging
  /// leave it alone).
  virtual bool WorldMouse(const View& view) {
    (void)view;
    return false;
  }
  /// Marks the panel draws over the world view, after the scene, into the current window.
  virtual void DrawOverWorld(const sim::Experiment& shown, const View& view) {
    (void)shown;
    (void)view;
  }
};

}  // namespace formsim::app
