#pragma once
/// \file The formsim user interface, drawn with ImGui the same way in the GLFW window and in
/// headless `--ui` frames: panels Scenario, Run, Parameters (generic, from the ParamTable),
/// View, Plots, Tables and Summary around the world view. Knows nothing of GLFW or GL.

#include <imgui.h>

#include <memory>
#include <string>
#include <vector>

#include "app/fonts.hpp"
#include "app/session.hpp"
#include "app/view.hpp"

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
  std::vector<char> plot_open;  ///< per figure (char: vector<bool> has no data())
  bool screenshot_requested = false;
  std::string status;  ///< last message for the status line
  char save_path[512] = "";
  char open_path[512] = "";
  long long seed_input = 1;
  std::string drag_name;  ///< robot or obstacle being dragged
  double sim_ms = 0, frame_ms = 0;
  int steps_last_frame = 0;
  double step_budget = 0;  ///< simulated seconds owed to real time
};

class AppUi {
 public:
  explicit AppUi(std::unique_ptr<Session> session);
  /// Borrows a session owned by the caller (headless --ui frames); Open() then takes ownership
  /// of any newly loaded one.
  explicit AppUi(Session& borrowed);

  Session& session() { return *session_; }
  UiState& state() { return state_; }

  /// Advances the simulation for `wall_dt` seconds of real time at the chosen speed (GUI loop).
  void Advance(double wall_dt);
  /// Builds all windows for a display of `display` pixels. `interactive` = false draws the same
  /// panels without reading mouse or keyboard (headless --ui frames).
  void Draw(ImVec2 display, const Fonts& fonts, bool interactive);
  /// With "whole run" on, adds the experiment's current bounds to the camera's union (headless
  /// runs that draw only a final snapshot call this while stepping).
  void TrackBounds();
  /// Loads another scenario file (keeps the view options). Errors go to the status line.
  void Open(const std::string& file);

 private:
  void HandleKeys();
  void DrawControlPanel(const Fonts& fonts, bool interactive);
  void DrawScenarioSection();
  void DrawRunSection();
  void DrawViewSection();
  void DrawParamSection();
  void DrawMessagesSection();
  void DrawWorldWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts, bool interactive);
  void DrawWorldMouse(const View& view);
  void DrawPlotsWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts);
  void UpdateView(ImVec2 min, ImVec2 max);

  std::unique_ptr<Session> owned_;
  Session* session_ = nullptr;
  UiState state_;
  std::vector<std::string> shipped_;
  int shipped_index_ = 0;
  bool confirm_overwrite_ = false;
  AutoFit auto_fit_;
};

}  // namespace formsim::app
