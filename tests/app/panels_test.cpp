// The window's panels (app/gui/panel.hpp): the one command table is assembled from the panels'
// rows in its documented order, and the formation kind's own panel (the Formation editor) is
// there exactly when the experiment exposes formation::FormationEditing.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "app/gui/command_table.hpp"
#include "app/gui/formation_editor_panel.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "tests/app/ui_window.hpp"

namespace formsim::app {
namespace {

int GroupIndex(const Command& c) {
  static const std::vector<std::string> kGroups = {"File", "Run", "View", "Compare", "",
                                                   "Formation", "Help"};
  const std::string top = c.menu.substr(0, c.menu.find('/'));
  for (std::size_t i = 0; i < kGroups.size(); ++i)
    if (kGroups[i] == top) return static_cast<int>(i);
  return -1;
}

TEST(Panels, TheTableHoldsEachPanelsRowsOnceInItsOrder) {
  std::set<std::string> names;
  for (const Command& c : Commands()) EXPECT_TRUE(names.insert(c.name).second) << c.name;
  // Each panel's rows are in the table, as the panel registers them, in the panel's order.
  for (const auto& rows :
       {FormationEditorPanel::Rows(), HistoryPanel::Rows(), LessonPanel::Rows(),
        TimelinePanel::Rows()}) {
    ASSERT_FALSE(rows.empty());
    std::size_t last = 0;
    for (const Command& r : rows) {
      const Command* c = FindCommand(r.name);
      ASSERT_NE(c, nullptr) << r.name;
      EXPECT_EQ(c->menu, r.menu);
      EXPECT_EQ(c->Usage(), r.Usage());
      const auto at = static_cast<std::size_t>(c - Commands().data());
      EXPECT_GE(at, last) << r.name << " out of its panel's order";
      last = at;
    }
  }
  // Grouped by menu: File, Run, View, Compare, the script-only rows, Formation, Help.
  int group = 0;
  for (const Command& c : Commands()) {
    const int g = GroupIndex(c);
    ASSERT_GE(g, 0) << c.name << ": " << c.menu;
    EXPECT_GE(g, group) << c.name << " is out of its menu's group";
    group = g;
  }
  // The Formation menu is the Formation editor's rows, all of them.
  std::size_t formation_rows = 0;
  for (const Command& c : Commands()) formation_rows += GroupIndex(c) == 5;
  EXPECT_EQ(formation_rows, FormationEditorPanel::Rows().size());
}

TEST(Panels, TheFormationEditorIsTheFormationKindsOwn) {
  testing::UiWindow w("formation_traj2");
  AppUi& ui = w.ui();
  ASSERT_NE(ui.Find<FormationEditorPanel>(), nullptr);
  EXPECT_NE(ui.Find<LessonPanel>(), nullptr);
  EXPECT_NE(ui.Find<HistoryPanel>(), nullptr);
  EXPECT_EQ(ui.RunScriptAction("editor add l_phi"), "");
  EXPECT_EQ(ui.Find<FormationEditorPanel>()->mode(), FormationEditorPanel::EditMode::kAdd);
  EXPECT_EQ(ui.PanelToDismiss(), ui.Find<FormationEditorPanel>());
  // Esc stops the editor (before leaving presentation mode).
  EXPECT_EQ(ui.RunScriptAction("present on"), "");
  EXPECT_EQ(ui.PressKey("Esc"), "");
  EXPECT_EQ(ui.Find<FormationEditorPanel>()->mode(), FormationEditorPanel::EditMode::kOff);
  EXPECT_TRUE(ui.state().present);
  EXPECT_EQ(ui.PanelToDismiss(), nullptr);
  EXPECT_EQ(ui.PressKey("Esc"), "");
  EXPECT_FALSE(ui.state().present);
  // Another kind has no formation editor; a formation scenario loaded again gets a new one.
  EXPECT_EQ(ui.RunScriptAction("editor slots"), "");
  EXPECT_EQ(ui.RunScriptAction("load agv_fused"), "");
  w.Frame();
  EXPECT_EQ(ui.Find<FormationEditorPanel>(), nullptr);
  EXPECT_EQ(ui.PanelToDismiss(), nullptr);
  EXPECT_NE(ui.RunScriptAction("click 0 0").find("only for a formation scenario"),
            std::string::npos);
  EXPECT_EQ(ui.RunScriptAction("load formation_traj1"), "");
  ASSERT_NE(ui.Find<FormationEditorPanel>(), nullptr);
  EXPECT_EQ(ui.Find<FormationEditorPanel>()->mode(), FormationEditorPanel::EditMode::kOff);
  w.Frame();
}

TEST(Panels, TheTimelineOwnsItsState) {
  testing::UiWindow w("formation_traj2");
  AppUi& ui = w.ui();
  TimelinePanel* timeline = ui.Find<TimelinePanel>();
  ASSERT_NE(timeline, nullptr);
  for (int i = 0; i < 20; ++i) ASSERT_EQ(ui.RunScriptAction("step"), "");
  EXPECT_FALSE(timeline->Active());
  EXPECT_EQ(timeline->Shown(), nullptr);
  EXPECT_NE(ui.RunScriptAction("branch").find("move the timeline back first"), std::string::npos);
  EXPECT_EQ(ui.RunScriptAction("scrub 0"), "");
  ASSERT_TRUE(timeline->Active());
  ASSERT_NE(timeline->Shown(), nullptr);
  EXPECT_EQ(timeline->Shown()->steps(), 0);
  EXPECT_EQ(ui.session().exp().steps(), 20);
  w.Frame();  // the world view draws the replay, the strip its time
  EXPECT_EQ(ui.RunScriptAction("live"), "");
  EXPECT_FALSE(timeline->Active());
  EXPECT_EQ(ui.RunScriptAction("scrub 0"), "");
  EXPECT_EQ(ui.RunScriptAction("play"), "");  // playing goes on from the live end
  EXPECT_FALSE(timeline->Active());
}

}  // namespace
}  // namespace formsim::app
