// Tuning in the window under Xvfb, driven by --script through the same commands as the mouse and
// keyboard: a recorded session replays headless to the same CSV byte for byte, "Run N seeds"
// gives the tables of `formsim sweep`, and pins, history, restore, undo, redo, revert, the
// timeline and branches do what they say (checked through the files the window writes).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/export/video_writer.hpp"
#include "sim/session/run_history.hpp"
#include "sim/session/session.hpp"
#include "sim/session/session_record.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

using testing::Binary;
using testing::CountOf;
using testing::ReadText;
using testing::RunShell;
using testing::Xvfb;
using testing::TempDir;

// Runs the GUI on `scenario` with `script`; returns the log (the exit code must be 0).
std::string Gui(const std::string& dir, const std::string& scenario, const std::string& script,
                const std::string& flags) {
  std::ofstream(dir + "/script.txt") << script;
  const int rc = RunShell(Xvfb(Binary() + " gui " + scenario + " --size 1000x640 " + flags +
                               " --script " + dir + "/script.txt"),
                          dir + "/gui.log");
  const std::string log = ReadText(dir + "/gui.log");
  EXPECT_EQ(rc, 0) << log;
  return log;
}

TEST(GuiTuning, ARecordedSessionReplaysToTheSameCsvByteForByte) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_replay");
  // Edits at several steps (stepped by hand and while playing), a reset, a seed change, a drag,
  // a pin, a branch from an earlier time with a new gain, and an edit waiting for a reset.
  const std::string script =
      "1 step\n2 step\n3 step\n"
      "4 edit robots.R2.follow.k_l=0.4\n"
      "5 step\n6 step\n"
      "7 edit robots.R2.follow.k_phi=0.2\n"
      "8 play\n20 pause\n"
      "21 reset-seed 7\n"
      "22 step\n23 step\n24 edit noise.phi_variance=2e-4\n25 step\n"
      "26 play\n33 edit formation.settle_time=0.5\n34 pause\n"
      "35 reset\n"
      "36 edit robots.R3.follow.k_l2=0.1\n"
      // Stepped past the time the branch starts from (playing alone depends on the frame rate).
      "37 step\n38 step\n39 step\n40 step\n41 step\n42 step\n43 step\n"
      "44 play\n50 pause\n"
      "51 pin\n52 wait\n"
      "53 scrub 0.05\n54 branch\n"
      "55 edit robots.R2.follow.k_l=0.25\n"
      "56 play\n66 pause\n"
      "67 step\n";
  const std::string log = Gui(dir, "formation_traj2_noisy_raw", script,
                              "--paused --speed 0.5 --set duration=3 --exit-after 70 --session " +
                                  dir + "/s.yaml --out " + dir + "/A");
  EXPECT_EQ(CountOf(log, "refused"), 0) << log;
  const sim::SessionRecord record = sim::SessionRecord::Read(dir + "/s.yaml");
  int resets = 0, seeds = 0, edits = 0, branches = 0;
  for (const auto& e : record.events()) {
    resets += e.kind == sim::SessionEvent::Kind::kReset;
    seeds += e.kind == sim::SessionEvent::Kind::kReset && e.has_seed;
    edits += e.kind == sim::SessionEvent::Kind::kEdit;
    branches += e.kind == sim::SessionEvent::Kind::kBranch;
  }
  EXPECT_EQ(resets, 2);
  EXPECT_EQ(seeds, 1);
  EXPECT_EQ(edits, 6);
  EXPECT_EQ(branches, 1);
  // The scenario file may change afterwards: the record holds its text.
  const std::string cmd =
      Binary() + " replay " + dir + "/s.yaml --out " + dir + "/B --plots " + dir + "/B/plots -q";
  ASSERT_EQ(RunShell(cmd, dir + "/replay.log"), 0) << ReadText(dir + "/replay.log");
  const std::string a = ReadText(dir + "/A/timeseries.csv"),
                    b = ReadText(dir + "/B/timeseries.csv");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "the replay's CSV differs from the window's";
  EXPECT_EQ(ReadText(dir + "/A/summary.json"), ReadText(dir + "/B/summary.json"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/B/plots/phi_error.png"));
  // A record that does not fit is refused with a reason naming the file and line.
  std::ofstream(dir + "/bad.yaml")
      << "formsim_session: 1\nscenarios: []\nevents:\n  - {do: load}\n";
  EXPECT_EQ(
      RunShell(Binary() + " replay " + dir + "/bad.yaml --out " + dir + "/C", dir + "/bad.log"), 2);
  EXPECT_NE(ReadText(dir + "/bad.log").find("bad.yaml:4: key 'step': missing"), std::string::npos)
      << ReadText(dir + "/bad.log");
}

TEST(GuiTuning, RunNSeedsGivesTheTablesOfFormsimSweep) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_seeds");
  const std::string script =
      "1 edit robots.R2.follow.k_l=0.3\n"
      "2 seeds 5000\n"
      "3 seeds 4\n"  // refused: one is running
      "4 cancel-seeds\n"
      "5 wait\n"
      "6 seeds 3\n"
      "7 wait\n"
      "8 cancel-seeds\n"  // refused: none is running
      "9 screenshot " +
      dir + "/band.png\n";
  const std::string log = Gui(dir, "formation_traj2_noisy_raw", script,
                              "--paused --set duration=2 --exit-after 11 --out " + dir + "/A");
  EXPECT_EQ(CountOf(log, "refused"), 2) << log;
  EXPECT_NE(log.find("a Monte Carlo is running"), std::string::npos) << log;
  const std::string cmd = Binary() +
                          " sweep formation_traj2_noisy_raw --set duration=2 --set "
                          "robots.R2.follow.k_l=0.3 --seeds 1..3 --out " +
                          dir + "/B -q";
  ASSERT_EQ(RunShell(cmd, dir + "/sweep.log"), 0) << ReadText(dir + "/sweep.log");
  for (const char* f : {"runs.csv", "aggregate.csv"}) {
    const std::string a = ReadText(dir + "/A/montecarlo/" + f), b = ReadText(dir + "/B/" + f);
    ASSERT_GT(a.size(), 100u) << f;
    EXPECT_TRUE(a == b) << f << " differs from formsim sweep's";
  }
}

TEST(GuiTuning, PinsHistoryRestoreUndoRedoRevertAndSavedHistory) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("gui_history");
  const std::string k_l = "robots.R2.follow.k_l";
  const std::string script =
      "1 pin\n"  // refused: nothing has run yet
      "2 step\n3 step\n4 pin\n5 wait\n"
      "6 unpin 9\n"  // refused
      "7 unpin 1\n8 pin\n9 unpin-all\n"
      "10 reset\n"  // history row 1 (k_l as loaded, seed 1)
      "11 edit " +
      k_l +
      "=0.4\n12 reset-seed 5\n13 step\n14 reset\n"  // row 2: k_l 0.4, seed 5
      "15 edit " +
      k_l +
      "=0.2\n"
      "16 restore 2\n"   // k_l back to 0.4 through the edit path, seed 5 into the seed field
      "17 restore 99\n"  // refused
      "18 pin-row 2\n19 wait\n"
      "20 edit robots.R2.follow.k_phi=0.3\n"
      "21 undo\n"  // k_phi back to the file's value
      "22 redo\n"  // and to 0.3 again
      "23 revert robots.R2.follow.k_phi\n"
      "24 branch\n"  // refused: the timeline is at the live end
      "25 save " +
      dir +
      "/tuned.yaml\n"
      "26 open " +
      dir +
      "/tuned.yaml\n"  // the history comes back with it
      "27 step\n28 reset\n"
      "29 save " +
      dir +
      "/again.yaml\n"
      "30 tab history\n31 screenshot " +
      dir + "/history.png\n";
  const std::string log = Gui(dir, "formation_traj2", script, "--paused --exit-after 33");
  EXPECT_EQ(CountOf(log, "refused"), 4) << log;
  EXPECT_NE(log.find("pin: the run has not started"), std::string::npos) << log;
  EXPECT_NE(log.find("no pin 9"), std::string::npos) << log;
  EXPECT_NE(log.find("no history row 99"), std::string::npos) << log;
  EXPECT_NE(log.find("move the timeline"), std::string::npos) << log;
  // The saved scenario: k_l restored to 0.4, k_phi reverted to the file's value.
  sim::Session saved(dir + "/tuned.yaml", {}, -1);
  EXPECT_EQ(saved.params().Find(k_l)->Text(), "0.4");
  EXPECT_EQ(saved.params().Find("robots.R2.follow.k_phi")->Text(), "0.08");
  // The history beside it, and again after reopening and one more reset.
  const sim::RunHistory h = sim::RunHistory::Load(dir + "/tuned.history.yaml");
  ASSERT_EQ(h.rows().size(), 2u);
  EXPECT_EQ(h.rows()[0].seed, 1u);
  EXPECT_EQ(h.rows()[1].seed, 5u);
  EXPECT_EQ(h.rows()[1].steps, 1);
  bool has_k_l = false;
  for (const auto& [k, v] : h.rows()[1].settings) has_k_l = has_k_l || (k == k_l && v == "0.4");
  EXPECT_TRUE(has_k_l);
  const sim::RunHistory h2 = sim::RunHistory::Load(dir + "/again.history.yaml");
  ASSERT_EQ(h2.rows().size(), 3u);
  EXPECT_EQ(h2.rows()[2].number, 3);
  EXPECT_TRUE(std::filesystem::exists(dir + "/history.png"));
}

}  // namespace
}  // namespace formsim::app
