// Lecture behaviour (issue 46, item 4), in-process on an OSMesa window: the run is held while a
// lesson's prediction question is open and goes on as it was once it is answered or closed;
// reset after the run's end leaves no table of zeros; every tab is reachable in every layout;
// the palette and the Parameters panel name a tunable the same way, with subscripts, and the
// palette lights one row; radio buttons, checkboxes and text meet the text contrast (4.5:1) in
// every theme.
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/gui/compare_panel.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/tunable_label.hpp"
#include "app/render/contrast.hpp"
#include "app/render/label_markup.hpp"
#include "app/render/theme.hpp"
#include "sim/session/session.hpp"
#include "tests/app/ui_window.hpp"

namespace formsim::app {
namespace {

using testing::TempDir;
using testing::UiWindow;

// The settings file of these tests (lesson progress): a folder of their own.
void LectureSettingsDir(const std::string& name) {
  const std::string dir = TempDir(name) + "/config";
  ::setenv("XDG_CONFIG_HOME", dir.c_str(), 1);
}

void LectureFrames(UiWindow& w, int n) {
  for (int i = 0; i < n; ++i) w.Frame();
}

// ---- 1. The run pauses while a prediction question is open.

TEST(GuiLecture, APredictionQuestionHoldsTheRunThenItGoesOnAsItWas) {
  LectureSettingsDir("lecture_hold");
  UiWindow w("formation_traj2", 1600, 900);
  AppUi& ui = w.ui();
  RunPanel& run = *ui.Find<RunPanel>();
  // Playing, then a step with a question: the run stops at once and waits.
  ASSERT_EQ(ui.RunScriptAction("lesson lphi_time_constant"), "");
  ASSERT_EQ(ui.RunScriptAction("lesson-step 4"), "");
  ASSERT_EQ(ui.RunScriptAction("play"), "");
  LectureFrames(w, 6);
  EXPECT_TRUE(ui.Find<LessonPanel>()->QuestionOpen());
  EXPECT_EQ(ui.session().exp().steps(), 0) << "the run went on while the question was open";
  EXPECT_FALSE(ui.state().playing);
  EXPECT_TRUE(run.Playing());  // it will play once answered
  EXPECT_NE(run.HeldText().find("prediction"), std::string::npos);
  // Answered: it plays again by itself.
  ASSERT_EQ(ui.RunScriptAction("lesson-predict 1"), "");
  LectureFrames(w, 6);
  EXPECT_FALSE(ui.Find<LessonPanel>()->QuestionOpen());
  EXPECT_TRUE(ui.state().playing);
  EXPECT_GT(ui.session().exp().steps(), 0);
  EXPECT_EQ(run.HeldText(), "");

  // Paused when the question opens: it stays paused once answered.
  ASSERT_EQ(ui.RunScriptAction("pause"), "");
  ASSERT_EQ(ui.RunScriptAction("lesson noise_and_ukf"), "");
  ASSERT_EQ(ui.RunScriptAction("lesson-step 2"), "");
  LectureFrames(w, 4);
  EXPECT_TRUE(ui.Find<LessonPanel>()->QuestionOpen());
  EXPECT_FALSE(run.Playing());
  ASSERT_EQ(ui.RunScriptAction("lesson-predict 1"), "");
  LectureFrames(w, 4);
  EXPECT_FALSE(ui.state().playing);
  EXPECT_EQ(ui.session().exp().steps(), 0);

  // Closed without an answer (another tab brought over it): it goes on as it was (playing).
  ui.state().settings.lessons.clear();
  ASSERT_EQ(ui.RunScriptAction("lesson noise_and_ukf"), "");
  ASSERT_EQ(ui.RunScriptAction("lesson-step 2"), "");
  ASSERT_EQ(ui.RunScriptAction("play"), "");
  LectureFrames(w, 4);
  const long held_at = ui.session().exp().steps();
  LectureFrames(w, 4);
  EXPECT_EQ(ui.session().exp().steps(), held_at);
  EXPECT_TRUE(ui.Find<LessonPanel>()->QuestionOpen());
  ASSERT_EQ(ui.RunScriptAction("tab plots"), "");
  LectureFrames(w, 4);
  EXPECT_FALSE(ui.Find<LessonPanel>()->QuestionOpen());
  EXPECT_TRUE(ui.state().playing);
  EXPECT_GT(ui.session().exp().steps(), held_at);
}

// ---- 2. Reset after the run's end clears every table.

// The ImGui tables drawn in the last frame inside window `name`.
int LectureTablesDrawnIn(const char* name) {
  ImGuiContext& g = *ImGui::GetCurrentContext();
  const ImGuiWindow* win = ImGui::FindWindowByName(name);
  int n = 0;
  for (int i = 0; i < g.Tables.GetMapSize(); ++i)
    if (ImGuiTable* t = g.Tables.TryGetMapData(i))
      if (t->LastFrameActive == g.FrameCount && t->OuterWindow != nullptr &&
          t->OuterWindow->RootWindow == win)
        ++n;
  return n;
}

TEST(GuiLecture, ResetAfterTheEndLeavesNoTableOfZeros) {
  LectureSettingsDir("lecture_reset");
  UiWindow w("formation_traj2", 1600, 900);
  AppUi& ui = w.ui();
  while (!ui.session().exp().finished()) ui.session().Step();
  ASSERT_EQ(ui.RunScriptAction("pin"), "");
  for (int i = 0; i < 2000 && ui.Busy(); ++i) w.Frame();
  ASSERT_FALSE(ui.Busy());
  ASSERT_EQ(ui.RunScriptAction("tab tables"), "");
  LectureFrames(w, 3);
  const int at_end = LectureTablesDrawnIn("Plots###plots");
  EXPECT_GE(at_end, 2);  // the comparison and the results' tables

  ASSERT_EQ(ui.RunScriptAction("reset"), "");
  LectureFrames(w, 3);
  ASSERT_EQ(ui.session().exp().steps(), 0);
  // Only the comparison is left, its live column empty: nothing is cut to 0 s.
  EXPECT_EQ(LectureTablesDrawnIn("Plots###plots"), 1);
  std::string title;
  const auto runs = ui.Find<ComparePanel>()->CompareRuns(ui.session().exp().Results(), &title);
  EXPECT_EQ(title.find("0 ... 0.0 s"), std::string::npos) << title;
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_TRUE(runs[0].no_data);
  EXPECT_EQ(runs[0].metrics, nullptr);
  EXPECT_EQ(runs[0].header, "now (no data yet)");
  EXPECT_NE(runs[1].metrics, nullptr);
  EXPECT_EQ(runs[1].header, "pin 1 (11.0 s)");
  // Without a pin, nothing but the empty state.
  ASSERT_EQ(ui.RunScriptAction("unpin-all"), "");
  LectureFrames(w, 2);
  EXPECT_EQ(LectureTablesDrawnIn("Plots###plots"), 0);
}

// ---- 3. Every tab is reachable in every layout.

// The name of the tab selected in the tab bar of the window "Plots###plots".
std::string LectureSelectedTab() {
  ImGuiWindow* win = ImGui::FindWindowByName("Plots###plots");
  if (win == nullptr || !win->Active) return "";
  ImGuiTabBar* bar = ImGui::GetCurrentContext()->TabBars.GetByKey(ImHashStr("tabs", 0, win->ID));
  if (bar == nullptr) return "";
  for (const ImGuiTabItem& tab : bar->Tabs)
    if (tab.ID == bar->SelectedTabId) return bar->GetTabName(&tab);
  return "";
}

TEST(GuiLecture, EveryTabIsReachableInEveryLayout) {
  LectureSettingsDir("lecture_tabs");
  struct Layout {
    const char* name;
    int w, h;
    bool present;
  };
  // 1280x800 at UI scale 1.5 is 853x533 font units: the narrow layout.
  for (const Layout& l : {Layout{"narrow", 853, 533, false}, Layout{"wide", 1600, 900, false},
                          Layout{"presentation", 1600, 900, true}}) {
    UiWindow w("formation_traj2", l.w, l.h);
    AppUi& ui = w.ui();
    ASSERT_EQ(ui.RunScriptAction("lesson lphi_time_constant"), "") << l.name;
    for (const char* tab : {"controls", "lesson", "plots", "tables", "history", "summary"}) {
      if (l.present) {
        ASSERT_EQ(ui.RunScriptAction("present on"), "");
      }
      LectureFrames(w, 2);
      EXPECT_EQ(ui.RunScriptAction(std::string("tab ") + tab), "") << l.name << " " << tab;
      LectureFrames(w, 3);
      EXPECT_FALSE(ui.state().present) << l.name << ": presentation is left to show " << tab;
      EXPECT_EQ(ui.state().select_tab, "") << l.name << " " << tab << ": never left waiting";
      std::string want = tab;
      want[0] = static_cast<char>(want[0] - 'a' + 'A');
      if (std::string(tab) == "controls" && std::string(l.name) != "narrow") {
        // The control panel is always in view beside the world view.
        const ImGuiWindow* controls = ImGui::FindWindowByName("formsim");
        ASSERT_NE(controls, nullptr);
        EXPECT_TRUE(controls->Active) << l.name;
      } else {
        EXPECT_EQ(LectureSelectedTab(), want) << l.name;
      }
    }
  }
  // A tab that is not there is refused with the reason, never left pending.
  UiWindow w("formation_traj2", 1600, 900);
  EXPECT_NE(w.ui().RunScriptAction("tab lesson").find("no lesson"), std::string::npos);
  EXPECT_EQ(w.ui().state().select_tab, "");
}

// ---- 4. One name for a tunable, with subscripts; one highlighted row in the palette.

TEST(GuiLecture, PaletteAndParametersNameATunableAlikeWithSubscripts) {
  EXPECT_EQ(TunableLabelMarkup("k l1"), "k_{l1}");
  EXPECT_EQ(TunableLabelMarkup("k l"), "k_{l}");
  EXPECT_EQ(TunableLabelMarkup("k φ"), "k_{φ}");
  EXPECT_EQ(TunableLabelMarkup("φ desired"), "φ_{des}");
  EXPECT_EQ(TunableLabelMarkup("l2 desired"), "l_{2,des}");
  EXPECT_EQ(TunableLabelMarkup("σ x,y"), "σ_{x,y}");
  EXPECT_EQ(TunableLabelMarkup("v_ref"), "v_{ref}");
  EXPECT_EQ(TunableLabelMarkup("spiral R0"), "spiral R_{0}");
  EXPECT_EQ(TunableLabelMarkup("leader v"), "leader v");
  EXPECT_EQ(TunableLabelMarkup("k obstacle"), "k obstacle");
  EXPECT_EQ(TunableLabelMarkup("innovation gate (≤0 off)"), "innovation gate (≤0 off)");
  EXPECT_EQ(MarkupText(TunableLabelMarkup("k l1")), "kₗ₁");

  UiWindow w("formation_cascade7", 1600, 900);
  AppUi& ui = w.ui();
  const sim::Param* p = ui.session().params().Find("robots.R3.follow.k_l");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(TunableLabel(*p), "k_{l1}");
  bool found = false;
  for (const PaletteEntry& e : ui.PaletteEntries("k_l R3")) {
    if (e.name != p->key) continue;
    found = true;
    EXPECT_NE(e.detail_markup.find(TunableLabel(*p)), std::string::npos) << e.detail_markup;
    EXPECT_NE(e.detail.find("kₗ₁"), std::string::npos) << e.detail;
    EXPECT_EQ(e.detail.find("k l1"), std::string::npos) << e.detail;
  }
  EXPECT_TRUE(found);
}

// The rows of the palette drawn highlighted in the last frame (Header, HeaderHovered or
// HeaderActive quads in its draw list).
int LecturePaletteRowsLit() {
  const ImGuiWindow* win = ImGui::FindWindowByName("##palette");
  if (win == nullptr || !win->Active) return -1;
  std::vector<ImU32> cols;
  for (ImGuiCol c : {ImGuiCol_Header, ImGuiCol_HeaderHovered, ImGuiCol_HeaderActive})
    cols.push_back(ImGui::GetColorU32(c));
  int verts = 0;
  for (const ImDrawVert& v : win->DrawList->VtxBuffer)
    for (ImU32 c : cols)
      if (v.col == c) {
        ++verts;
        break;
      }
  return verts / 4;
}

TEST(GuiLecture, ThePaletteLightsOneRowTheMouseMovesIt) {
  UiWindow w("formation_cascade7", 1600, 900);
  AppUi& ui = w.ui();
  ASSERT_EQ(ui.RunScriptAction("palette k_l"), "");
  LectureFrames(w, 2);
  EXPECT_EQ(LecturePaletteRowsLit(), 1);
  const ImGuiWindow* win = ImGui::FindWindowByName("##palette");
  ASSERT_NE(win, nullptr);
  const float x = win->Pos.x + 0.5f * win->Size.x;
  // The mouse down the palette: the row under it becomes the selected one, the only one lit.
  bool moved = false;
  for (float y = win->Pos.y; y < win->Pos.y + win->Size.y && !moved; y += 3) {
    w.Frame([&](ImGuiIO& io) { io.MousePos = ImVec2(x, y); });
    if (ui.state().palette_selected >= 2) moved = true;
  }
  ASSERT_TRUE(moved) << "hovering a row does not select it";
  w.Frame();  // the mouse rests
  EXPECT_EQ(LecturePaletteRowsLit(), 1);
  // The keys move the selection from there; the row under the resting mouse is not lit.
  w.Frame([](ImGuiIO& io) {
    io.KeyMap[ImGuiKey_DownArrow] = 264;
    io.KeysDown[264] = true;
  });
  w.Frame();
  EXPECT_EQ(LecturePaletteRowsLit(), 1);
}

// ---- 5. Radio buttons, checkboxes and text meet the text contrast in every theme.

sim::Color LectureCol(const ImVec4& v) { return {v.x, v.y, v.z, v.w}; }

TEST(GuiLecture, WidgetsAndTextMeetTheTextContrastInEveryTheme) {
  UiWindow w("formation_traj2", 800, 600);  // an ImGui context
  for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint, ThemeId::kHighContrast}) {
    const Theme& theme = GetTheme(id);
    ApplyImGuiTheme(theme);
    const ImGuiStyle& s = ImGui::GetStyle();
    auto c = [&](ImGuiCol k) { return LectureCol(s.Colors[k]); };
    const sim::Color window = Over(c(ImGuiCol_WindowBg), sim::Color{0, 0, 0, 1});
    // The boxes and circles have a visible edge.
    EXPECT_GE(s.FrameBorderSize, 1.0f) << theme.name;
    for (const sim::Color base :
         {window, Over(c(ImGuiCol_PopupBg), window), Over(c(ImGuiCol_ChildBg), window)}) {
      EXPECT_GE(ContrastRatio(Over(c(ImGuiCol_Border), base), base), kTextContrast)
          << theme.name << ": the edge of a checkbox or radio button";
      for (ImGuiCol frame : {ImGuiCol_FrameBg, ImGuiCol_FrameBgHovered, ImGuiCol_FrameBgActive}) {
        const sim::Color bg = Over(c(frame), base);
        EXPECT_GE(ContrastRatio(Over(c(ImGuiCol_CheckMark), bg), bg), kTextContrast)
            << theme.name << ": the check mark on " << ImGui::GetStyleColorName(frame);
      }
      for (ImGuiCol surface :
           {ImGuiCol_WindowBg, ImGuiCol_PopupBg, ImGuiCol_FrameBg, ImGuiCol_FrameBgHovered,
            ImGuiCol_FrameBgActive, ImGuiCol_Header, ImGuiCol_HeaderHovered,
            ImGuiCol_HeaderActive, ImGuiCol_Button, ImGuiCol_ButtonHovered,
            ImGuiCol_ButtonActive, ImGuiCol_Tab, ImGuiCol_TabHovered, ImGuiCol_TabActive,
            ImGuiCol_TableHeaderBg, ImGuiCol_TableRowBgAlt, ImGuiCol_MenuBarBg}) {
        const sim::Color bg = Over(c(surface), base);
        for (ImGuiCol text : {ImGuiCol_Text, ImGuiCol_TextDisabled})
          EXPECT_GE(ContrastRatio(Over(c(text), bg), bg), kTextContrast)
              << theme.name << ": " << ImGui::GetStyleColorName(text) << " on "
              << ImGui::GetStyleColorName(surface);
      }
    }
  }
  ApplyImGuiTheme(GetTheme(ThemeId::kLight));
}

}  // namespace
}  // namespace formsim::app
