#include "app/gui/gui.hpp"

#include <GLFW/glfw3.h>
#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "app/gui/compare_panel.hpp"
#include "app/gui/gui_loop.hpp"
#include "app/gui/ui.hpp"
#include "app/render/gl_api.hpp"
#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/stop_signal.hpp"
#include "sim/scenario/scenario_files.hpp"

namespace formsim::app {
namespace {

void GlfwError(int code, const char* text) {
  sim::Print(stderr, "formsim: GLFW error %d: %s\n", code, text);
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

// What the window wrote when signal `sig` ended it, for stderr.
std::string InterruptedMessage(int sig, const GuiOptions& opt, bool session_saved) {
  std::string text = "formsim: window interrupted by " + sim::StopSignalName(sig) + "; ";
  if (!opt.out_dir.empty()) text += "the results so far were written and marked interrupted";
  if (session_saved)
    text += ", the session was saved";
  else if (opt.session_file.empty())
    text += "; the session journal is kept for restore";
  return text + "\n";
}

}  // namespace

int RunGui(const GuiOptions& opt) {
  // SIGINT, SIGTERM and SIGHUP end the loop at the next frame; what `run` writes is written.
  sim::InstallStopSignals();
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
  const std::string title = WindowTitle(session->exp().setup().name);
  GLFWwindow* window = glfwCreateWindow(opt.width, opt.height, title.c_str(), nullptr, nullptr);
  if (window == nullptr) throw std::runtime_error("cannot create an OpenGL 3.3 core window");
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  // The window's own pointers: glfwGetProcAddress, never the gl* symbols libOSMesa exports.
  LoadGl(reinterpret_cast<GlGetProcAddress>(&glfwGetProcAddress), "GLFW window");

  int exit_code = 0;
  {
    GuiLoop loop(window, std::move(session), opt, std::move(scripted));
    AppUi& ui = loop.ui();
    while (!glfwWindowShouldClose(window)) {
      glfwPollEvents();
      if (sim::StopSignal() != 0 || !loop.Frame()) break;
    }
    exit_code = loop.exit_code();
    // A stop signal ends the run as `formsim run` ends it: written, marked interrupted.
    const int sig = sim::StopSignal();
    if (sig != 0) {
      sim::Experiment& exp = ui.session().exp();
      exp.Interrupt("interrupted by " + sim::StopSignalName(sig) + " at t = " +
                    std::to_string(exp.time()) + " s (step " + std::to_string(exp.steps()) + ")");
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
        std::fputs(("formsim: " + err + "\n").c_str(), stderr);
        exit_code = 2;
      }
    }
    // The journal goes at a clean exit and once the session file is written; after a signal
    // without a session file, or when the session file could not be written, it stays,
    // offered for restore at the next start.
    ui.CloseJournal(session_saved || (sig == 0 && opt.session_file.empty()));
    if (sig != 0) {
      std::fputs(InterruptedMessage(sig, opt, session_saved).c_str(), stderr);
      exit_code = 128 + sig;
    }
    if (opt.timing) std::fputs(loop.TimingReport().c_str(), stderr);
  }
  glfwDestroyWindow(window);
  return exit_code;
}

}  // namespace formsim::app
