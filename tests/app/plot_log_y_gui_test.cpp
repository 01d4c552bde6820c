// The window's log y axes: the script action `log-y PLOT on|off` (a row of the command table)
// sets a time plot's axis and is refused for what is no time plot, listing the time plots.
#include <gtest/gtest.h>

#include "app/gui/plots_panel.hpp"
#include "tests/app/ui_window.hpp"

namespace formsim::app {
namespace {

TEST(PlotLogYGui, ScriptActionSetsAndClearsAPlotsLogAxis) {
  testing::UiWindow w("formation_traj2", 1600, 900);
  ASSERT_EQ(w.ui().RunScriptAction("step"), "");
  ASSERT_EQ(w.ui().RunScriptAction("log-y distance_error on"), "");
  EXPECT_EQ(w.ui().Find<PlotsPanel>()->LogY("distance_error"), true);
  for (int i = 0; i < 3; ++i) w.Frame();  // drawn with the log axis
  const std::string why = w.ui().RunScriptAction("log-y trajectories on");
  EXPECT_NE(why.find("PLOT expects"), std::string::npos) << why;
  EXPECT_NE(why.find("distance_error"), std::string::npos) << why;
  EXPECT_NE(w.ui().RunScriptAction("log-y distance_error sideways").find("on, off"),
            std::string::npos);
  ASSERT_EQ(w.ui().RunScriptAction("log-y distance_error off"), "");
  EXPECT_EQ(w.ui().Find<PlotsPanel>()->LogY("distance_error"), false);
  w.Frame();
}

}  // namespace
}  // namespace formsim::app
