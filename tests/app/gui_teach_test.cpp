// Teaching in the window, driven by --script through the same commands as the buttons and the
// mouse: the formation editor (add with picked leaders, remove, re-attach, switch law, drag a
// slot, shapes, undo / redo), refused changes (missing leader, cycle, impossible triangle, bad
// arguments) that keep the GUI alive, overlays, legend, help, presentation mode, UI scale and
// angle unit (kept in the settings file), Save of the edited formation, and the session record
// of it all replaying to the same CSV.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/export/png_writer.hpp"
#include "app/export/video_writer.hpp"
#include "sim/session/session.hpp"
#include "sim/formation/formation_editing.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::CountOf;
using testing::NonBackgroundFraction;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;
using testing::XvfbRun;

TEST(GuiTeach, EveryEditorActionAndRefusalKeepsTheGuiAlive) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_teach");
  // formation_traj2 paused at t = 0: R1 (0, 0), R2 (-0.2, -0.223), R3 (-0.285, -0.09).
  std::ofstream script(dir + "/script.txt");
  script << "2 editor add l_phi\n3 click 0 0\n4 click -0.6 0.25\n"  // R4, l-φ to R1
         << "5 editor add l_l\n6 click -0.2 -0.223\n7 click -0.285 -0.09\n"
         << "8 click -0.75 -0.45\n"                                     // R5, l-l to R2, R3
         << "9 editor remove\n10 click 0 0\n"                           // refused: R2, R3 follow R1
         << "11 editor attach l_phi\n12 click 0 0\n13 click -0.6 0.25\n"  // refused: a cycle
         << "14 editor law\n15 click -0.75 -0.45\n"                     // R5 becomes l-φ to R2
         << "16 editor slots\n17 click -0.6 0.25\n18 click -0.7 0.35\n"  // R4's slot moved
         << "19 formation add l_l R1,R2 -0.234 -0.1785\n"  // refused: M between R1 and R2, l1 + l2 < their separation
         << "20 formation shape grid 0.5\n"
         << "21 formation shape hexagon\n"                              // refused
         << "22 undo\n23 redo\n"
         << "24 overlay all\n25 overlay bogus\n"                        // refused
         << "26 legend off\n27 legend on\n"
         << "28 help on\n29 screenshot " << dir << "/help.png\n31 help off\n"
         << "32 present on\n33 ui-scale 2\n34 ui-scale 7\n"             // refused
         << "35 angle-unit rad\n36 angle-unit grad\n"                   // refused
         << "37 play\n60 screenshot " << dir << "/present.png\n"
         << "61 present off\n62 ui-scale 1\n63 pause\n"
         << "64 save " << dir << "/edited.yaml\n"
         << "65 editor bogus\n66 click nan 0\n"                          // refused
         << "67 editor off\n";
  script.close();
  const std::string cmd = "XDG_CONFIG_HOME=" + dir + "/config " + XvfbRun("1280x800") +
                          Binary() + " gui formation_traj2 --paused --size 1000x600 --speed max " +
                          "--set duration=3 --exit-after 70 --script " + dir + "/script.txt " +
                          "--session " + dir + "/s.yaml --out " + dir + "/A";
  const int rc = RunShell(cmd, dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  ASSERT_EQ(rc, 0) << log;
  EXPECT_EQ(CountOf(log, "refused"), 9) << log;
  EXPECT_NE(log.find("not a robot of this scenario"), std::string::npos) << log;
  EXPECT_NE(log.find("cycle"), std::string::npos) << log;
  EXPECT_NE(log.find("triangle"), std::string::npos) << log;
  EXPECT_NE(log.find("unknown overlay 'bogus'"), std::string::npos) << log;
  // The saved formation: five robots, the grid's graph, and it loads alone.
  sim::Session saved(dir + "/edited.yaml", {}, -1);
  EXPECT_EQ(saved.exp().world().robots().size(), 5u);
  EXPECT_TRUE(sim::formation::EditingOf(saved.exp())->LeadersOf("R1").empty());
  for (const char* f : {"R2", "R3", "R5"})
    EXPECT_FALSE(sim::formation::EditingOf(saved.exp())->LeadersOf(f).empty()) << f;
  // R4 sits behind R1, between R2 and R3 of the front row: l-l to them.
  EXPECT_EQ(sim::formation::EditingOf(saved.exp())->LeadersOf("R4"),
            (std::vector<std::string>{"R2", "R3"}));
  // The settings file keeps the last UI scale and the angle unit.
  const std::string settings = ReadText(dir + "/config/formsim/settings.yaml");
  EXPECT_NE(settings.find("ui_scale: 1"), std::string::npos) << settings;
  EXPECT_NE(settings.find("angle_unit: rad"), std::string::npos) << settings;
  for (const char* png : {"help.png", "present.png"}) {
    int w = 0, h = 0;
    const auto px = ReadPng(dir + "/" + png, &w, &h);
    EXPECT_EQ(w, 1000) << png;
    EXPECT_GT(NonBackgroundFraction(px), 0.05) << png;
  }
  // The session record replays the edited formation to the window's CSV, byte for byte.
  const std::string replay = Binary() + " replay " + dir + "/s.yaml --out " + dir + "/B -q";
  ASSERT_EQ(RunShell(replay, dir + "/replay.log"), 0) << ReadText(dir + "/replay.log");
  const std::string a = ReadText(dir + "/A/timeseries.csv"), b = ReadText(dir + "/B/timeseries.csv");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "the replay's CSV differs from the window's";
  EXPECT_NE(a.find("R5.x"), std::string::npos);
}

TEST(GuiTeach, OverlaysAreDrawnHeadlessAndBadNamesRefused) {
  const std::string dir = TempDir("teach_overlays");
  const std::string base = Binary() + " run formation_traj2_ukf --set duration=1 -q --size 640x400 --out " + dir;
  ASSERT_EQ(RunShell(base + "/a --snapshot " + dir + "/plain.png", dir + "/a.log"), 0);
  ASSERT_EQ(RunShell(base + "/b --overlay all --legend --snapshot " + dir + "/all.png", dir + "/b.log"), 0)
      << ReadText(dir + "/b.log");
  int w = 0, h = 0;
  const auto plain = ReadPng(dir + "/plain.png", &w, &h);
  const auto all = ReadPng(dir + "/all.png", &w, &h);
  // More is drawn with every overlay and the legend.
  EXPECT_GT(NonBackgroundFraction(all), NonBackgroundFraction(plain) + 0.005);
  EXPECT_EQ(RunShell(base + "/c --overlay slots,bogus --snapshot " + dir + "/c.png", dir + "/c.log"), 2);
  EXPECT_NE(ReadText(dir + "/c.log").find("--overlay 'slots,bogus': unknown overlay 'bogus'"),
            std::string::npos)
      << ReadText(dir + "/c.log");
}

}  // namespace
}  // namespace formsim::app
