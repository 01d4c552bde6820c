#pragma once
/// \file One frame of the window, shared by the desktop window (`formsim gui`, a loop around
/// Frame()) and the browser page (app/web/, a callback the browser calls once per animation
/// frame): script actions, the UI build, drawing, screenshots, the title and --timing.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "app/gui/gui.hpp"
#include "app/render/imgui_layer.hpp"

struct GLFWwindow;

namespace formsim::sim {
class Session;
}

namespace formsim::app {

class AppUi;

class GuiLoop {
 public:
  /// The window's GL context must be current and loaded (LoadGl). `scripted` is sorted by frame.
  GuiLoop(GLFWwindow* window, std::unique_ptr<sim::Session> session, const GuiOptions& opt,
          std::vector<ScriptAction> scripted);
  ~GuiLoop();
  GuiLoop(const GuiLoop&) = delete;
  GuiLoop& operator=(const GuiLoop&) = delete;

  /// Draws one frame (the caller polls the events first). Returns false when the window should
  /// end: --exit-after reached, --exit-when-finished and finished, or `quit`.
  bool Frame();

  /// Queues an action to run before the next frame, after the ones already queued (the page's
  /// entry point). Returns a ticket for Result().
  int Queue(const std::string& action, const std::string& where);
  /// The outcome of a queued action: nullptr until it ran (a `wait`: until the background work
  /// is done; a screenshot: until its file is written), then "" or the refusal text.
  const std::string* Result(int ticket) const;

  AppUi& ui() { return *ui_; }
  long frames() const { return frames_; }
  /// 4 when a --screenshot asked for on the command line could not be written.
  int exit_code() const { return exit_code_; }
  /// The --timing statistics line (empty with fewer than 11 frames).
  std::string TimingReport() const;

 private:
  void RunDueActions();
  void TakeScreenshot(bool last_frame, bool finished_exit);

  GLFWwindow* window_;
  GuiOptions opt_;
  std::vector<ScriptAction> scripted_;
  std::vector<int> tickets_;  ///< parallel to scripted_: 0 for the command line's actions
  std::map<int, std::string> results_;
  std::vector<int> ran_this_frame_;  ///< tickets whose result is set at the end of the frame
  int next_ticket_ = 1;
  int waiting_ticket_ = 0;  ///< the `wait` holding the script
  ImGuiLayer layer_;
  bool backend_ = false;  ///< the GLFW platform backend is initialised
  std::unique_ptr<AppUi> ui_;
  std::size_t next_action_ = 0;
  long clock_ = 0;  ///< script time: stands still while a `wait` holds the script
  long frames_ = 0;
  bool holding_ = false;
  bool swap_pending_ = false;  ///< a rendered frame waits for glfwSwapBuffers
  bool f1_down_ = false;
  int shot_counter_ = 0;
  std::string shot_where_;
  std::string title_shown_;
  double last_ = 0;  ///< the previous frame's start (steady clock, s)
  int exit_code_ = 0;
  std::vector<double> frame_ms_, sim_ms_, ui_ms_, gl_ms_, draw_calls_, triangles_;
};

/// The window title for a scenario name ("formsim — NAME", shortened).
std::string WindowTitle(const std::string& scenario_name);

}  // namespace formsim::app
