#pragma once
/// \file The window's interface in-process for tests: an OSMesa context, ImGui and an AppUi over
/// a shipped scenario, driven frame by frame with synthetic mouse and keyboard input (no display).

#include <imgui.h>
#include <imgui_internal.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/render/imgui_layer.hpp"
#include "app/render/offscreen_context.hpp"
#include "app/gui/ui.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app::testing {

class UiWindow {
 public:
  /// A paused window on shipped scenario `scenario`, `width` x `height` pixels, laid out.
  explicit UiWindow(const std::string& scenario = "formation_traj2", int width = 1280,
                    int height = 800)
      : w_(width),
        h_(height),
        ctx_(width, height),
        ui_(std::make_unique<sim::Session>(Scenario(scenario), std::vector<sim::Override>{})) {
    ui_.state().playing = false;
    ImGuiIO& io = ImGui::GetIO();
    io.KeyMap[ImGuiKey_Z] = 'Z';
    io.KeyMap[ImGuiKey_Y] = 'Y';
    io.KeyMap[ImGuiKey_Enter] = 13;
    for (int i = 0; i < 3; ++i) Frame();  // windows laid out
  }
  AppUi& ui() { return ui_; }
  int width() const { return w_; }
  int height() const { return h_; }

  /// One frame with `input` set before it starts; mouse buttons and keys are released after.
  void Frame(const std::function<void(ImGuiIO&)>& input = {}) {
    ImGuiIO& io = ImGui::GetIO();
    if (input) input(io);
    layer_.NewHeadlessFrame(w_, h_, 1.0f / 60.0f);
    ui_.Advance(1.0 / 60.0);
    ui_.Draw(ImVec2(static_cast<float>(w_), static_cast<float>(h_)), layer_.fonts(), true);
    ImGui::Render();
    ui_.AfterRender();
    io.MouseDown[0] = false;
    io.KeyCtrl = io.KeyShift = false;
    for (bool& k : io.KeysDown) k = false;
  }
  /// The widget under `p` (0: none).
  ImGuiID Hover(ImVec2 p) {
    Frame([&](ImGuiIO& io) { io.MousePos = p; });
    return ImGui::GetCurrentContext()->HoveredId;
  }
  /// Where the widget `label` of window `window` is, scanning a column x of the panel.
  ImVec2 Find(const char* window, const char* label, float x) {
    const ImGuiWindow* w = ImGui::FindWindowByName(window);
    if (w == nullptr) return ImVec2(-1, -1);  // not in this layout
    const ImGuiID id = ImHashStr(label, 0, w->ID);
    for (float y = 0; y < static_cast<float>(h_); y += 4)
      if (Hover(ImVec2(x, y)) == id) return ImVec2(x, y);
    return ImVec2(-1, -1);
  }

 private:
  int w_, h_;
  OffscreenContext ctx_;
  ImGuiLayer layer_;
  AppUi ui_;
};

}  // namespace formsim::app::testing
