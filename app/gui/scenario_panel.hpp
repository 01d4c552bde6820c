#pragma once
/// \file The Scenario panel: which scenario runs, and its file. It shows the scenario's name
/// and description, offers the shipped scenarios and lessons, opens a file by path (the current
/// run stays when the file cannot be read), reloads it from disk, and saves the tuned scenario
/// (the file's own text with only the changed values rewritten; an existing file asks first
/// unless a script saves). It owns the list, the path fields and the overwrite question, and
/// registers open, load, reload, save and save-as. Replacing the session is the window's
/// (PanelContext::adopt).

#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"

namespace formsim::app {

class ScenarioPanel : public Panel {
 public:
  explicit ScenarioPanel(const PanelContext& ctx);
  /// open, load, reload, save, save-as (File menu).
  static std::vector<Command> Rows();

  const char* Name() const override { return "Scenario"; }
  /// The Scenario section of the control panel.
  void Draw(const Fonts& fonts) override;

  /// Loads a shipped scenario by name, or a path.
  std::string CmdLoad(const std::string& name_or_path);
  /// Opens a scenario file by path.
  std::string CmdOpen(const std::string& path);
  /// Re-reads the current file from disk (tuned values are dropped).
  std::string CmdReload();
  /// Saves the tuned scenario; without `overwrite` an existing file asks for confirmation.
  std::string CmdSave(const std::string& path, bool overwrite);
  /// After a load or reload: the list's entry and the path fields follow the session's file.
  void SyncScenario();

 private:
  const PanelContext& ctx_;
  std::vector<std::string> shipped_;  ///< the shipped scenarios, then the lessons
  int shipped_index_ = -1;            ///< the loaded file's entry, -1: a file of the user's
  char open_path_[512] = "";
  char save_path_[512] = "";
  bool confirm_overwrite_ = false;  ///< Save found the file there: ask before overwriting
};

}  // namespace formsim::app
