// libFuzzer harness for `--script` action lines, run against the window's command handlers
// (app/gui/command_table.hpp) in an in-process window: an OSMesa context and ImGui, no display.
// The first byte picks a scenario; each following line is one action ("FRAME" left out), run
// through AppUi::RunScriptAction, then one frame is built (Advance + Draw), so that what an
// action leaves for the drawing (texts, ranges, modes) meets ImGui's assertions too. A refusal
// is a message; a crash, a sanitizer report or an ImGui assertion is a find.
#include <imgui.h>

#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/render/imgui_layer.hpp"
#include "app/render/offscreen_context.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/ui.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "tests/fuzz/fuzz_lines.hpp"

namespace {

constexpr int kW = 800, kH = 500;

// Scenarios with every command's ground covered: formation editing and switching, an AGV.
std::string ScenarioFor(std::uint8_t b) {
  static const char* const kNames[] = {"formation_switching", "formation_traj2", "agv_fused"};
  return formsim::sim::ResolveScenario(kNames[b % 3]);
}

std::string& OwnDir() {
  static std::string dir;
  return dir;
}

}  // namespace

// The window saves its settings (ui-scale, angle-unit, theme: $XDG_CONFIG_HOME/formsim) and its
// session journals (FORMSIM_STATE_DIR) as actions change them: into a folder of the harness's
// own, removed at exit, never the user's. (A fuzz run once left `ui_scale: 3` in ~/.config.)
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char dir[] = "/tmp/formsim_fuzz_script_XXXXXX";
  if (mkdtemp(dir) == nullptr) return 0;
  OwnDir() = dir;
  setenv("XDG_CONFIG_HOME", (OwnDir() + "/config").c_str(), 1);
  setenv("FORMSIM_STATE_DIR", (OwnDir() + "/state").c_str(), 1);
  std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(OwnDir(), ec);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace formsim;
  static app::OffscreenContext context(kW, kH);
  static app::ImGuiLayer layer;
  if (size < 1) return 0;
  const std::vector<std::string> lines = formsim::fuzz::InputLines(data, size, 24);
  std::unique_ptr<app::AppUi> ui;
  try {
    ui = std::make_unique<app::AppUi>(
        std::make_unique<sim::Session>(ScenarioFor(data[0]), std::vector<sim::Override>{}));
  } catch (const std::exception&) {
    return 0;
  }
  ui->state().playing = false;
  for (const std::string& line : lines) {
    if (line.rfind("quit", 0) == 0) continue;  // ends the window by design
    ui->RunScriptAction(line);
    layer.NewHeadlessFrame(kW, kH, 1.0f / 60.0f);
    ui->Advance(1.0 / 60.0);
    ui->Draw(ImVec2(kW, kH), layer.fonts(), true);
    ImGui::Render();
    ui->AfterRender();
  }
  // Background work (pins, seeds) stops with the window.
  ui->Find<formsim::app::ComparePanel>()->CmdCancelSeeds();
  return 0;
}
