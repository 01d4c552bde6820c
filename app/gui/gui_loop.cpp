#include "app/gui/gui_loop.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_internal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "app/export/png_writer.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/gl_api.hpp"
#include "app/render/long_text.hpp"
#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/wall_clock.hpp"
#include "sim/session/session_journal.hpp"

namespace formsim::app {
namespace {

using sim::WallSeconds;

}  // namespace

std::vector<ScriptAction> ReadScript(const std::string& file) {
  std::string text;
  try {
    text = sim::ReadBoundedFile(file);  // a regular file of at most 4 MiB (never /dev/zero)
  } catch (const sim::FileReadError& e) {
    throw std::runtime_error("--script '" + file + "': " + e.reason());
  }
  std::istringstream in(text);
  std::vector<ScriptAction> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto sp = line.find_first_of(" \t", first);
    const std::string where = file + ":" + std::to_string(n);
    long long frame = 0;
    if (sp == std::string::npos ||
        !sim::ParseInteger(line.substr(first, sp - first), 0, 1000000000LL, &frame))
      throw std::runtime_error(where + ": expected FRAME ACTION [ARGS], e.g. '30 reset'");
    const auto act = line.find_first_not_of(" \t", sp);
    if (act == std::string::npos) throw std::runtime_error(where + ": no action after the frame");
    std::string action = line.substr(act);
    while (!action.empty() && (action.back() == '\r' || action.back() == ' ')) action.pop_back();
    out.push_back({static_cast<long>(frame), action, where});
  }
  return out;
}

std::string WindowTitle(const std::string& scenario_name) {
  return "formsim — " + Shorten(scenario_name, 200);
}

GuiLoop::GuiLoop(GLFWwindow* window, std::unique_ptr<sim::Session> session, const GuiOptions& opt,
                 std::vector<ScriptAction> scripted)
    : window_(window),
      opt_(opt),
      scripted_(std::move(scripted)),
      tickets_(scripted_.size(), 0),
      layer_(GetTheme(opt.theme)) {
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  backend_ = true;
  title_shown_ = WindowTitle(session->exp().setup().name);
  ui_ = std::make_unique<AppUi>(std::move(session));
  AppUi& ui = *ui_;
  ui.state().theme = opt_.theme;
  if (ui.session().lesson().present) ui.state().select_tab = "lesson";
  if (!opt_.session_file.empty()) ui.SetSessionFile(opt_.session_file);
  // Plots keep a bounded history however long the window runs; with --out the rows of the
  // current run stream to disk as they are recorded.
  ui.SetRunSetup([this](sim::Experiment& e) {
    e.mutable_recorder().SetHistoryLimit(20000);
    if (!opt_.out_dir.empty()) e.mutable_recorder().StreamTo(sim::CsvPath(opt_.out_dir));
  });
  ui.Find<RunPanel>()->SetSpeed(opt_.speed);
  ui.state().playing = !opt_.paused;
  {
    std::string warning;
    ui.state().settings = LoadUiSettings(&warning);
    if (!warning.empty()) std::fputs(("formsim: " + warning + "\n").c_str(), stderr);
  }
  if (opt_.overlays_given) ui.state().overlays = opt_.overlays;
  // Crash-safe sessions: an unfinished one (its window gone) is offered, never restored by
  // itself; this window's record is journaled as it grows (sim/session/session_journal.hpp).
  const std::string journal_dir = sim::JournalDir();
  ui.FindUnfinishedSessions(journal_dir);
  ui.StartJournal(journal_dir);
  last_ = WallSeconds();
}

GuiLoop::~GuiLoop() {
  ui_.reset();
  if (backend_) ImGui_ImplGlfw_Shutdown();
}

int GuiLoop::Queue(const std::string& action, const std::string& where) {
  // Queued after everything already queued, at the current script time.
  ScriptAction a{clock_, action, where};
  if (!scripted_.empty() && next_action_ < scripted_.size())
    a.frame = std::max(a.frame, scripted_.back().frame);
  scripted_.push_back(std::move(a));
  tickets_.push_back(next_ticket_);
  return next_ticket_++;
}

const std::string* GuiLoop::Result(int ticket) const {
  const auto it = results_.find(ticket);
  return it == results_.end() ? nullptr : &it->second;
}

void GuiLoop::RunDueActions() {
  AppUi& ui = *ui_;
  if (holding_ && !ui.Busy()) {
    holding_ = false;
    if (waiting_ticket_ != 0) results_[waiting_ticket_] = "";
    waiting_ticket_ = 0;
  }
  // Scripted actions run through the same commands as the buttons and keys; a refused one is
  // reported and the GUI goes on.
  while (!holding_ && next_action_ < scripted_.size() && scripted_[next_action_].frame <= clock_) {
    const int ticket = tickets_[next_action_];
    const ScriptAction& a = scripted_[next_action_++];
    if (a.action == "wait") {
      holding_ = ui.Busy();
      if (holding_)
        waiting_ticket_ = ticket;
      else if (ticket != 0)
        results_[ticket] = "";
      continue;
    }
    if (a.action.rfind("screenshot", 0) == 0)
      shot_where_ = a.where + " (frame " + std::to_string(a.frame) + "): '" + a.action + "'";
    const std::string err = ui.RunScriptAction(a.action);
    if (!err.empty())
      sim::Print(stderr, "formsim: %s (frame %ld): '%s' refused: %s\n", a.where.c_str(), a.frame,
                 a.action.c_str(), err.c_str());
    if (ticket != 0) {
      // Set at the end of the frame, once a screenshot it asked for is written.
      results_[-ticket] = err;
      ran_this_frame_.push_back(ticket);
    }
  }
}

bool GuiLoop::Frame() {
  AppUi& ui = *ui_;
  const double now = WallSeconds();
  const double wall_dt = std::min(0.1, now - last_);
  last_ = now;
  RunDueActions();

  ImGui_ImplGlfw_NewFrame();
  {
    // UI scale: the interface is laid out on a display `scale` times smaller and drawn `scale`
    // times larger (fonts rasterised at that size), as PNGs at a --dpi are.
    ImGuiIO& io = ImGui::GetIO();
    const float scale = std::clamp(ui.state().settings.ui_scale, kMinUiScale, kMaxUiScale);
    const float device = scale * io.DisplayFramebufferScale.x;
    if (layer_.fonts().scale != device) layer_.SetFontScale(device);
    io.DisplaySize = ImVec2(io.DisplaySize.x / scale, io.DisplaySize.y / scale);
    io.DisplayFramebufferScale = ImVec2(device, device);
    if (io.MousePos.x > -1e30f) io.MousePos = ImVec2(io.MousePos.x / scale, io.MousePos.y / scale);
    // F1 (ImGui 1.86 names no function keys): the help overlay.
    const bool f1 = glfwGetKey(window_, GLFW_KEY_F1) == GLFW_PRESS;
    if (f1 && !f1_down_) ui.PressKey("F1");
    f1_down_ = f1;
  }
  layer_.NewFrame();
  const double t_ui = WallSeconds();
  try {
    ui.Advance(wall_dt);
    ui.NoteJournalStep();
    ui.Draw(ImGui::GetIO().DisplaySize, layer_.fonts(), true);
  } catch (const std::exception& e) {
    // Nothing may close the window but the user: close what the frame left open, pause, and
    // say what happened.
    ImGui::ErrorCheckEndFrameRecover(nullptr);
    ui.state().playing = false;
    ui.state().status = std::string("error (the run is paused): ") + e.what();
    ui.state().status_is_error = true;
  }
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  const double t_gl = WallSeconds();
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  // The previous frame is shown only now, and this one is handed to the GL without waiting: a
  // software rasteriser (llvmpipe) draws it on its own threads while the next frame's
  // simulation and UI are built, instead of the main thread waiting for every pixel.
  if (swap_pending_) {
    glfwSwapBuffers(window_);
    swap_pending_ = false;
  }
  layer_.Render(fw, fh, bg.x, bg.y, bg.z);
  ui.AfterRender();
  GlFlush();
  if (opt_.timing) {
    // GL: issuing this frame's draws and waiting for the previous frame's pixels.
    // The simulation runs inside Advance: the UI build is the rest of that time.
    sim_ms_.push_back(ui.Find<RunPanel>()->sim_ms());
    ui_ms_.push_back(1e3 * (t_gl - t_ui) - sim_ms_.back());
    gl_ms_.push_back(1e3 * (WallSeconds() - t_gl));
    const ImDrawData* dd = ImGui::GetDrawData();
    int calls = 0;
    for (int i = 0; dd && i < dd->CmdListsCount; ++i) calls += dd->CmdLists[i]->CmdBuffer.Size;
    draw_calls_.push_back(calls);
    triangles_.push_back(dd ? dd->TotalIdxCount / 3 : 0);
  }

  const bool last_frame = opt_.exit_after >= 0 && clock_ + 1 >= opt_.exit_after && !holding_;
  const bool finished_exit = opt_.exit_when_finished && ui.session().exp().finished();
  if (ui.state().screenshot_requested ||
      ((last_frame || finished_exit) && !opt_.screenshot.empty()))
    TakeScreenshot(last_frame, finished_exit);
  for (const int t : ran_this_frame_) {
    results_[t] = results_[-t];
    results_.erase(-t);
  }
  ran_this_frame_.clear();
  swap_pending_ = true;  // shown at the next frame, or never if the window closes now
  const std::string now_title = WindowTitle(ui.session().exp().setup().name);
  if (now_title != title_shown_) {
    glfwSetWindowTitle(window_, now_title.c_str());
    title_shown_ = now_title;
  }
  ui.state().frame_ms = 1e3 * (WallSeconds() - now);
  if (opt_.timing) frame_ms_.push_back(ui.state().frame_ms);
  ++frames_;
  if (!holding_) ++clock_;
  return !(last_frame || finished_exit || ui.state().quit_requested);
}

void GuiLoop::TakeScreenshot(bool last_frame, bool finished_exit) {
  AppUi& ui = *ui_;
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  std::string path = opt_.screenshot;
  if (ui.state().screenshot_requested && !ui.state().screenshot_path.empty()) {
    path = ui.state().screenshot_path;  // scripted "screenshot PATH"
  } else if (path.empty() || (ui.state().screenshot_requested && !last_frame && !finished_exit)) {
    const std::string name = sim::Sprintf("formsim_screenshot_%03d.png", shot_counter_++);
    path = opt_.screenshot.empty() ? name : path;
  }
  const bool scripted_shot = ui.state().screenshot_requested && !shot_where_.empty();
  ui.state().screenshot_path.clear();
  try {
    WritePng(path, fw, fh, GlReadRgba(fw, fh).data());
    ui.state().status = "screenshot " + path;
    ui.state().status_is_error = false;
    ui.NoteFileWritten(path, "image/png");
  } catch (const std::exception& e) {
    // Said in the status line, and on stderr for a script or --screenshot; --screenshot exits
    // with the export-failure status (4), as `run` does.
    ui.state().status = std::string("screenshot failed: ") + e.what();
    ui.state().status_is_error = true;
    if (scripted_shot)
      std::fputs(("formsim: " + shot_where_ + " failed: " + e.what() + "\n").c_str(), stderr);
    else if (!opt_.screenshot.empty() && (last_frame || finished_exit))
      std::fputs(("formsim: --screenshot " + path + " failed: " + e.what() + "\n").c_str(), stderr);
    if ((last_frame || finished_exit) && !opt_.screenshot.empty() && !scripted_shot) exit_code_ = 4;
    for (const int t : ran_this_frame_)
      if (results_[-t].empty()) results_[-t] = std::string("screenshot failed: ") + e.what();
  }
  shot_where_.clear();
  ui.state().screenshot_requested = false;
}

std::string GuiLoop::TimingReport() const {
  if (frame_ms_.size() <= 10) return "";
  // Skip the first frames (font atlas upload, first layout).
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (std::size_t i = 5; i < v.size(); ++i) s += v[i];
    return s / static_cast<double>(v.size() - 5);
  };
  std::vector<double> sorted(frame_ms_.begin() + 5, frame_ms_.end());
  std::sort(sorted.begin(), sorted.end());
  return sim::Sprintf(
      "gui: %zu frames at %dx%d: frame %.1f ms mean, %.1f ms median, %.1f ms p95 "
      "(sim %.1f, ImGui build %.1f, GL %.1f ms; %.0f draw calls, %.0f triangles)\n",
      frame_ms_.size(), opt_.width, opt_.height, mean(frame_ms_), sorted[sorted.size() / 2],
      sorted[sorted.size() * 95 / 100], mean(sim_ms_), mean(ui_ms_), mean(gl_ms_),
      mean(draw_calls_), mean(triangles_));
}

}  // namespace formsim::app
