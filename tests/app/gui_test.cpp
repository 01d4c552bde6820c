// The GUI under Xvfb (skipped only when xvfb-run is absent), and the CLI's headless mode with
// DISPLAY unset. Both run the built formsim binary.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/export/png_writer.hpp"
#include "sim/core/number_format.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"
#include "app/export/video_writer.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::NonBackgroundFraction;
using testing::ReadText;
using testing::RunShell;
using testing::Xvfb;
using testing::Scenario;
using testing::TempDir;

TEST(Gui, RunsUnderXvfbWithParameterChangesAndSavesAScreenshot) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_xvfb");
  // Parameter changes as if dragged: a live double, a choice, and a malformed value (refused).
  sim::Session probe(Scenario("formation_traj2_ukf"), {}, -1);
  std::string edits;
  int frame = 20;
  for (const auto& p : probe.params().all()) {
    if (p.kind == sim::Param::Kind::kDouble && p.tune.live && frame < 200) {
      edits += " --edit " + std::to_string(frame) + ":" + p.key + "=" +
               sim::FormatDouble(p.slider_min() + 0.3 * (p.slider_max() - p.slider_min()));
      frame += 15;
    } else if (p.kind == sim::Param::Kind::kChoice && frame < 200) {
      edits += " --edit " + std::to_string(frame) + ":" + p.key + "=" + p.choices.back();
      frame += 15;
    }
  }
  edits += " --edit 150:" + probe.params().all().front().key + "=not_a_value";
  const std::string shot = dir + "/gui.png";
  const int rc = RunShell(
      Xvfb(Binary() +
           " gui formation_traj2_ukf --size 960x600 --speed 5 --exit-after 300 --screenshot " +
           shot + edits),
      dir + "/log.txt");
  ASSERT_EQ(rc, 0) << ReadText(dir + "/log.txt");
  int w = 0, h = 0;
  const auto px = ReadPng(shot, &w, &h);
  EXPECT_EQ(w, 960);
  EXPECT_EQ(h, 600);
  EXPECT_GT(NonBackgroundFraction(px), 0.2) << "GUI screenshot looks blank";
}

TEST(Gui, RunWithoutEditsWritesTheSameCsvAsHeadless) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_csv");
  const std::string args = " formation_traj2 --set duration=2.5 --seed 7";
  ASSERT_EQ(
      RunShell("env -u DISPLAY " + Binary() + " run" + args + " -q --out " + dir + "/headless",
               dir + "/run.txt"),
      0)
      << ReadText(dir + "/run.txt");
  ASSERT_EQ(
      RunShell(Xvfb(Binary() + " gui" + args +
                    " --size 800x500 --speed max --exit-when-finished --exit-after 5000 --out " +
                    dir + "/gui"),
               dir + "/gui.txt"),
      0)
      << ReadText(dir + "/gui.txt");
  const std::string a = ReadText(dir + "/headless/timeseries.csv");
  const std::string b = ReadText(dir + "/gui/timeseries.csv");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "GUI and headless runs differ";
}

TEST(Cli, HeadlessExportWorksWithoutDisplay) {
  const std::string dir = TempDir("cli_headless");
  const int rc =
      RunShell("env -u DISPLAY " + Binary() + " run formation_traj2 --set duration=0.5 -q --out " +
                   dir + "/out --frames " + dir + "/frames --fps 10 --size 256x160 --ui",
               dir + "/log.txt");
  ASSERT_EQ(rc, 0) << ReadText(dir + "/log.txt");
  int w = 0, h = 0;
  const auto px = ReadPng(dir + "/frames/frame_00004.png", &w, &h);
  EXPECT_EQ(w, 256);
  EXPECT_EQ(h, 160);
  EXPECT_FALSE(std::filesystem::exists(dir + "/frames/frame_00005.png"));
}

TEST(Cli, VideoWithoutFfmpegIsAClearErrorBeforeSimulating) {
  const std::string dir = TempDir("cli_noffmpeg");
  const int rc =
      RunShell("env -u DISPLAY PATH=/nonexistent " + Binary() + " run formation_traj2 -q --out " +
                   dir + "/out --video " + dir + "/v.mp4",
               dir + "/log.txt");
  EXPECT_NE(rc, 0);
  const std::string log = ReadText(dir + "/log.txt");
  EXPECT_NE(log.find("ffmpeg"), std::string::npos) << log;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/timeseries.csv")) << "simulated anyway";
}

}  // namespace
}  // namespace formsim::app
