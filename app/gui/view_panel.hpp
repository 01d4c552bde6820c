#pragma once
/// \file The View panel: how the world view looks. The camera (fit, follow, zoom, whole run),
/// the grid and coordinates, the theme, the scene's overlays ("what the law sees") and the
/// legend, the help overlay (F1), presentation mode with its small bar, the UI scale and the
/// angle unit (both kept between runs in the settings file). The options themselves are the
/// window's (UiState): the world view, the plots and the tables read them. It registers
/// screenshot, present, frame-formation, theme, ui-scale, angle-unit, overlay, legend, follow,
/// fit, tab and help. View options are view-only: never recorded as edits.

#include <imgui.h>

#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"

namespace formsim::app {

class ViewPanel : public Panel {
 public:
  explicit ViewPanel(const PanelContext& ctx) : ctx_(ctx) {}
  /// screenshot (File menu), the View menu's rows, help (Help menu).
  static std::vector<Command> Rows();

  const char* Name() const override { return "View"; }
  /// The View section of the control panel.
  void Draw(const Fonts& fonts) override;
  /// The help overlay (keys and mouse) over the world view, between `min` and `max`.
  void DrawHelpOverlay(ImVec2 min, ImVec2 max);
  /// Presentation mode's small bar of buttons, top right of the world view.
  void DrawPresentationBar(ImVec2 min, ImVec2 max);

  /// Overlays of the scene: "NAME,..." as --overlay (all, none, default, -NAME), applied to the
  /// ones shown now.
  std::string CmdOverlay(const std::string& list);
  std::string CmdLegend(bool on);
  std::string CmdHelp(bool on);
  /// Presentation mode: panels hidden, the world view fills the window.
  std::string CmdPresent(bool on);
  /// UI scale (fonts and line widths) 1 ... 3, kept between runs.
  std::string CmdUiScale(double scale);
  /// Angles shown in degrees or radians ("deg" / "rad"), kept between runs.
  std::string CmdAngleUnit(const std::string& unit);

 private:
  void DrawOverlayToggles();
  void SaveSettings();
  const PanelContext& ctx_;
};

}  // namespace formsim::app
