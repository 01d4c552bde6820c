// Formation switching from the window (the experiment's buttons, key n, the script action
// `switch-formation [NAME]`) and lessons (`formsim gui --lesson NAME`, the Lesson tab,
// `formsim list`, `formsim run` of a lesson by name).
#include <gtest/gtest.h>
#include <imgui.h>

#include <filesystem>
#include <fstream>

#include "app/render/fonts.hpp"
#include "app/render/imgui_layer.hpp"
#include "app/render/offscreen_context.hpp"
#include "app/export/png_writer.hpp"
#include "app/export/video_writer.hpp"
#include "app/gui/ui.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/formation/formation_experiment.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::CountOf;
using testing::ReadText;
using testing::RunShell;
using testing::Scenario;
using testing::TempDir;
using testing::XvfbRun;

constexpr int kW = 1280, kH = 800;

// In-process, an OSMesa context and synthetic keys: n switches to the next shape; n again
// during the transition is refused (the run goes on); after it, n goes back to initial.
TEST(GuiTeaching, KeyNSwitchesToTheNextFormation) {
  OffscreenContext ctx(kW, kH);
  ImGuiLayer layer;
  AppUi ui(std::make_unique<sim::Session>(Scenario("formation_switching"),
                                          std::vector<sim::Override>{{"switching.schedule", "[]", "--set", -1}}));
  ui.state().playing = true;
  ASSERT_EQ(ui.RunScriptAction("speed 10"), "");  // a 2 s transition lasts about 12 frames
  auto frame = [&](char key) {
    ImGuiIO& io = ImGui::GetIO();
    if (key != 0) io.AddInputCharacter(key);
    layer.NewHeadlessFrame(kW, kH, 1.0f / 60.0f);
    ui.Advance(1.0 / 60.0);
    ui.Draw(ImVec2(kW, kH), layer.fonts(), true);
    ImGui::Render();
  };
  auto exp = [&]() -> const sim::formation::FormationExperiment& {
    return dynamic_cast<const sim::formation::FormationExperiment&>(ui.session().exp());
  };
  for (int k = 0; k < 3; ++k) frame(0);
  frame('n');
  frame(0);
  EXPECT_TRUE(exp().in_transition());
  frame('n');  // refused: a transition is in progress
  frame(0);
  EXPECT_EQ(ui.session().exp().events().Count("formation_switch"), 1);
  EXPECT_FALSE(ui.session().rejected().empty());
  EXPECT_NE(ui.session().rejected().back().find("in progress"), std::string::npos);
  while (ui.session().exp().time() < 3.0 && !ui.session().exp().finished()) frame(0);
  EXPECT_EQ(exp().shape(), 0);  // column
  frame('n');
  for (int k = 0; k < 3; ++k) frame(0);
  EXPECT_EQ(ui.session().exp().events().Count("formation_switch"), 2);
}

// Under Xvfb: `formsim gui --lesson` opens the lesson on its tab; the script action
// switch-formation switches (and refuses an unknown shape with the reason); the CSV and summary
// of --out hold the switch.
TEST(GuiTeaching, LessonWindowAndScriptedSwitch) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_teaching");
  {
    std::ofstream script(dir + "/script.txt");
    script << "2 switch-formation nosuch\n"   // refused: no such shape
           << "3 switch-formation column\n"
           << "40 screenshot " << dir << "/lesson.png\n";
  }
  const int rc = RunShell(XvfbRun("1600x900") + Binary() +
                              " gui --lesson switching_around_obstacles --set 'switching.schedule=[]' "
                              "--size 1600x900 --speed max --exit-after 45 --script " + dir +
                              "/script.txt --out " + dir + "/out",
                          dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  ASSERT_EQ(rc, 0) << log;
  EXPECT_EQ(CountOf(log, "refused"), 1) << log;
  EXPECT_NE(log.find("switch-formation:nosuch"), std::string::npos) << log;
  const std::string summary = ReadText(dir + "/out/summary.json");
  EXPECT_NE(summary.find("\"formation_switch\": 1"), std::string::npos) << summary.substr(0, 2000);
  EXPECT_NE(summary.find("(asked for)"), std::string::npos);
  ASSERT_TRUE(std::filesystem::exists(dir + "/lesson.png"));
  int w = 0, h = 0;
  const auto px = ReadPng(dir + "/lesson.png", &w, &h);
  EXPECT_EQ(w, 1600);
  EXPECT_GT(testing::NonBackgroundFraction(px), 0.05);
}

TEST(GuiTeaching, ListAndRunTakeLessons) {
  const std::string dir = TempDir("cli_lessons");
  ASSERT_EQ(RunShell(Binary() + " list", dir + "/list.txt"), 0);
  const std::string list = ReadText(dir + "/list.txt");
  EXPECT_NE(list.find("lessons (formsim gui --lesson NAME)"), std::string::npos) << list;
  EXPECT_NE(list.find("ll_singularity"), std::string::npos) << list;
  EXPECT_NE(list.find("formation_switching"), std::string::npos) << list;
  ASSERT_EQ(RunShell(Binary() + " run lphi_time_constant -q --set duration=0.5 --out " + dir + "/run",
                     dir + "/run.txt"),
            0)
      << ReadText(dir + "/run.txt");
  EXPECT_TRUE(std::filesystem::exists(dir + "/run/timeseries.csv"));
  const int bad = RunShell(Binary() + " gui --lesson no_such_lesson --exit-after 1", dir + "/bad.txt");
  EXPECT_NE(bad, 0);
  EXPECT_NE(ReadText(dir + "/bad.txt").find("the lessons are"), std::string::npos);
}

// Every character of a lesson's text is in the font atlas (fonts.cpp's ranges): the Lesson tab
// shows no '?' boxes for the equations.
TEST(GuiTeaching, LessonTextUsesOnlyGlyphsOfTheAtlas) {
  const unsigned short* ranges = FontGlyphRanges();
  auto in_atlas = [&](unsigned cp) {
    for (const unsigned short* r = ranges; r[0] != 0; r += 2)
      if (cp >= r[0] && cp <= r[1]) return true;
    return cp == '\n';
  };
  for (const std::string& file : sim::ShippedLessons()) {
    const std::string text = ReadText(file);
    for (std::size_t i = 0; i < text.size();) {
      const unsigned char c = static_cast<unsigned char>(text[i]);
      const int n = c < 0x80 ? 1 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : 4;
      unsigned cp = n == 1 ? c : c & (0xFF >> (n + 1));
      for (int k = 1; k < n && i + k < text.size(); ++k) cp = cp << 6 | (static_cast<unsigned char>(text[i + k]) & 0x3F);
      EXPECT_TRUE(in_atlas(cp)) << file << ": U+" << std::hex << cp << " at byte " << std::dec << i;
      i += static_cast<std::size_t>(n);
    }
  }
}

}  // namespace
}  // namespace formsim::app
