// `formsim run` export flags for papers and slides, and `formsim figures`, through the built
// binary: clear errors for bad output names (nothing created), no partial file when ffmpeg
// fails, a looping GIF with the requested frames, progress on a terminal, all figures of
// several scenarios in one command (the same files as `run --plots`), and the GUI's themes.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <utility>

#include "app/export/png_writer.hpp"
#include "app/export/video_writer.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;
using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

std::string RunCmd(const std::string& args) {
  return "env -u DISPLAY " + Binary() + " run " + args;
}

// Every file of `a` has the bytes of the file of the same name in `b`; returns how many.
int ExpectSameFiles(const std::string& a, const std::string& b) {
  int compared = 0;
  for (const auto& e : fs::directory_iterator(a)) {
    const std::string bytes = ReadText(e.path().string());
    EXPECT_GT(bytes.size(), 1000u) << e.path();
    EXPECT_TRUE(bytes == ReadText(b + "/" + e.path().filename().string())) << e.path().filename();
    ++compared;
  }
  return compared;
}

TEST(FigureCli, BadOutputNamesAreClearErrorsThatCreateNothing) {
  const std::string dir = TempDir("cli_bad_names");
  struct Case {
    std::string args, flag, hint, must_not_exist;
  };
  const std::vector<Case> cases = {
      {"--plots " + dir + "/p.svg", "--plots", "--plot-format", dir + "/p.svg"},
      {"--frames " + dir + "/f.png", "--frames", "folder", dir + "/f.png"},
      {"--video " + dir + "/v.gif", "--video", "--gif", dir + "/v.gif"},
      {"--video " + dir + "/v.avi", "--video", ".mp4", dir + "/v.avi"},
      {"--gif " + dir + "/g.mp4", "--gif", ".gif", dir + "/g.mp4"},
      {"--snapshot " + dir + "/s.jpg", "--snapshot", ".svg", dir + "/s.jpg"},
      {"--snapshot " + dir + "/s.svg --ui", "--snapshot", "--ui", dir + "/s.svg"},
      {"--plots " + dir + "/p --plot-size 8.5cm", "--plot-size", "8.5cmx6cm", dir + "/p"},
      {"--plots " + dir + "/p --plot-format png,jpeg", "--plot-format", "png, svg, pdf",
       dir + "/p"},
      {"--plots " + dir + "/p --theme sepia", "--theme", "high-contrast", dir + "/p"},
      {"--plots " + dir + "/p --titles long", "--titles", "full|short|none", dir + "/p"},
      {"--plots " + dir + "/p --log-y nope", "--log-y", "distance_error", dir + "/p"},
      {"--plots " + dir + "/p --log-y trajectories", "--log-y", "the time plots: ", dir + "/p"},
      {"--plots " + dir + "/p --log-y distance_error,", "--log-y", "empty name", dir + "/p"},
      {"--plots " + dir + "/p --dpi 1200 --plot-size 30cmx20cm", "--plot-size", "--dpi 1200",
       dir + "/p"},
  };
  for (const Case& c : cases) {
    const int rc =
        RunShell(RunCmd("formation_traj2 -q --out " + dir + "/out " + c.args), dir + "/log.txt");
    const std::string log = ReadText(dir + "/log.txt");
    EXPECT_EQ(rc, 2) << c.args << "\n" << log;
    EXPECT_NE(log.find("error: " + c.flag + " "), std::string::npos) << c.args << "\n" << log;
    EXPECT_NE(log.find(c.hint), std::string::npos) << c.args << "\n" << log;
    EXPECT_FALSE(fs::exists(c.must_not_exist)) << c.args << " created " << c.must_not_exist;
    EXPECT_FALSE(fs::exists(dir + "/out/timeseries.csv")) << c.args << ": simulated anyway";
  }
  // --size errors still name --size.
  RunShell(RunCmd("formation_traj2 -q --out " + dir + "/out --size 100"), dir + "/log.txt");
  EXPECT_NE(ReadText(dir + "/log.txt").find("error: --size '100'"), std::string::npos);
}

// An empty file or folder name (an unset shell variable) is refused by the option's name before
// anything runs, in each command; it used to be taken as "not given" without a word.
TEST(FigureCli, AnEmptyFileOrFolderNameIsRefusedByName) {
  const std::string dir = TempDir("cli_empty_names");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run formation_traj2 -q --out " + dir + "/out --frames ''", "--frames"},
      {"run formation_traj2 -q --out " + dir + "/out --snapshot ''", "--snapshot"},
      {"run formation_traj2 -q --out " + dir + "/out --plots ''", "--plots"},
      {"run formation_traj2 -q --out " + dir + "/out --video ''", "--video"},
      {"run formation_traj2 -q --out " + dir + "/out --gif ''", "--gif"},
      {"run formation_traj2 -q --out ''", "--out"},
      {"figures formation_traj2 -q --out ''", "--out"},
      {"sweep formation_traj2 -q --out '' --seeds 1,2", "--out"},
  };
  for (const auto& [args, flag] : cases) {
    // From the test's folder: a command that took '' as "not given" would write into out/.
    const int rc = RunShell("cd " + dir + " && " + Binary() + " " + args, dir + "/log.txt");
    const std::string log = ReadText(dir + "/log.txt");
    EXPECT_EQ(rc, 2) << args << "\n" << log;
    EXPECT_NE(log.find("error: " + flag + " '': an empty name"), std::string::npos) << args << "\n"
                                                                                    << log;
    EXPECT_FALSE(fs::exists(dir + "/out")) << args << ": ran anyway";
  }
}

// --log-y: the named time plot gets decade ticks in its SVG; the others keep a linear axis.
// A frame rate out of range is named as typed in its shortest form (1e308 printed as %f was a
// 300-digit number).
TEST(FigureCli, AnFpsOutOfRangeIsRefusedInOneShortLine) {
  const std::string dir = TempDir("cli_bad_fps");
  for (const auto& [fps, shown] : {std::pair{"1e308", "got 1e+308"}, std::pair{"nan", "got nan"},
                                   std::pair{"-3", "got -3"}, std::pair{"0", "got 0"}}) {
    EXPECT_EQ(
        RunShell(RunCmd(std::string("formation_traj2 -q --fps ") + fps + " --frames " + dir + "/f"),
                 dir + "/log.txt"),
        2)
        << fps;
    const std::string log = ReadText(dir + "/log.txt");
    EXPECT_NE(log.find(shown), std::string::npos) << log;
    EXPECT_LT(log.size(), 200u) << log;
    EXPECT_FALSE(fs::exists(dir + "/f")) << fps;
  }
}

TEST(FigureCli, LogYGivesTheNamedPlotDecadeTicks) {
  const std::string dir = TempDir("cli_log_y");
  // 30 s: the distance errors fall through several decades.
  const int rc =
      RunShell(RunCmd("formation_traj2 --set duration=30 -q --out " + dir + "/out --plots " + dir +
                      "/p --plot-format svg --log-y " + "distance_error"),
               dir + "/log.txt");
  ASSERT_EQ(rc, 0) << ReadText(dir + "/log.txt");
  const std::string svg = ReadText(dir + "/p/distance_error.svg");
  EXPECT_NE(svg.find(">10⁻³</text>"), std::string::npos);
  EXPECT_NE(svg.find(">log y: "), std::string::npos) << "the errors cross zero: a note";
  EXPECT_EQ(ReadText(dir + "/p/alpha_error.svg").find(">10⁻"), std::string::npos);
}

// An ffmpeg that starts and then fails: the run's results are written, the export is reported
// (exit 4), and neither the video nor the GIF (nor a partial file) is left behind.
TEST(FigureCli, FailingFfmpegLeavesNoFileAndKeepsTheResults) {
  const std::string dir = TempDir("cli_bad_ffmpeg"),
                    log_file = TempDir("cli_bad_ffmpeg_log") + "/log.txt";
  fs::create_directories(dir + "/bin");
  {
    std::ofstream f(dir + "/bin/ffmpeg");
    // Like a real ffmpeg that dies mid-way: its output file exists (empty) when it fails.
    f << "#!/bin/sh\nfor last; do :; done\n: > \"$last\"\ncat >/dev/null\n"
         "echo 'ffmpeg: simulated failure' >&2\nexit 1\n";
  }
  chmod((dir + "/bin/ffmpeg").c_str(), 0755);
  for (const std::string& out : {"--video " + dir + "/v.mp4", "--gif " + dir + "/v.gif"}) {
    const int rc = RunShell("env -u DISPLAY PATH=" + dir + "/bin:/usr/bin:/bin " + Binary() +
                                " run formation_traj2 --set duration=1 -q --size 320x200 --out " +
                                dir + "/out " + out,
                            log_file);
    const std::string log = ReadText(log_file);
    EXPECT_EQ(rc, 4) << out << "\n" << log;
    EXPECT_NE(log.find("export failed (the results were written)"), std::string::npos) << log;
    EXPECT_TRUE(fs::exists(dir + "/out/summary.json"));
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) left.push_back(e.path().filename().string());
    EXPECT_TRUE(left.empty()) << out << " left " << left.front();
  }
}

TEST(FigureCli, GifHasTheRequestedFramesSizeAndLoops) {
  if (FindOnPath("ffprobe").empty()) GTEST_SKIP() << "ffprobe not installed";
  const std::string dir = TempDir("cli_gif");
  const std::string gif = dir + "/f8.gif";
  ASSERT_EQ(RunShell(RunCmd("formation_traj2 --set duration=2 -q --out " + dir + "/out --gif " +
                            gif + " --gif-fps 10 --gif-width 320"),
                     dir + "/log.txt"),
            0)
      << ReadText(dir + "/log.txt");
  ASSERT_EQ(RunShell("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                     "stream=nb_read_frames,width,height -of default=nw=1 " +
                         gif,
                     dir + "/probe.txt"),
            0);
  const std::string probe = ReadText(dir + "/probe.txt");
  EXPECT_NE(probe.find("nb_read_frames=20"), std::string::npos) << probe;
  EXPECT_NE(probe.find("width=320"), std::string::npos) << probe;
  EXPECT_NE(probe.find("height=180"), std::string::npos) << probe;
  const std::string bytes = ReadText(gif);
  EXPECT_EQ(bytes.substr(0, 6), "GIF89a");
  EXPECT_NE(bytes.find("NETSCAPE2.0"), std::string::npos) << "the GIF does not loop";
  // Slides want small files: 2 s at 320 px is far below a megabyte.
  EXPECT_LT(bytes.size(), 1u << 20);
}

// The target for slides: the 10 s figure-eight at 640 px wide under 5 MB.
TEST(FigureCli, TenSecondFigureEightGifIsUnderFiveMegabytes) {
  if (FindOnPath("ffprobe").empty()) GTEST_SKIP() << "ffprobe not installed";
  const std::string dir = TempDir("cli_gif_10s");
  const std::string gif = dir + "/f8.gif";
  ASSERT_EQ(
      RunShell(RunCmd("formation_traj2 --set duration=10 -q --out " + dir + "/out --gif " + gif),
               dir + "/log.txt"),
      0)
      << ReadText(dir + "/log.txt");
  ASSERT_EQ(RunShell("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                     "stream=nb_read_frames,width -of default=nw=1 " +
                         gif,
                     dir + "/probe.txt"),
            0);
  const std::string probe = ReadText(dir + "/probe.txt");
  EXPECT_NE(probe.find("nb_read_frames=150"), std::string::npos) << probe;  // 15 fps default
  EXPECT_NE(probe.find("width=640"), std::string::npos) << probe;
  EXPECT_LT(fs::file_size(gif), 5u * 1000 * 1000);
}

TEST(FigureCli, LongExportShowsFramesAndTimeLeftOnATerminal) {
  if (FindOnPath("script").empty()) GTEST_SKIP() << "script (util-linux) not installed";
  const std::string dir = TempDir("cli_progress");
  // `script` gives formsim a terminal; the progress line appears after half a second. 1280x720:
  // since the PNG encoder of issue 28, 180 frames of 640x360 are written in about that time.
  const std::string cmd = RunCmd("formation_traj2 --set duration=6 --out " + dir +
                                 "/out --frames " + dir + "/frames --size 1280x720");
  ASSERT_EQ(
      RunShell("script -qfec " + ShellQuote(cmd) + " " + dir + "/typescript", dir + "/log.txt"), 0)
      << ReadText(dir + "/log.txt");
  const std::string tty = ReadText(dir + "/typescript");
  EXPECT_NE(tty.find("/180 frames"), std::string::npos) << tty;
  EXPECT_NE(tty.find(" left"), std::string::npos) << tty;
  // Without a terminal nothing of it is printed.
  ASSERT_EQ(RunShell(RunCmd("formation_traj2 --set duration=6 --out " + dir + "/out2 --frames " +
                            dir + "/frames2 --size 640x360"),
                     dir + "/log2.txt"),
            0);
  EXPECT_EQ(ReadText(dir + "/log2.txt").find("frames  "), std::string::npos);
}

TEST(FigureCli, FiguresCommandDrawsEveryFigureOfEveryScenarioLikeRun) {
  const std::string dir = TempDir("cli_figures");
  ASSERT_EQ(
      RunShell("env -u DISPLAY " + Binary() + " figures formation_traj2 agv_odometry_only --out " +
                   dir + "/figs --plot-format svg,png -j 2",
               dir + "/log.txt"),
      0)
      << ReadText(dir + "/log.txt");
  const std::string log = ReadText(dir + "/log.txt");
  EXPECT_NE(log.find("for 2 scenarios"), std::string::npos) << log;
  long files = 0;
  for (const char* scen : {"formation_traj2", "agv_odometry_only"}) {
    const std::string d = dir + "/figs/" + scen;
    ASSERT_TRUE(fs::is_directory(d)) << d;
    long svg = 0, png = 0;
    for (const auto& e : fs::directory_iterator(d))
      (e.path().extension() == ".svg" ? svg : png) += 1;
    EXPECT_EQ(svg, png) << scen;
    EXPECT_GE(svg, 3) << scen;
    EXPECT_TRUE(fs::exists(d + "/world.svg")) << scen;
    EXPECT_TRUE(fs::exists(d + "/world.png")) << scen;
    files += svg + png;
  }
  // The count it reports is the files it wrote.
  EXPECT_NE(log.find("wrote " + std::to_string(files) + " files"), std::string::npos) << log;
  // The same figure as `formsim run --plots` writes, byte for byte.
  ASSERT_EQ(RunShell(RunCmd("formation_traj2 -q --out " + dir + "/run --plots " + dir +
                            "/plots --plot-format svg"),
                     dir + "/log.txt"),
            0);
  const std::string a = ReadText(dir + "/plots/phi_error.svg");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == ReadText(dir + "/figs/formation_traj2/phi_error.svg"));
  // Bad input is refused before anything runs.
  EXPECT_EQ(RunShell("env -u DISPLAY " + Binary() + " figures formation_traj2 no_such --out " +
                         dir + "/bad",
                     dir + "/log.txt"),
            2);
  EXPECT_FALSE(fs::exists(dir + "/bad"));
  EXPECT_EQ(
      RunShell("env -u DISPLAY " + Binary() + " figures formation_traj2 --out " + dir + "/bad.pdf",
               dir + "/log.txt"),
      2);
  EXPECT_NE(ReadText(dir + "/log.txt").find("--out"), std::string::npos);
}

// A worker left alone at the end takes the freed cores between two steps (issue 28): its
// figures stay those of a one-thread run, byte for byte. formation_traj2 ends long before
// formation_swarm_100, whose link filters then run on two threads.
TEST(FigureCli, FiguresOfAWorkerThatGainsThreadsMidRunAreThoseOfOneThread) {
  const std::string dir = TempDir("cli_figures_threads");
  ASSERT_EQ(RunShell("env -u DISPLAY " + Binary() +
                         " figures formation_swarm_100 formation_traj2 -q -j 2 --out " + dir +
                         "/figs",
                     dir + "/log.txt"),
            0)
      << ReadText(dir + "/log.txt");
  ASSERT_EQ(RunShell(RunCmd("formation_swarm_100 -q --threads 1 --out " + dir + "/run --plots " +
                            dir + "/plots"),
                     dir + "/log.txt"),
            0)
      << ReadText(dir + "/log.txt");
  EXPECT_GE(ExpectSameFiles(dir + "/plots", dir + "/figs/formation_swarm_100"), 3);
}

// --ui frames show the plots of their own step: the window redraws plots at most every 100 ms
// of wall time, which made which frames showed fresh plots depend on the machine's speed (two
// runs differed in 21 of 30 frames).
TEST(FigureCli, UiFramesAreTheSameInEveryRun) {
  const std::string dir = TempDir("cli_ui_frames_twice");
  for (const auto& [run, threads] : {std::pair{"a", "2"}, std::pair{"b", "1"}}) {
    ASSERT_EQ(
        RunShell(RunCmd(std::string("formation_traj2 --ui --set duration=3 -q --fps 10 ") +
                        "--size 960x540 --threads " + threads + " --frames " + dir + "/" + run),
                 dir + "/log.txt"),
        0)
        << ReadText(dir + "/log.txt");
  }
  EXPECT_EQ(ExpectSameFiles(dir + "/a", dir + "/b"), 30);
}

TEST(FigureCli, GuiThemeColoursTheWindow) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("cli_gui_theme");
  std::vector<std::uint8_t> light, dark;
  for (const std::string& theme : std::vector<std::string>{"light", "dark"}) {
    const std::string shot = dir + "/" + theme + ".png";
    ASSERT_EQ(RunShell(testing::Xvfb(Binary()) +
                           " gui formation_traj2 --size 960x600 --exit-after 5 --theme " + theme +
                           " --screenshot " + shot,
                       dir + "/log.txt"),
              0)
        << ReadText(dir + "/log.txt");
    int w = 0, h = 0;
    (theme == "light" ? light : dark) = ReadPng(shot, &w, &h);
  }
  // Mean brightness of the whole window.
  auto mean = [](const std::vector<std::uint8_t>& px) {
    double s = 0;
    for (std::size_t i = 0; i < px.size(); i += 4) s += px[i] + px[i + 1] + px[i + 2];
    return s / (3.0 * px.size() / 4);
  };
  EXPECT_GT(mean(light), 180);
  EXPECT_LT(mean(dark), 90);
}

}  // namespace
}  // namespace formsim::app
