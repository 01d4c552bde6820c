/// \file The browser page's program: the window of `formsim gui` (app/gui/gui_loop.hpp) in the
/// page's canvas, one frame per animation frame of the browser, and the entry points the page's
/// JavaScript calls (web/formsim_page.js): queue script actions, read their results, run a
/// scenario to its end without drawing. Arguments (the page builds them from its URL):
///   [SCENARIO] [--lesson NAME] [--theme NAME] [--present] [--script FILE] [--paused]
#include <GLFW/glfw3.h>
#include <emscripten.h>
#include <emscripten/html5.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/gui/gui_loop.hpp"
#include "app/gui/ui.hpp"
#include "app/render/gl_api.hpp"
#include "control/common/shortest_double_format.hpp"
#include "sim/core/json.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/provenance.hpp"
#include "sim/core/run_output.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"

// Calls into the page (web/formsim_page.js defines them on Module; absent ones are skipped).
EM_JS(void, formsim_js_download, (const char* path, const char* mime), {
  if (Module.formsimDownload) Module.formsimDownload(UTF8ToString(path), UTF8ToString(mime));
});
EM_JS(void, formsim_js_pick_file, (), {
  if (Module.formsimPickFile) Module.formsimPickFile();
});
EM_JS(void, formsim_js_fatal, (const char* text), {
  if (Module.formsimFatal) Module.formsimFatal(UTF8ToString(text));
});

namespace formsim::app {
namespace {

constexpr const char* kAssets = "/formsim/assets";  // preloaded (app/web/CMakeLists.txt)
constexpr const char* kHome = "/home/web_user";

struct WebApp {
  GLFWwindow* window = nullptr;
  std::unique_ptr<GuiLoop> loop;
  int width = 0, height = 0;
  std::string result;  ///< the last string handed to JavaScript (valid until the next call)
};
WebApp* g_app = nullptr;

// `initial` gets the script actions the arguments stand for (--present: `present on`).
GuiOptions ParseArgs(int argc, char** argv, std::vector<std::string>* initial) {
  GuiOptions opt;
  std::vector<std::string> a(argv + 1, argv + argc);
  for (std::size_t i = 0; i < a.size(); ++i) {
    auto value = [&](const char* flag) {
      if (i + 1 >= a.size()) throw std::runtime_error(std::string(flag) + " needs a value");
      return a[++i];
    };
    if (a[i] == "--lesson")
      opt.lesson = value("--lesson");
    else if (a[i] == "--theme")
      opt.theme = ParseTheme(value("--theme"), "theme");
    else if (a[i] == "--script")
      opt.script = value("--script");
    else if (a[i] == "--present")
      initial->push_back("present on");
    else if (a[i] == "--paused")
      opt.paused = true;
    else if (!a[i].empty() && a[i][0] != '-' && opt.scenario.empty())
      opt.scenario = a[i];
    else
      throw std::runtime_error("unknown argument '" + a[i] + "'");
  }
  if (!opt.lesson.empty() && !opt.scenario.empty())
    throw std::runtime_error("give a scenario or a lesson, not both");
  return opt;
}

// The canvas follows the size the page's CSS gives it.
void FollowCanvasSize(WebApp& app) {
  double w = 0, h = 0;
  emscripten_get_element_css_size("#canvas", &w, &h);
  const int iw = std::max(320, static_cast<int>(w)), ih = std::max(240, static_cast<int>(h));
  if (iw != app.width || ih != app.height) {
    app.width = iw;
    app.height = ih;
    glfwSetWindowSize(app.window, iw, ih);
  }
}

void Frame() {
  WebApp& app = *g_app;
  FollowCanvasSize(app);
  glfwPollEvents();
  if (!app.loop->Frame()) {
    // `quit` in a page: stop drawing; the page stays as it was.
    emscripten_cancel_main_loop();
    std::fputs("formsim: the window was closed (quit); reload the page to start again\n", stderr);
  }
}

int Start(int argc, char** argv) {
  setenv("FORMSIM_ASSETS", kAssets, 1);
  std::filesystem::create_directories(std::string(kHome) + "/uploads");
  // Files the user saves without a folder (screenshots, the tuned scenario) land in the home
  // folder, from which the page offers them as downloads.
  std::filesystem::current_path(kHome);
  std::vector<std::string> initial;
  GuiOptions opt = ParseArgs(argc, argv, &initial);
  std::vector<ScriptAction> scripted;
  for (const auto& line : initial) scripted.push_back({0, line, "the page's address"});
  if (!opt.script.empty())
    for (auto& act : ReadScript(opt.script)) scripted.push_back(std::move(act));
  std::stable_sort(scripted.begin(), scripted.end(),
                   [](const ScriptAction& x, const ScriptAction& y) { return x.frame < y.frame; });
  std::string file;
  if (!opt.lesson.empty())
    file = sim::ResolveLesson(opt.lesson);
  else if (!opt.scenario.empty())
    file = sim::ResolveScenario(opt.scenario);
  else
    file = sim::ResolveScenario("formation_traj2_ukf");
  auto session = std::make_unique<sim::Session>(file, std::vector<sim::Override>{});

  if (!glfwInit()) throw std::runtime_error("GLFW could not start in this page");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
  g_app = new WebApp;
  double w = 0, h = 0;
  emscripten_get_element_css_size("#canvas", &w, &h);
  g_app->width = std::max(320, static_cast<int>(w));
  g_app->height = std::max(240, static_cast<int>(h));
  opt.width = g_app->width;
  opt.height = g_app->height;
  g_app->window =
      glfwCreateWindow(g_app->width, g_app->height,
                       WindowTitle(session->exp().setup().name).c_str(), nullptr, nullptr);
  if (g_app->window == nullptr) throw std::runtime_error("this browser gives no WebGL 2 context");
  glfwMakeContextCurrent(g_app->window);
  LoadGl(nullptr, "the page's canvas");
  g_app->loop =
      std::make_unique<GuiLoop>(g_app->window, std::move(session), opt, std::move(scripted));
  g_app->loop->ui().SetFileWrittenHook([](const std::string& path, const std::string& mime) {
    formsim_js_download(path.c_str(), mime.c_str());
  });
  g_app->loop->ui().SetPickFileHook([] { formsim_js_pick_file(); });
  // The browser calls Frame once per animation frame; main returns and the page lives on.
  emscripten_set_main_loop(Frame, 0, false);
  return 0;
}

std::string RunHeadless(const std::string& scenario, const std::string& seed) {
  sim::Json out = sim::Json::Object();
  try {
    std::vector<sim::Override> overrides;
    if (!seed.empty()) overrides.push_back({"seed", seed, "seed", -1});
    const std::string file = sim::ResolveScenario(scenario);
    sim::Session session(file, overrides);
    const std::string dir =
        std::string(kHome) + "/headless/" + std::filesystem::path(file).stem().string();
    sim::PrepareOutputDir(dir);
    // As `formsim run SCENARIO --out DIR`: rows stream to the CSV as they are recorded.
    sim::Recorder& rec = session.exp().mutable_recorder();
    rec.StreamTo(sim::CsvPath(dir));
    rec.SetHistoryLimit(sim::kRunHistoryRows);
    const auto t0 = std::chrono::steady_clock::now();
    sim::Experiment& exp = session.exp();
    while (!exp.finished()) exp.Step();
    sim::WriteRunOutputs(exp, dir);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out["dir"] = dir;
    out["csv"] = sim::CsvPath(dir);
    out["steps"] = static_cast<long long>(exp.steps());
    out["sim_time"] = exp.time();
    out["wall_ms"] = 1e3 * wall;
  } catch (const std::exception& e) {
    out = sim::Json::Object();
    out["error"] = std::string(e.what());
  }
  return out.Dump(0);
}

// The simulation alone: the run to its end with its rows kept in memory as numbers (the
// window's bound), no CSV text. Milliseconds of wall time, or -1 when it cannot run.
double TimeSimulation(const std::string& scenario) {
  try {
    sim::Session session(sim::ResolveScenario(scenario), {});
    session.exp().mutable_recorder().SetHistoryLimit(sim::kRunHistoryRows);
    const auto t0 = std::chrono::steady_clock::now();
    sim::Experiment& exp = session.exp();
    while (!exp.finished()) exp.Step();
    return 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  } catch (const std::exception& e) {
    formsim::sim::Print(stderr, "formsim: %s\n", e.what());
    return -1;
  }
}

}  // namespace
}  // namespace formsim::app

using formsim::app::g_app;

extern "C" {

EMSCRIPTEN_KEEPALIVE int formsim_web_queue(const char* action) {
  if (g_app == nullptr || g_app->loop == nullptr) return 0;
  return g_app->loop->Queue(action ? action : "", "page");
}

EMSCRIPTEN_KEEPALIVE const char* formsim_web_result(int ticket) {
  if (g_app == nullptr || g_app->loop == nullptr) return nullptr;
  const std::string* r = g_app->loop->Result(ticket);
  if (r == nullptr) return nullptr;
  g_app->result = *r;
  return g_app->result.c_str();
}

EMSCRIPTEN_KEEPALIVE double formsim_web_frames() {
  return g_app && g_app->loop ? static_cast<double>(g_app->loop->frames()) : 0.0;
}

EMSCRIPTEN_KEEPALIVE double formsim_web_frame_ms() {
  return g_app && g_app->loop ? g_app->loop->ui().state().frame_ms : 0.0;
}

EMSCRIPTEN_KEEPALIVE int formsim_web_busy() {
  return g_app && g_app->loop && g_app->loop->ui().Busy() ? 1 : 0;
}

EMSCRIPTEN_KEEPALIVE const char* formsim_web_run_headless(const char* scenario, const char* seed) {
  static std::string out;
  out = formsim::app::RunHeadless(scenario ? scenario : "", seed ? seed : "");
  return out.c_str();
}

EMSCRIPTEN_KEEPALIVE double formsim_web_time_simulation(const char* scenario) {
  return formsim::app::TimeSimulation(scenario ? scenario : "");
}

// The text the page writes for a double (CSV cells, summaries): the browser test compares it
// with std::to_chars' on the desktop (tests/web/shortest_doubles.json).
EMSCRIPTEN_KEEPALIVE const char* formsim_web_format_double(double v) {
  static char text[32];
  *formsim::control::WriteShortestDouble(text, text + sizeof text - 1, v) = '\0';
  return text;
}

EMSCRIPTEN_KEEPALIVE const char* formsim_web_version() {
  static const std::string v = formsim::sim::FormsimVersion();
  return v.c_str();
}

}  // extern "C"

int main(int argc, char** argv) {
  try {
    return formsim::app::Start(argc, argv);
  } catch (const std::exception& e) {
    formsim::sim::Print(stderr, "formsim: %s\n", e.what());
    formsim_js_fatal(e.what());
    return 1;
  }
}
