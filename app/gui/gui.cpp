#include "app/gui/gui.hpp"

#include <GLFW/glfw3.h>
#include <dlfcn.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_internal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "app/gui/compare_panel.hpp"
#include "app/gui/run_panel.hpp"
#include "app/render/gl_api.hpp"
#include "app/render/imgui_layer.hpp"
#include "app/render/long_text.hpp"
#include "app/export/png_writer.hpp"
#include "app/cli/stop_signal.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/scenario/scenario_files.hpp"

namespace formsim::app {
namespace {

void GlfwError(int code, const char* text) {
  std::fprintf(stderr, "formsim: GLFW error %d: %s\n", code, text);
}

std::string DefaultScenario() {
  const auto files = sim::ShippedScenarios();
  for (const auto& f : files)
    if (std::filesystem::path(f).stem().string().rfind("formation_", 0) == 0) return f;
  if (files.empty())
    throw std::runtime_error("no scenario given and none shipped in " + sim::ScenarioDir());
  return files.front();
}

// "120:robots.R2.follow.k_l=0.3" -> frame 120, "edit robots.R2.follow.k_l=0.3".
std::vector<ScriptAction> ParseEdits(const std::vector<std::string>& in) {
  std::vector<ScriptAction> out;
  for (const auto& e : in) {
    const auto colon = e.find(':'), eq = e.find('=');
    if (colon == std::string::npos || eq == std::string::npos || eq < colon)
      throw std::runtime_error("--edit '" + e + "': expected FRAME:key=value");
    long long frame = 0;
    if (!sim::ParseInteger(e.substr(0, colon), 0, 1000000000LL, &frame))
      throw std::runtime_error("--edit '" + e + "': FRAME must be a frame number");
    out.push_back({static_cast<long>(frame), "edit " + e.substr(colon + 1), "--edit " + e});
  }
  return out;
}

// GLFW unloads the GL driver in glfwTerminate, before LeakSanitizer reports at exit, so the
// driver's own never-freed allocations show up as leaks in "<unknown module>" that no
// suppression can name. Loading the driver libraries once more with RTLD_NODELETE keeps them
// mapped, so a sanitizer build names them (tests/sanitizer/lsan.supp) and formsim's own leaks
// stay visible. Harmless otherwise: the process holds one more reference until it exits.
void PinGlDriverLibraries() {
  for (const char* lib : {"libGLX_mesa.so.0", "libglapi.so.0", "libGL.so.1", "libGLX.so.0",
                          "libGLdispatch.so.0", "swrast_dri.so", "kms_swrast_dri.so"}) {
    std::string path = lib;
    if (path.find("_dri.so") != std::string::npos) path = std::string(FORMSIM_DRI_DIR) + "/" + path;
    dlopen(path.c_str(), RTLD_NOW | RTLD_NODELETE | RTLD_GLOBAL);
  }
}

struct GlfwSession {
  GlfwSession() {
    PinGlDriverLibraries();
    glfwSetErrorCallback(GlfwError);
    if (!glfwInit())
      throw std::runtime_error(
          "cannot open a window (no display? DISPLAY is unset or unreachable). "
          "Use `formsim run SCENARIO --frames DIR` for headless pictures, or xvfb-run.");
  }
  ~GlfwSession() { glfwTerminate(); }
};

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

int RunGui(const GuiOptions& opt) {
  // SIGINT, SIGTERM and SIGHUP end the loop at the next frame; what `run` writes is written.
  InstallStopSignals();
  std::vector<ScriptAction> scripted = ParseEdits(opt.edits);
  if (!opt.script.empty())
    for (auto& a : ReadScript(opt.script)) scripted.push_back(std::move(a));
  // Same frame: --edit first, then the script in file order.
  std::stable_sort(scripted.begin(), scripted.end(),
                   [](const ScriptAction& a, const ScriptAction& b) { return a.frame < b.frame; });
  if (!opt.lesson.empty() && !opt.scenario.empty())
    throw std::runtime_error("--lesson " + opt.lesson + ": give a scenario or a lesson, not both");
  const std::string file = !opt.lesson.empty()    ? sim::ResolveLesson(opt.lesson)
                           : opt.scenario.empty() ? DefaultScenario()
                                                  : sim::ResolveScenario(opt.scenario);
  std::vector<sim::Override> overrides = sim::CliOverrides(opt.sets, -1);
  if (!opt.seed.empty()) overrides.push_back({"seed", opt.seed, "--seed", -1});
  auto session = std::make_unique<sim::Session>(file, overrides);
  if (!opt.out_dir.empty()) sim::PrepareOutputDir(opt.out_dir);
  if (!opt.session_file.empty()) {
    const std::filesystem::path parent = std::filesystem::path(opt.session_file).parent_path();
    if (!parent.empty()) sim::PrepareOutputDir(parent.string());  // fail now, not on exit
  }

  GlfwSession glfw;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  const std::string title = "formsim — " + Shorten(session->exp().setup().name, 200);
  GLFWwindow* window = glfwCreateWindow(opt.width, opt.height, title.c_str(), nullptr, nullptr);
  if (window == nullptr) throw std::runtime_error("cannot create an OpenGL 3.3 core window");
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  // The window's own pointers: glfwGetProcAddress, never the gl* symbols libOSMesa exports.
  LoadGl(reinterpret_cast<GlGetProcAddress>(&glfwGetProcAddress), "GLFW window");

  int exit_code = 0;
  {
    ImGuiLayer layer(GetTheme(opt.theme));
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    AppUi ui(std::move(session));
    ui.state().theme = opt.theme;
    if (ui.session().lesson().present) ui.state().select_tab = "lesson";
    if (!opt.session_file.empty()) ui.SetSessionFile(opt.session_file);
    // Plots keep a bounded history however long the window runs; with --out the rows of the
    // current run stream to disk as they are recorded.
    ui.SetRunSetup([&opt](sim::Experiment& e) {
      e.mutable_recorder().SetHistoryLimit(20000);
      if (!opt.out_dir.empty()) e.mutable_recorder().StreamTo(sim::CsvPath(opt.out_dir));
    });
    ui.Find<RunPanel>()->SetSpeed(opt.speed);
    ui.state().playing = !opt.paused;
    {
      std::string warning;
      ui.state().settings = LoadUiSettings(&warning);
      if (!warning.empty()) std::fprintf(stderr, "formsim: %s\n", warning.c_str());
    }
    if (opt.overlays_given) ui.state().overlays = opt.overlays;
    // Crash-safe sessions: an unfinished one (its window gone) is offered, never restored by
    // itself; this window's record is journaled as it grows (sim/session/session_journal.hpp).
    {
      const std::string journal_dir = sim::JournalDir();
      ui.FindUnfinishedSessions(journal_dir);
      ui.StartJournal(journal_dir);
    }
    std::string shot_where;  // the script line of the screenshot asked for (its failure names it)
    bool f1_down = false;

    using Clock = std::chrono::steady_clock;
    auto last = Clock::now();
    int shot_counter = 0;
    std::size_t next_action = 0;
    // Script time: frames counted for the script and --exit-after; it stands still while a
    // `wait` holds the script for the background work (pins, Monte Carlo, timeline).
    long clock = 0;
    bool holding = false;
    std::string title_shown = title;
    std::vector<double> frame_ms, sim_ms, ui_ms, gl_ms;  // for --timing
    std::vector<double> draw_calls, triangles;          // for --timing: what GL was given
    for (; !glfwWindowShouldClose(window); clock += holding ? 0 : 1) {
      glfwPollEvents();
      if (StopSignal() != 0) break;
      const auto now = Clock::now();
      const double wall_dt = std::min(0.1, std::chrono::duration<double>(now - last).count());
      last = now;
      // Scripted actions run through the same commands as the buttons and keys; a refused
      // one is reported and the GUI goes on.
      if (holding && !ui.Busy()) holding = false;
      while (!holding && next_action < scripted.size() && scripted[next_action].frame <= clock) {
        const ScriptAction& a = scripted[next_action++];
        if (a.action == "wait") {
          holding = ui.Busy();
          continue;
        }
        if (a.action.rfind("screenshot", 0) == 0)
          shot_where = a.where + " (frame " + std::to_string(a.frame) + "): '" + a.action + "'";
        const std::string err = ui.RunScriptAction(a.action);
        if (!err.empty())
          std::fprintf(stderr, "formsim: %s (frame %ld): '%s' refused: %s\n", a.where.c_str(),
                       a.frame, a.action.c_str(), err.c_str());
      }

      ImGui_ImplGlfw_NewFrame();
      {
        // UI scale: the interface is laid out on a display `scale` times smaller and drawn
        // `scale` times larger (fonts rasterised at that size), as PNGs at a --dpi are.
        ImGuiIO& io = ImGui::GetIO();
        const float scale = std::clamp(ui.state().settings.ui_scale, kMinUiScale, kMaxUiScale);
        const float device = scale * io.DisplayFramebufferScale.x;
        if (layer.fonts().scale != device) layer.SetFontScale(device);
        io.DisplaySize = ImVec2(io.DisplaySize.x / scale, io.DisplaySize.y / scale);
        io.DisplayFramebufferScale = ImVec2(device, device);
        if (io.MousePos.x > -1e30f) io.MousePos = ImVec2(io.MousePos.x / scale, io.MousePos.y / scale);
        // F1 (ImGui 1.86 names no function keys): the help overlay.
        const bool f1 = glfwGetKey(window, GLFW_KEY_F1) == GLFW_PRESS;
        if (f1 && !f1_down) ui.PressKey("F1");
        f1_down = f1;
      }
      layer.NewFrame();
      const auto t_ui = Clock::now();
      try {
        ui.Advance(wall_dt);
        ui.NoteJournalStep();
        ui.Draw(ImGui::GetIO().DisplaySize, layer.fonts(), true);
      } catch (const std::exception& e) {
        // Nothing may close the window but the user: close what the frame left open, pause,
        // and say what happened.
        ImGui::ErrorCheckEndFrameRecover(nullptr);
        ui.state().playing = false;
        ui.state().status = std::string("error (the run is paused): ") + e.what();
        ui.state().status_is_error = true;
      }
      int fw = 0, fh = 0;
      glfwGetFramebufferSize(window, &fw, &fh);
      const auto t_gl = Clock::now();
      const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
      layer.Render(fw, fh, bg.x, bg.y, bg.z);
      if (opt.timing) {
        GlFinish();  // attribute the rasterisation to this frame
        // The simulation runs inside Advance: the UI build is the rest of that time.
        sim_ms.push_back(ui.Find<RunPanel>()->sim_ms());
        ui_ms.push_back(1e3 * std::chrono::duration<double>(t_gl - t_ui).count() - sim_ms.back());
        gl_ms.push_back(1e3 * std::chrono::duration<double>(Clock::now() - t_gl).count());
        const ImDrawData* dd = ImGui::GetDrawData();
        int calls = 0;
        for (int i = 0; dd && i < dd->CmdListsCount; ++i) calls += dd->CmdLists[i]->CmdBuffer.Size;
        draw_calls.push_back(calls);
        triangles.push_back(dd ? dd->TotalIdxCount / 3 : 0);
      }

      const bool last_frame = opt.exit_after >= 0 && clock + 1 >= opt.exit_after && !holding;
      const bool finished_exit = opt.exit_when_finished && ui.session().exp().finished();
      if (ui.state().screenshot_requested ||
          ((last_frame || finished_exit) && !opt.screenshot.empty())) {
        std::string path = opt.screenshot;
        if (ui.state().screenshot_requested && !ui.state().screenshot_path.empty()) {
          path = ui.state().screenshot_path;  // scripted "screenshot PATH"
        } else if (path.empty() ||
                   (ui.state().screenshot_requested && !last_frame && !finished_exit)) {
          char name[64];
          std::snprintf(name, sizeof(name), "formsim_screenshot_%03d.png", shot_counter++);
          path = opt.screenshot.empty() ? name : path;
        }
        const bool scripted_shot = ui.state().screenshot_requested && !shot_where.empty();
        ui.state().screenshot_path.clear();
        try {
          WritePng(path, fw, fh, GlReadRgba(fw, fh).data());
          ui.state().status = "screenshot " + path;
          ui.state().status_is_error = false;
        } catch (const std::exception& e) {
          // Said in the status line, and on stderr for a script or --screenshot; --screenshot
          // exits with the export-failure status (4), as `run` does.
          ui.state().status = std::string("screenshot failed: ") + e.what();
          ui.state().status_is_error = true;
          if (scripted_shot)
            std::fprintf(stderr, "formsim: %s failed: %s\n", shot_where.c_str(), e.what());
          else if (!opt.screenshot.empty() && (last_frame || finished_exit))
            std::fprintf(stderr, "formsim: --screenshot %s failed: %s\n", path.c_str(), e.what());
          if ((last_frame || finished_exit) && !opt.screenshot.empty() && !scripted_shot) exit_code = 4;
        }
        shot_where.clear();
        ui.state().screenshot_requested = false;
      }
      glfwSwapBuffers(window);
      const std::string now_title = "formsim — " + Shorten(ui.session().exp().setup().name, 200);
      if (now_title != title_shown) {
        glfwSetWindowTitle(window, now_title.c_str());
        title_shown = now_title;
      }
      ui.state().frame_ms = 1e3 * std::chrono::duration<double>(Clock::now() - now).count();
      if (opt.timing) frame_ms.push_back(ui.state().frame_ms);
      if (last_frame || finished_exit || ui.state().quit_requested) break;
    }
    // A stop signal ends the run as `formsim run` ends it: written, marked interrupted.
    const int sig = StopSignal();
    if (sig != 0) {
      sim::Experiment& exp = ui.session().exp();
      exp.Interrupt("interrupted by " + StopSignalName(sig) + " at t = " + std::to_string(exp.time()) +
                    " s (step " + std::to_string(exp.steps()) + ")");
    }
    if (!opt.out_dir.empty()) {
      sim::WriteRunOutputs(ui.session().exp(), opt.out_dir);
      ui.Find<ComparePanel>()->WriteMonteCarlo(opt.out_dir);
    }
    bool session_saved = false;
    if (!opt.session_file.empty()) {
      const std::string err = ui.CmdSaveSession(opt.session_file);
      session_saved = err.empty();
      if (!err.empty()) {
        std::fprintf(stderr, "formsim: %s\n", err.c_str());
        exit_code = 2;
      }
    }
    // The journal goes at a clean exit and once the session file is written; after a signal
    // without a session file, or when the session file could not be written, it stays,
    // offered for restore at the next start.
    ui.CloseJournal(session_saved || (sig == 0 && opt.session_file.empty()));
    if (sig != 0) {
      std::fprintf(stderr, "formsim: window interrupted by %s; %s%s\n", StopSignalName(sig).c_str(),
                   opt.out_dir.empty() ? "" : "the results so far were written and marked interrupted",
                   session_saved ? ", the session was saved"
                                 : opt.session_file.empty() ? "; the session journal is kept for restore" : "");
      exit_code = 128 + sig;
    }
    if (opt.timing && frame_ms.size() > 10) {
      // Skip the first frames (font atlas upload, first layout).
      auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (std::size_t i = 5; i < v.size(); ++i) s += v[i];
        return s / static_cast<double>(v.size() - 5);
      };
      std::vector<double> sorted(frame_ms.begin() + 5, frame_ms.end());
      std::sort(sorted.begin(), sorted.end());
      std::fprintf(stderr,
                   "gui: %zu frames at %dx%d: frame %.1f ms mean, %.1f ms median, %.1f ms p95 "
                   "(sim %.1f, ImGui build %.1f, GL %.1f ms; %.0f draw calls, %.0f triangles)\n",
                   frame_ms.size(), opt.width, opt.height, mean(frame_ms),
                   sorted[sorted.size() / 2], sorted[sorted.size() * 95 / 100], mean(sim_ms),
                   mean(ui_ms), mean(gl_ms), mean(draw_calls), mean(triangles));
    }
    ImGui_ImplGlfw_Shutdown();
  }
  glfwDestroyWindow(window);
  return exit_code;
}

}  // namespace formsim::app
