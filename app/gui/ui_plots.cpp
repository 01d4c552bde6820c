/// \file The right-hand window: a tab for each panel shown there (Lesson, Plots, Tables,
/// History, Summary), the tab a script asks for (`tab NAME`) brought to the front once. In the
/// narrow layout it is the left-hand window and its first tab holds the control panel.
#include <cctype>

#include "app/gui/compare_panel.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/plots_panel.hpp"
#include "app/gui/tables_panel.hpp"
#include "app/gui/ui.hpp"

namespace formsim::app {

void AppUi::DrawPlotsWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts, bool with_controls) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::Begin("Plots###plots", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoBackground);  // as "formsim"
  // A tab asked for by a script (`tab history`) comes to the front once.
  auto tab = [&](const char* name) {
    std::string lower = name;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool select = state_.select_tab == lower;
    if (select) state_.select_tab.clear();
    return select ? ImGuiTabItemFlags_SetSelected : ImGuiTabItemFlags_None;
  };
  // The control panel is a tab only in the narrow layout; elsewhere it is always in view.
  if (!with_controls && state_.select_tab == "controls") state_.select_tab.clear();
  // Every tab stays reachable however narrow the window: tabs that do not fit shrink, and the
  // list button at the left of the bar names them all (the narrow layout).
  const ImGuiTabBarFlags bar_flags =
      with_controls ? ImGuiTabBarFlags_TabListPopupButton | ImGuiTabBarFlags_FittingPolicyResizeDown
                    : ImGuiTabBarFlags_None;
  if (ImGui::BeginTabBar("tabs", bar_flags)) {
    if (with_controls && ImGui::BeginTabItem("Controls", nullptr, tab("Controls"))) {
      // With the window's padding: full-width items end inside the clip rectangle, not under it.
      ImGui::BeginChild("controls", ImVec2(0, 0), false, ImGuiWindowFlags_AlwaysUseWindowPadding);
      DrawControlPanel(fonts, true);
      ImGui::EndChild();
      ImGui::EndTabItem();
    }
    // A lesson file's text comes first (formsim gui --lesson NAME opens on it).
    if (session_->lesson().present && ImGui::BeginTabItem("Lesson", nullptr, tab("Lesson"))) {
      if (auto* lesson = Find<LessonPanel>()) lesson->Draw(fonts);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Plots", nullptr, tab("Plots"))) {
      plots_->Draw(fonts);
      ImGui::EndTabItem();
    }
    // Always there (a run not started yet says so): `tab tables` is never left waiting.
    if (ImGui::BeginTabItem("Tables", nullptr, tab("Tables"))) {
      tables_->Draw(fonts);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("History", nullptr, tab("History"))) {
      compare_->DrawPinnedRuns();
      history_->Draw(fonts);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Summary", nullptr, tab("Summary"))) {
      tables_->DrawSummary(fonts);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

}  // namespace formsim::app
