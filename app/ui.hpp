#pragma once
/// \file The formsim user interface, drawn with ImGui the same way in the GLFW window and in
/// headless `--ui` frames: panels Scenario, Run, Parameters (generated from the scenario's
/// ParamTable), View, Plots, Tables and Summary around the world view. Knows nothing of GLFW or
/// GL. Every user action is a command (Cmd*) called alike by buttons, keys and `--script`.

#include <imgui.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "app/fonts.hpp"
#include "app/theme.hpp"
#include "app/view.hpp"
#include "sim/core/session.hpp"

namespace formsim::app {

/// Speeds offered by the Run panel; 0 means as fast as possible.
const std::vector<double>& SpeedChoices();

/// State of the interface that is not simulation state.
struct UiState {
  bool playing = true;
  int speed_index = 3;  ///< into SpeedChoices(), 3 = 1x
  View view;
  bool auto_fit = true;    ///< keep everything in view until the user pans or zooms
  bool whole_run = false;  ///< auto-fit shows everything since the start (else: tracks)
  bool fit_now = true;
  int follow = -1;  ///< robot index to follow, -1 none
  bool grid = true;
  bool coordinates = true;
  ThemeId theme = ThemeId::kLight;          ///< colours of the panels, the world view and the plots
  std::map<std::string, bool> plot_closed;  ///< figure id -> hidden by the user
  bool screenshot_requested = false;
  std::string screenshot_path;  ///< where the requested screenshot goes ("" = numbered name)
  std::string status;           ///< last message for the status line
  bool status_is_error = false;
  char save_path[512] = "";
  char open_path[512] = "";
  char seed_text[32] = "";
  std::string drag_name;  ///< robot or obstacle being dragged
  double sim_ms = 0, frame_ms = 0;
  int steps_last_frame = 0;
  double step_budget = 0;  ///< simulated seconds owed to real time
};

class AppUi {
 public:
  explicit AppUi(std::unique_ptr<sim::Session> session);
  /// Borrows a session owned by the caller (headless --ui frames); loading another scenario
  /// then makes the interface own the new one.
  explicit AppUi(sim::Session& borrowed);

  sim::Session& session() { return *session_; }
  /// Applied to every experiment of every session the interface runs (the current one, resets,
  /// and scenarios loaded later): bounded history, streaming of the rows to --out.
  void SetRunSetup(std::function<void(sim::Experiment&)> setup);
  UiState& state() { return state_; }

  /// Advances the simulation for `wall_dt` seconds of real time at the chosen speed (GUI loop).
  void Advance(double wall_dt);
  /// Builds all windows for a display of `display` pixels. `interactive` = false draws the same
  /// panels without reading mouse or keyboard (headless --ui frames).
  void Draw(ImVec2 display, const Fonts& fonts, bool interactive);
  /// With "whole run" on, adds the experiment's current bounds to the camera's union (headless
  /// runs that draw only a final snapshot call this while stepping).
  void TrackBounds();

  // ---- Commands: what buttons, keys and scripts do. Each returns "" or why it was refused,
  // and leaves a message in the status line. None of them can end the program.
  std::string CmdPlay();
  std::string CmdPause();
  std::string CmdStep();
  std::string CmdReset();
  /// Reset with a seed given as text (0 ... 2^64 - 1).
  std::string CmdResetSeed(const std::string& seed_text);
  /// Re-reads the current file from disk (tuned values are dropped).
  std::string CmdReload();
  /// Loads a shipped scenario by name, or a path.
  std::string CmdLoad(const std::string& name_or_path);
  /// Opens a scenario file by path.
  std::string CmdOpen(const std::string& path);
  /// Saves the tuned scenario; without `overwrite` an existing file asks for confirmation.
  std::string CmdSave(const std::string& path, bool overwrite);
  std::string CmdEdit(const std::string& key, const std::string& value);
  std::string CmdAction(const std::string& id);
  /// Asks for a screenshot of the next frame (the window writes it).
  std::string CmdScreenshot(const std::string& path);
  /// Runs one script action "ACTION [ARGS]" (see `formsim gui --script`). Returns "" or the
  /// reason it was refused.
  std::string RunScriptAction(const std::string& line);

 private:
  void HandleKeys();
  void SetStatus(const std::string& message, bool error = false);
  /// Replaces the session after a successful load (keeps view options, resets per-run state).
  void Adopt(std::unique_ptr<sim::Session> session, const std::string& message);
  void SyncScenarioFields();
  void DrawControlPanel(const Fonts& fonts, bool interactive);
  void DrawScenarioSection();
  void DrawRunSection();
  void DrawViewSection();
  void DrawParamSection();
  void DrawMessagesSection();
  void DrawWorldWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts, bool interactive);
  void DrawWorldMouse(const View& view);
  void DrawPlotsWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts);
  /// What the plots window shows, refreshed at most ten times a second (app/ui_plots.cpp).
  struct PlotsCache;
  std::shared_ptr<PlotsCache> plots_cache_;
  void UpdateView(ImVec2 min, ImVec2 max);

  std::function<void(sim::Experiment&)> run_setup_;
  std::unique_ptr<sim::Session> owned_;
  sim::Session* session_ = nullptr;
  UiState state_;
  std::vector<std::string> shipped_;
  int shipped_index_ = 0;
  bool confirm_overwrite_ = false;
  AutoFit auto_fit_;
};

}  // namespace formsim::app
