// Sweeps over several scenarios on the core test kind: every scenario runs every point and
// seed, the run numbering, the manifest, the `scenario` column, the statistics over the
// scenarios (the fold `formsim tune --over` minimises), and results that do not depend on the
// number of threads. The command line (@LIST, a scenario without a key, job lines, figures):
// tests/app/study_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

#include "sim/study/scenario_set.hpp"
#include "sim/study/sweep.hpp"
#include "sim/study/sweep_tables.hpp"
#include "sim/study/tune.hpp"
#include "sweep_test_util.hpp"
#include "test_kind.hpp"

namespace formsim::sim {
namespace {

namespace fs = std::filesystem;

using sweeptest::Circle;
using sweeptest::ErrorOf;

// The circle turning twice as fast: another x for the same v.
ScenarioSource FastCircle() {
  std::string text = testkind::kScenario;
  text.replace(text.find("omega: 0.5"), 10, "omega: 1.0");
  return ScenarioSource::FromText(text, "circle_fast.yaml", "");
}

std::vector<SweepRecord> RunAll(const std::vector<ScenarioSource>& sources,
                                const SweepDefinition& d, int threads) {
  TaskPool pool(threads);
  std::vector<SweepRecord> recs;
  std::vector<std::size_t> runs(d.runs());
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = i;
  RunSweep(sources, d, runs, pool,
           [&](const SweepRecord& r, const SweepProgress&) { recs.push_back(r); });
  return recs;
}

std::string Line(const std::string& csv, std::size_t i) {
  std::size_t at = 0;
  for (std::size_t k = 0; k < i; ++k) at = csv.find('\n', at) + 1;
  return csv.substr(at, csv.find('\n', at) - at);
}

TEST(SweepScenarios, EveryScenarioRunsEveryPointAndSeedInItsOwnRows) {
  const std::vector<ScenarioSource> two = {Circle(), FastCircle()};
  const SweepDefinition d = DefineSweep(two, {}, {"v=0.5,1.2"}, {1, 2});
  ASSERT_EQ(d.runs(), 8u);
  EXPECT_TRUE(d.MultiScenario());
  // Run r: scenario r / 4, point (r / 2) % 2, seed r % 2.
  EXPECT_EQ(d.ScenarioOf(5), 1u);
  EXPECT_EQ(d.PointOf(5), 0u);
  EXPECT_EQ(d.SeedOf(5), 2u);
  const std::vector<SweepRecord> recs = RunAll(two, d, 1);
  const SweepTables t = BuildSweepTables(d, recs);
  EXPECT_EQ(Line(t.runs_csv, 0), "run,scenario,v,seed,x,status,message");
  EXPECT_EQ(Line(t.runs_csv, 1).substr(0, 17), "0,circle,0.5,1,0.");
  EXPECT_EQ(Line(t.runs_csv, 5).substr(0, 22), "4,circle_fast,0.5,1,0.");
  EXPECT_EQ(Line(t.aggregate_csv, 0).substr(0, 34), "point,scenario,v,runs,failed,x.n,x");
  EXPECT_EQ(Line(t.aggregate_csv, 3).substr(0, 24), "0,circle_fast,0.5,2,0,2,");
  ASSERT_EQ(t.points, (std::vector<std::size_t>{0, 1, 0, 1}));
  ASSERT_EQ(t.scenarios, (std::vector<std::size_t>{0, 0, 1, 1}));
  // Each scenario's rows are exactly what a sweep of it alone gives.
  for (std::size_t s = 0; s < 2; ++s) {
    const SweepDefinition alone = DefineSweep(two[s], {}, {"v=0.5,1.2"}, {1, 2});
    const SweepTables a = BuildSweepTables(alone, RunAll({two[s]}, alone, 1));
    for (std::size_t p = 0; p < 2; ++p) {
      EXPECT_EQ(t.stats[2 * s + p][0].mean, a.stats[p][0].mean);
      EXPECT_EQ(t.stats[2 * s + p][0].max, a.stats[p][0].max);
    }
  }
  // x = (v/ω) sin(ω) differs between the circles: the scenario matters.
  EXPECT_NE(t.stats[0][0].mean, t.stats[2][0].mean);
  // The same bytes with any number of threads and in any order of the records.
  std::vector<SweepRecord> shuffled = RunAll(two, d, 3);
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(3));
  const SweepTables b = BuildSweepTables(d, shuffled);
  EXPECT_EQ(b.runs_csv, t.runs_csv);
  EXPECT_EQ(b.aggregate_csv, t.aggregate_csv);
  EXPECT_EQ(b.pooled.csv, t.pooled.csv);
}

TEST(SweepScenarios, OverScenariosIsTheFoldTheRobustTuneMinimises) {
  const std::vector<ScenarioSource> two = {Circle(), FastCircle()};
  // The scenario's own v (1.2): the point tune evaluates first.
  const SweepDefinition d = DefineSweep(two, {}, {"v=0.5,1.2"}, {1, 2});
  const SweepTables t = BuildSweepTables(d, RunAll(two, d, 2));
  EXPECT_EQ(Line(t.pooled.csv, 0).substr(0, 37), "point,v,scenarios,runs,failed,x.n,x.m");
  EXPECT_EQ(Line(t.pooled.csv, 2).substr(0, 14), "1,1.2,2,4,0,4,");
  ASSERT_EQ(t.pooled.points, (std::vector<std::size_t>{0, 1}));
  TuneSettings s;
  s.params = {ParseTuneParam("v:0.2:2", ParseScenario(Circle(), {}).params)};
  s.objective = ParseMetricExpr("x");
  s.seeds = {1, 2};
  s.budget = 5;  // evaluation 1 is all this needs
  s.algorithm = "bobyqa";
  TaskPool pool(2);
  for (const char* over : {"mean", "max", "quantile:0.95"}) {
    s.over = ParseTuneOver(over);
    const TuneResult r = RunTune(two, s, pool);
    ASSERT_FALSE(r.history.empty());
    ASSERT_EQ(r.history[0].values[0], 1.2);
    const MetricStats& st = t.pooled.stats[1][0];
    const double want = std::string(over) == "mean"  ? st.mean
                        : std::string(over) == "max" ? st.max
                                                     : st.q95;
    EXPECT_EQ(r.history[0].objective, want) << over;
  }
  // The ranking orders the points by their mean over every scenario and seed.
  const std::string ranking = RankingText(d, t, 0);
  EXPECT_NE(ranking.find("over every scenario and seed (2 scenarios)"), std::string::npos)
      << ranking;
  // One scenario: no third table.
  const SweepDefinition one = DefineSweep(Circle(), {}, {"v=0.5,1.2"}, {1, 2});
  EXPECT_TRUE(BuildSweepTables(one, RunAll({Circle()}, one, 1)).pooled.csv.empty());
}

TEST(SweepScenarios, ManifestHoldsEveryScenarioAndOneScenarioKeepsItsBytes) {
  const SweepDefinition one = DefineSweep(Circle(), {}, {"v=0.5,1.2"}, {1});
  const SweepDefinition two = DefineSweep({Circle(), FastCircle()}, {}, {"v=0.5,1.2"}, {1});
  // One scenario: the manifest and id of every sweep before scenarios could be several.
  const std::string text = ManifestText(one);
  EXPECT_EQ(text.substr(0, text.find("sample_seed")),
            "formsim sweep manifest 1\nid " + one.id + "\nscenario circle.yaml\nscenario_sha256 " +
                Circle().sha256() + "\n");
  EXPECT_NE(one.id, two.id);
  const SweepDefinition back = ParseManifest(ManifestText(two), "m");
  EXPECT_EQ(back.id, two.id);
  ASSERT_EQ(back.scenarios.size(), 2u);
  EXPECT_EQ(back.scenarios[1].Name(), "circle_fast");
  EXPECT_EQ(back.scenarios[1].sha256, FastCircle().sha256());
  // The other order is another sweep (run numbers would mean other runs).
  const SweepDefinition swapped = DefineSweep({FastCircle(), Circle()}, {}, {"v=0.5,1.2"}, {1});
  EXPECT_NE(swapped.id, two.id);
  // A run of the second scenario is that scenario with the run's overrides.
  const auto rec = RunSweepRun({Circle(), FastCircle()}, two, 3);
  const auto alone =
      RunSweepRun(FastCircle(), DefineSweep(FastCircle(), {}, {"v=0.5,1.2"}, {1}), 1);
  ASSERT_TRUE(rec && alone);
  EXPECT_EQ(rec->metrics, alone->metrics);
  EXPECT_NE(ErrorOf([&] { RunSweepRun(Circle(), two, 0); }).find("the sweep has 2 scenarios"),
            std::string::npos);
  // The run count counts every scenario.
  EXPECT_NE(ErrorOf([] {
              DefineSweep({Circle(), FastCircle()}, {}, {"v=0.1:1:60"}, {1}, 1, 100);
            }).find("the sweep has 120 runs (scenarios x points x seeds)"),
            std::string::npos);
}

TEST(SweepScenarios, ListsAreReadAndNamesMustDiffer) {
  const fs::path dir = fs::temp_directory_path() / "formsim_test_sweep_scenarios";
  fs::remove_all(dir);
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  for (const char* sub : {"a", "b"}) {
    std::ofstream f(dir / sub / "circle.yaml");
    f << testkind::kScenario;
  }
  {
    std::ofstream f(dir / "other.yaml");
    f << testkind::kScenario;
  }
  {
    std::ofstream f(dir / "list.txt");
    f << "# two circles\n"
      << (dir / "a" / "circle.yaml").string() << "\n\n   " << (dir / "other.yaml").string()
      << "   # the other\n";
  }
  const auto set = ReadScenarioSet("", {"@" + (dir / "list.txt").string()}, "formsim sweep");
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(ScenarioStem(set[1]), "other");
  // Two files with one stem would share a name in the tables: refused, naming both.
  const std::string same = ErrorOf([&] {
    ReadScenarioSet((dir / "a" / "circle.yaml").string(), {(dir / "b" / "circle.yaml").string()},
                    "formsim sweep");
  });
  EXPECT_NE(same.find("its name 'circle' is taken by"), std::string::npos) << same;
  EXPECT_NE(ErrorOf([] {
              ReadScenarioSet("", {}, "formsim sweep");
            }).find("formsim sweep: give a scenario"),
            std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace formsim::sim
