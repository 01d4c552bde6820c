// The interface in-process with synthetic mouse and keyboard input (an OSMesa context, no
// display): typing into a field never triggers a shortcut (even in the frame the click opens the
// field), the shortcuts work when nothing is being typed into, Ctrl+Z / Ctrl+Y undo and redo
// edits, and nothing in the parameter panel moves when an edit is made.
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <functional>
#include <map>

#include "app/gui/parameters_panel.hpp"
#include "app/render/imgui_layer.hpp"
#include "app/render/offscreen_context.hpp"
#include "app/gui/ui.hpp"
#include "tests/app/test_util.hpp"
#include "tests/app/ui_window.hpp"

namespace formsim::app {
namespace {

constexpr int kKeysW = 1600, kKeysH = 900;  // three columns: the control panel in view

using Window = testing::UiWindow;

TEST(GuiKeys, TypingIntoAFieldNeverTriggersAShortcut) {
  Window w("formation_traj2", kKeysW, kKeysH);
  const ImVec2 seed = w.Find("formsim", "seed", 60);
  ASSERT_GE(seed.y, 0) << "the seed field was not found";
  const long steps = w.ui().session().exp().steps();
  // The click that opens the field and the first characters in the same frame: the field was not
  // active in the frame before, which is when the old check looked.
  w.Frame([&](ImGuiIO& io) {
    io.MousePos = seed;
    io.MouseDown[0] = true;
    for (char c : std::string("0.03")) io.AddInputCharacter(c);
  });
  w.Frame([&](ImGuiIO& io) {
    for (char c : std::string("r.s 5")) io.AddInputCharacter(c);
  });
  w.Frame();
  EXPECT_EQ(w.ui().session().exp().steps(), steps) << "'.' typed into the field stepped the run";
  EXPECT_FALSE(w.ui().state().screenshot_requested)
      << "'s' typed into the field asked for a screenshot";
  EXPECT_NE(w.ui().state().status, "reset");
  // Click into the world view: the field lets go, and '.' steps again.
  w.Frame([&](ImGuiIO& io) {
    io.MousePos = ImVec2(kKeysW / 2, kKeysH / 2);
    io.MouseDown[0] = true;
  });
  w.Frame();
  w.Frame([&](ImGuiIO& io) { io.AddInputCharacter('.'); });
  EXPECT_EQ(w.ui().session().exp().steps(), steps + 1);
}

TEST(GuiKeys, CtrlZAndCtrlYUndoAndRedoEdits) {
  Window w;
  const std::string key = "robots.R2.follow.k_l";
  ASSERT_EQ(w.ui().Find<ParametersPanel>()->CmdEdit(key, "0.4"), "");
  w.Frame();
  w.Frame([&](ImGuiIO& io) {
    io.MousePos = ImVec2(kKeysW / 2, kKeysH / 2);
    io.KeyCtrl = true;
    io.KeysDown[int{'Z'}] = true;  // GLFW's key code of a letter is its capital
  });
  EXPECT_EQ(w.ui().session().EffectiveValue(key), "0.15");
  w.Frame([&](ImGuiIO& io) {
    io.KeyCtrl = true;
    io.KeysDown[int{'Y'}] = true;  // GLFW's key code of a letter is its capital
  });
  EXPECT_EQ(w.ui().session().EffectiveValue(key), "0.4");
  w.Frame([&](ImGuiIO& io) {
    io.KeyCtrl = io.KeyShift = true;  // Ctrl+Shift+Z redoes too; here: nothing left to redo
    io.KeysDown[int{'Z'}] = true;     // GLFW's key code of a letter is its capital
  });
  EXPECT_EQ(w.ui().session().EffectiveValue(key), "0.4");
}

TEST(GuiKeys, NothingInTheParameterPanelMovesWhenAnEditIsMade) {
  Window w;
  // What is under each point of the lower panel: labels, sliders, marks.
  auto probe = [&] {
    std::map<std::pair<int, int>, ImGuiID> ids;
    for (int y = 420; y < kKeysH - 10; y += 7)
      for (int x : {40, 170, 230, 262, 280, 296}) ids[{x, y}] = w.Hover(ImVec2(x, y));
    return ids;
  };
  const auto before = probe();
  int widgets = 0;
  for (const auto& [p, id] : before) widgets += id != 0;
  ASSERT_GT(widgets, 20);
  // A live edit, an edit waiting for a reset (↻), both marked edited (↺).
  ASSERT_EQ(w.ui().Find<ParametersPanel>()->CmdEdit("robots.R2.follow.k_l", "0.4"), "");
  ASSERT_EQ(w.ui().Find<ParametersPanel>()->CmdEdit("formation.settle_time", "0.5"), "");
  ASSERT_EQ(w.ui().Find<ParametersPanel>()->CmdEdit("robots.R3.follow.k_l", "0.3"), "");
  w.Frame();
  EXPECT_TRUE(w.ui().session().IsEdited("formation.settle_time"));
  const auto after = probe();
  for (const auto& [p, id] : before) {
    if (id == 0) continue;
    EXPECT_EQ(after.at(p), id) << "the widget at (" << p.first << ", " << p.second << ") moved";
  }
  // And back: reverting puts the marks away without moving anything either.
  ASSERT_EQ(w.ui().Find<ParametersPanel>()->CmdRevert("formation.settle_time"), "");
  w.Frame();
  const auto reverted = probe();
  for (const auto& [p, id] : before) {
    if (id == 0) continue;
    EXPECT_EQ(reverted.at(p), id);
  }
}

}  // namespace
}  // namespace formsim::app
