// Bounded inputs through the built binary (issue 21): devices, FIFOs and billion-laughs documents
// given to `run`, `replay` and `gui --script`; the sweep's run numbers, run count and seeds; run
// files edited to hold nan; `scrub` outside the run in the window. Each case is checked by its
// exit status and message (the file named, the line of the alias), never by a clock.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/export/video_writer.hpp"
#include "sim/session/session_record.hpp"
#include "sim/study/sweep_store.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;
using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

std::string Fixture(const std::string& name) {
  return std::string(FORMSIM_SOURCE_DIR) + "/tests/fixtures/invalid/" + name;
}

// Runs formsim with `args`; returns the exit status, the output in *log.
int Formsim(const std::string& args, const std::string& dir, std::string* log) {
  const int rc = RunShell(Binary() + " " + args, dir + "/out.log");
  *log = ReadText(dir + "/out.log");
  return rc;
}

bool Has(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

TEST(InputLimits, RunRefusesDevicesFoldersFifosAndTheBillionLaughs) {
  const std::string dir = TempDir("limits_run");
  std::string log;
  EXPECT_EQ(Formsim("run /dev/zero --out " + dir + "/a -q", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, "/dev/zero: is not a regular file (a device)")) << log;
  const std::string fifo = dir + "/fifo.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(Formsim("run " + fifo + " --out " + dir + "/b -q", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, fifo + ": is not a regular file (a FIFO)")) << log;
  const std::string laughs = Fixture("input_billion_laughs.yaml");
  EXPECT_EQ(Formsim("run " + laughs + " --out " + dir + "/c -q", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, laughs + ":12:8: alias '*f' makes the document expand to more than "
                                "1000000 nodes"))
      << log;
  // A --set value carrying aliases is bounded the same way.
  EXPECT_EQ(Formsim("run formation_traj2 --set 'formation.L=[&a [1,1,1,1,1,1,1,1,1,1], "
                    "&b [*a,*a,*a,*a,*a,*a,*a,*a,*a,*a], &c [*b,*b,*b,*b,*b,*b,*b,*b,*b,*b], "
                    "&d [*c,*c,*c,*c,*c,*c,*c,*c,*c,*c], &e [*d,*d,*d,*d,*d,*d,*d,*d,*d,*d], "
                    "&f [*e,*e,*e,*e,*e,*e,*e,*e,*e,*e], [*f,*f,*f,*f,*f,*f,*f,*f,*f,*f]]' --out " +
                        dir + "/d -q",
                    dir, &log),
            2)
      << log;
  EXPECT_TRUE(Has(log, "makes the document expand to more than 1000000 nodes")) << log;
  // The --script file of the window is read the same way (refused before any window opens).
  EXPECT_EQ(Formsim("gui formation_traj2 --script /dev/zero", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, "--script '/dev/zero': is not a regular file (a device)")) << log;
}

TEST(InputLimits, ReplayRefusesABillionLaughsAppendedToASession) {
  const std::string dir = TempDir("limits_replay");
  sim::SessionRecord record;
  sim::SessionEvent load;
  load.kind = sim::SessionEvent::Kind::kLoad;
  load.source = std::make_shared<sim::ScenarioSource>(
      sim::ScenarioSource::FromFile(testing::Scenario("formation_traj2")));
  record.Add(load);
  std::string text = record.ToYaml(20);
  const std::string path = dir + "/s.yaml";
  std::ofstream(path) << text;
  std::string log;
  // As written, it replays.
  ASSERT_EQ(Formsim("replay " + path + " --out " + dir + "/ok -q", dir, &log), 0) << log;
  const int first = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  const std::string laughs = ReadText(Fixture("input_billion_laughs.yaml"));
  text += laughs.substr(laughs.find("\na:") + 1);
  std::ofstream(path) << text;
  EXPECT_EQ(Formsim("replay " + path + " --out " + dir + "/r -q", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, path + ":" + std::to_string(first + 6) +
                           ":8: alias '*f' makes the "
                           "document expand"))
      << log;
  EXPECT_EQ(Formsim("replay /dev/zero --out " + dir + "/z -q", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, "/dev/zero: the session file is not a regular file (a device)")) << log;
}

TEST(InputLimits, SweepRunNumbersRunCountAndSeeds) {
  const std::string dir = TempDir("limits_sweep");
  const std::string base = "sweep formation_traj2 --set duration=0.2 --out " + dir + "/s ";
  std::string log;
  EXPECT_EQ(Formsim(base + "--vary formation.L=0.1,0.2 --run -1", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, "--run -1: a run number is 0 or more (runs are numbered 0 ... N-1)")) << log;
  EXPECT_EQ(Formsim(base + "--vary formation.L=0.1,0.2 --run 2", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, "--run 2: the sweep has runs 0 ... 1")) << log;
  // A million values: refused with the count, before anything is written.
  EXPECT_EQ(Formsim(base + "--vary formation.L=0.1:0.2:1000000", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log,
                  "the sweep has 1000000 runs (points x seeds), more than 100000; vary "
                  "fewer values, or allow it with --max-runs N (N <= 10000000)"))
      << log;
  EXPECT_FALSE(fs::exists(dir + "/s"));
  // 10^18 runs: counted without overflow.
  EXPECT_EQ(Formsim(base + "--vary formation.L=0.1:0.2:1000000 --vary "
                           "robots.R2.follow.k_l=0.1:1:1000000 --vary "
                           "robots.R2.follow.k_phi=0.1:1:1000000",
                    dir, &log),
            2)
      << log;
  EXPECT_TRUE(Has(log, "the sweep has 1000000000000000000 runs")) << log;
  // --max-runs lowers or raises the limit, within its own bounds.
  EXPECT_EQ(Formsim(base + "--vary formation.L=0.1:0.2:150 --max-runs 100", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, "the sweep has 150 runs (points x seeds), more than 100")) << log;
  EXPECT_EQ(Formsim(base + "--vary formation.L=0.1,0.2 --max-runs 0", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, "--max-runs 0: must be in 1 ... 10000000")) << log;
  EXPECT_EQ(Formsim(base + "--vary formation.L=0.1:0.2:3 --max-runs 3 --print-jobs", dir, &log), 0)
      << log;
  // Job lines carry --max-runs, so each of them defines the same sweep.
  EXPECT_TRUE(Has(log, " --max-runs 3 --out ")) << log;
  EXPECT_TRUE(Has(log, " --run 2\n")) << log;
  // An empty --seeds is refused, never read as the scenario's seed.
  EXPECT_EQ(Formsim(base + "--vary formation.L=0.1,0.2 --seeds ''", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, "--seeds '': no seeds")) << log;
  EXPECT_EQ(
      Formsim("tune formation_traj2 --param formation.L --metric a --seeds '' --out " + dir + "/t",
              dir, &log),
      2)
      << log;
  EXPECT_TRUE(Has(log, "--seeds '': no seeds")) << log;
}

TEST(InputLimits, ResumeAndCollectRefuseANanEditedIntoARunFile) {
  const std::string dir = TempDir("limits_nan");
  const std::string out = dir + "/s";
  const std::string sweep =
      "sweep formation_traj2 --set duration=0.2 --vary formation.L=0.1,0.2 "
      "--no-figures -q --out " +
      out;
  std::string log;
  ASSERT_EQ(Formsim(sweep, dir, &log), 0) << log;
  const std::string run = out + "/runs/000001.run";
  std::string text = ReadText(run);
  const std::size_t m = text.find("\nm ");
  ASSERT_NE(m, std::string::npos) << text;
  const std::size_t value = text.find(' ', text.find(' ', m + 1) + 1) + 1;
  const int line = static_cast<int>(std::count(text.begin(), text.begin() + m + 1, '\n')) + 1;
  text.replace(value, text.find('\n', value) - value, "nan");
  std::ofstream(run) << text;
  EXPECT_EQ(Formsim(sweep + " --resume", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, run + ":" + std::to_string(line) + ": metric '")) << log;
  EXPECT_TRUE(Has(log, "'nan' is not a finite number")) << log;
  EXPECT_EQ(Formsim("sweep collect " + out + " --out " + dir + "/c -q", dir, &log), 2) << log;
  EXPECT_TRUE(Has(log, run + ":" + std::to_string(line) + ": metric '")) << log;
  EXPECT_TRUE(Has(log, "'nan' is not a finite number")) << log;
}

TEST(InputLimits, ScrubOutsideTheRunIsRefusedAndBranchStaysSane) {
  if (FindOnPath("xvfb-run").empty()) GTEST_SKIP() << "xvfb-run not installed";
  const std::string dir = TempDir("limits_scrub");
  std::ofstream(dir + "/script.txt")
      << "1 step\n2 step\n3 step\n4 scrub 1e308\n5 scrub 1000\n6 scrub -1\n7 branch\n"
         "8 scrub 0.01\n9 branch\n";
  const int rc = RunShell(testing::Xvfb(Binary() +
                                        " gui formation_traj2 --paused --size 800x600 "
                                        "--exit-after 30 --script " +
                                        dir + "/script.txt"),
                          dir + "/gui.log");
  const std::string log = ReadText(dir + "/gui.log");
  EXPECT_EQ(rc, 0) << log;
  // 1e308 and -1 are refused by the command's argument range, 1000 s by the run's end.
  EXPECT_TRUE(Has(log, "'scrub 1e308' refused: scrub: T expects a number in 0 ... 1000000000"))
      << log;
  EXPECT_TRUE(Has(log,
                  "'scrub 1000' refused: scrub: t = 1000 s is outside the run so far, 0 ... "
                  "0.03 s"))
      << log;
  EXPECT_TRUE(Has(log, "'scrub -1' refused")) << log;
  EXPECT_TRUE(Has(log, "'branch' refused: branch: move the timeline back first")) << log;
  EXPECT_FALSE(Has(log, "-9223372036854775808")) << log;
}

}  // namespace
}  // namespace formsim::app
