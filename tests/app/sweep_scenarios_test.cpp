// `formsim sweep` over several scenarios end to end (the built binary on shipped scenarios,
// shortened): --scenario and @LIST, the scenario column, the same bytes with --jobs 1 and 2 and
// after a kill -9 and --resume, job lines and shards, the figure, and what is refused up front.
// The 64-bit seed flags of run, sweep and tune are checked here too.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>

#include "app/export/study_figures.hpp"
#include "sim/study/sweep_store.hpp"
#include "tests/app/test_util.hpp"

namespace formsim::app {
namespace {

namespace fs = std::filesystem;
using testing::Binary;
using testing::ReadText;
using testing::RunShell;
using testing::TempDir;

using testing::Formsim;

// A list of one more scenario, with a comment and a blank line.
std::string List() {
  const std::string list = TempDir("sweep_scen_list") + "/list.txt";
  std::ofstream(list) << "# the second trajectory\n\n  formation_traj2  # traj 2\n";
  return list;
}

// formation_traj1 and formation_traj2 (by @LIST), 2 values x 2 seeds: 8 runs.
std::string Sweep() {
  return " sweep formation_traj1 --scenario @" + List() +
         " --set duration=2 --vary robots.R2.follow.k_l=0.1,0.2 --seeds 1..2"
         " --metric links.R1-R2.rmse_after_settle.l";
}

const char* kTables[] = {"runs.csv", "aggregate.csv", "aggregate_over_scenarios.csv",
                         "ranking_links.R1-R2.rmse_after_settle.l.txt"};

void ExpectSameScenarioTables(const std::string& a, const std::string& b) {
  for (const char* f : kTables) {
    const std::string ta = ReadText(a + "/" + f);
    EXPECT_FALSE(ta.empty()) << a << "/" << f;
    EXPECT_EQ(ta, ReadText(b + "/" + f)) << f << " differs between " << a << " and " << b;
  }
}

std::string LineOf(const std::string& text, std::size_t i) {
  std::size_t at = 0;
  for (std::size_t k = 0; k < i; ++k) at = text.find('\n', at) + 1;
  return text.substr(at, text.find('\n', at) - at);
}

TEST(SweepScenariosCli, ScenarioColumnSameBytesForAnyJobsShardsAndJobLines) {
  const std::string a = TempDir("sweep_scen_j1"), b = TempDir("sweep_scen_j2");
  ASSERT_EQ(Formsim(Sweep() + " --jobs 1 --out " + a, a + ".log"), 0) << ReadText(a + ".log");
  EXPECT_NE(ReadText(a + ".log")
                .find("sweep of 2 scenarios (formation_traj1, formation_traj2): "
                      "2 scenarios x 2 points x 2 seeds = 8 runs"),
            std::string::npos)
      << ReadText(a + ".log");
  ASSERT_EQ(Formsim(Sweep() + " --jobs 2 -q --out " + b, b + ".log"), 0) << ReadText(b + ".log");
  ExpectSameScenarioTables(a, b);
  // The scenario (its file's stem) right after the run and the point; scenario by scenario.
  const std::string runs = ReadText(a + "/runs.csv"), agg = ReadText(a + "/aggregate.csv");
  EXPECT_EQ(LineOf(runs, 0).rfind("run,scenario,robots.R2.follow.k_l,seed,", 0), 0u) << runs;
  EXPECT_EQ(LineOf(runs, 1).rfind("0,formation_traj1,0.1,1,", 0), 0u) << runs;
  EXPECT_EQ(LineOf(runs, 8).rfind("7,formation_traj2,0.2,2,", 0), 0u) << runs;
  EXPECT_EQ(LineOf(agg, 0).rfind("point,scenario,robots.R2.follow.k_l,runs,failed,", 0), 0u);
  EXPECT_EQ(LineOf(agg, 3).rfind("0,formation_traj2,0.1,2,0,", 0), 0u) << agg;
  const std::string pooled = ReadText(a + "/aggregate_over_scenarios.csv");
  EXPECT_EQ(LineOf(pooled, 0).rfind("point,robots.R2.follow.k_l,scenarios,runs,failed,", 0), 0u);
  EXPECT_EQ(LineOf(pooled, 2).rfind("1,0.2,2,4,0,", 0), 0u) << pooled;
  EXPECT_GT(fs::file_size(a + "/plot_links.R1-R2.rmse_after_settle.l.png"), 10000u);
  // The figure: a mean line per scenario in its own colour, named by its stem, over its dots.
  {
    const sim::SweepDefinition def = sim::ReadManifest(a);
    const std::vector<sim::SweepRecord> recs = sim::ReadRecords(a, def);
    const sim::SweepTables t = sim::BuildSweepTables(def, recs);
    PlotData fig;
    ASSERT_TRUE(SweepFigure(def, t, recs, t.MetricIndex("links.R1-R2.rmse_after_settle.l"), &fig));
    std::vector<std::string> named;
    for (const PlotSeries& s : fig.series)
      if (!s.label.empty() && !s.markers_only && !s.x.empty()) named.push_back(s.label);
    EXPECT_EQ(named, (std::vector<std::string>{"formation_traj1", "formation_traj2"}));
    EXPECT_EQ(fig.series.size(), 6u) << "2 x (dots, line) and the grey key";
    EXPECT_NE(fig.series[2].color.r, fig.series[3].color.r);
    EXPECT_EQ(fig.series[2].y.size(), 2u);
  }

  // Three shards collect to the same bytes.
  const std::string merged = TempDir("sweep_scen_merged");
  std::string shards;
  for (const char* k : {"1", "2", "3"}) {
    const std::string s = TempDir(std::string("sweep_scen_shard") + k);
    ASSERT_EQ(Formsim(Sweep() + " -q --shard " + k + "/3 --out " + s, s + ".log"), 0) << k;
    shards += " " + s;
  }
  ASSERT_EQ(Formsim("sweep collect" + shards + " --out " + merged +
                        " --metric links.R1-R2.rmse_after_settle.l -q",
                    merged + ".log"),
            0)
      << ReadText(merged + ".log");
  ExpectSameScenarioTables(a, merged);

  // Job lines name every scenario by its path; each records its run.
  const std::string j = TempDir("sweep_scen_jobs");
  ASSERT_EQ(Formsim(Sweep() + " --print-jobs --out " + j, j + ".txt"), 0);
  const std::string jobs = ReadText(j + ".txt");
  ASSERT_EQ(std::count(jobs.begin(), jobs.end(), '\n'), 8);
  const std::string first = jobs.substr(0, jobs.find('\n'));
  EXPECT_NE(
      first.find(" --scenario " + fs::canonical(testing::Scenario("formation_traj1")).string() +
                 " --scenario " + fs::canonical(testing::Scenario("formation_traj2")).string()),
      std::string::npos)
      << first;
  const std::string last = jobs.substr(jobs.rfind('\n', jobs.size() - 2) + 1);
  ASSERT_EQ(RunShell(last.substr(0, last.size() - 1), j + ".log"), 0) << ReadText(j + ".log");
  EXPECT_EQ(ReadText(j + "/runs/000007.run"), ReadText(a + "/runs/000007.run"));
}

TEST(SweepScenariosCli, KilledMidwayResumesToTheSameBytes) {
  // 2 scenarios x 12 points x 4 seeds: about a second on two cores.
  const std::string big =
      " sweep formation_traj1 --scenario formation_traj3 "
      "--vary robots.R2.follow.k_l=0.05:0.5:12 --seeds 1..4 --no-figures";
  const std::string ref = TempDir("sweep_scen_kill_ref"), d = TempDir("sweep_scen_kill");
  ASSERT_EQ(Formsim(big + " -j1 -q --out " + ref, ref + ".log"), 0) << ReadText(ref + ".log");
  // kill -9 once two records are on disk. A fixed sleep raced the sweep: on a loaded CI machine
  // it slept past all 96 runs and killed the sweep while it wrote its tables.
  const int rc =
      RunShell(testing::SignalOnceRecorded(Binary() + big + " -j2 -q --out " + d, d, 2, "-9"),
               d + ".log");
  EXPECT_EQ(rc, 137) << ReadText(d + ".log");
  // Killed with a record half written, kill -9 may leave a .tmp (a record is written aside and
  // renamed), never a partial .run; the resume proves the rest.
  long recorded = 0;
  if (fs::is_directory(d + "/runs"))
    for (const auto& e : fs::directory_iterator(d + "/runs")) {
      const auto ext = e.path().extension();
      EXPECT_TRUE(ext == ".run" || ext == ".tmp") << e.path();
      recorded += ext == ".run";
    }
  EXPECT_GE(recorded, 2);
  EXPECT_LT(recorded, 96) << "killed midway";
  ASSERT_EQ(Formsim(big + " -j2 -q --resume --out " + d, d + ".log"), 0) << ReadText(d + ".log");
  EXPECT_EQ(ReadText(ref + "/runs.csv"), ReadText(d + "/runs.csv"));
  EXPECT_EQ(ReadText(ref + "/aggregate.csv"), ReadText(d + "/aggregate.csv"));
  EXPECT_EQ(ReadText(ref + "/aggregate_over_scenarios.csv"),
            ReadText(d + "/aggregate_over_scenarios.csv"));
  // The same scenarios in the other order are another sweep.
  EXPECT_EQ(Formsim(" sweep formation_traj3 --scenario formation_traj1 "
                    "--vary robots.R2.follow.k_l=0.05:0.5:12 --seeds 1..4 --resume --out " +
                        d,
                    d + ".log"),
            2);
  EXPECT_NE(ReadText(d + ".log").find("holds another sweep: the scenario's text differs"),
            std::string::npos)
      << ReadText(d + ".log");
}

TEST(SweepScenariosCli, RefusedUpFrontNamingScenarioAndKey) {
  const std::string d = TempDir("sweep_scen_bad");
  // agv_fused has no robots.R2.follow.k_l: refused before anything runs.
  EXPECT_EQ(Formsim("sweep formation_traj1 --scenario agv_fused "
                    "--vary robots.R2.follow.k_l=0.1,0.2 --out " +
                        d + "/a",
                    d + ".log"),
            2);
  const std::string log = ReadText(d + ".log");
  EXPECT_NE(log.find("--scenario"), std::string::npos) << log;
  EXPECT_NE(log.find("agv_fused.yaml"), std::string::npos) << log;
  EXPECT_NE(log.find("robots.R2.follow.k_l"), std::string::npos) << log;
  EXPECT_NE(log.find("every --vary key"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(d + "/a"));
  // A list that is a device, a folder, missing or empty; a scenario named twice.
  const std::string empty = d + "/empty.txt";
  std::ofstream(empty) << "# nothing\n\n";
  for (const std::string& bad :
       {std::string("/dev/zero"), TempDir("sweep_scen_dir"), std::string("/no/such/list"), empty}) {
    EXPECT_EQ(
        Formsim("sweep formation_traj1 --scenario @" + bad + " --out " + d + "/b", d + ".log"), 2)
        << bad;
    EXPECT_NE(ReadText(d + ".log").find("--scenario @" + bad), std::string::npos)
        << bad << ": " << ReadText(d + ".log");
  }
  EXPECT_EQ(
      Formsim("sweep formation_traj1 --scenario formation_traj1 --out " + d + "/c", d + ".log"), 2);
  EXPECT_NE(ReadText(d + ".log").find("--scenario formation_traj1: named twice"), std::string::npos)
      << ReadText(d + ".log");
  EXPECT_FALSE(fs::exists(d + "/b"));
  EXPECT_FALSE(fs::exists(d + "/c"));
}

TEST(StudyCli, SeedFlagsBeyond64BitsAreRefusedNamingTheFlag) {
  const std::string d = TempDir("seed_flags"), big = "18446744073709551616";  // 2^64
  const std::string tune =
      "tune formation_traj1 --param robots.R2.follow.k_l "
      "--metric links.R1-R2.rmse_after_settle.l --method bobyqa --budget 4 --out " +
      d + "/t";
  const std::string sweep = "sweep formation_traj1 --out " + d + "/s";
  // {arguments, flag, value}: each refused before anything runs, naming the flag and the value.
  const std::vector<std::array<std::string, 3>> cases = {
      {tune + " --search-seed " + big, "--search-seed", big},
      {tune + " --search-seed -1", "--search-seed", "-1"},
      {tune + " --seeds " + big, "--seeds", big},
      {tune + " --holdout 1.." + big, "--holdout", big},
      {sweep + " --seeds " + big, "--seeds", big},
      {sweep + " --sample-seed " + big, "--sample-seed", big},
      {"run formation_traj1 --seed " + big + " --out " + d + "/r", "--seed", big},
  };
  for (const auto& [cmd, flag, value] : cases) {
    EXPECT_EQ(Formsim(cmd, d + ".log"), 2) << cmd;
    const std::string log = ReadText(d + ".log");
    EXPECT_NE(log.find(flag), std::string::npos) << cmd << ": " << log;
    EXPECT_NE(log.find(value), std::string::npos) << cmd << ": " << log;
  }
  for (const char* out : {"/t", "/s", "/r"}) EXPECT_FALSE(fs::exists(d + out)) << out;
  // 2^64-1 itself is a seed.
  EXPECT_EQ(Formsim(tune + " --set duration=1 --search-seed "
                           "18446744073709551615 -q",
                    d + ".log"),
            0)
      << ReadText(d + ".log");
}

}  // namespace
}  // namespace formsim::app
