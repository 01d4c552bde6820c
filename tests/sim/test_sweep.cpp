// The sweep engine and the tuner on the core test kind (a unicycle on a circle): specs, seeds,
// the Latin hypercube, the run numbering, manifests and records on disk, the tables, the task
// pool, and results that do not depend on the number of threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>

#include "sim/core/number_format.hpp"
#include "sim/study/sweep.hpp"
#include "sim/study/sweep_tables.hpp"
#include "sim/study/tune.hpp"
#include "sim/study/tune_history.hpp"
#include "sim/study/tune_validation.hpp"
#include "sweep_test_util.hpp"
#include "test_kind.hpp"

namespace formsim::sim {
namespace {

namespace fs = std::filesystem;

using sweeptest::Circle;
using sweeptest::ErrorOf;

std::string SweepDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("formsim_test_sweep_" + name);
  fs::remove_all(p);
  return p.string();
}

TEST(ParseSeeds, RangesListsAndErrors) {
  EXPECT_EQ(ParseSeeds("1..3,7"), (std::vector<std::uint64_t>{1, 2, 3, 7}));
  EXPECT_EQ(ParseSeeds("5"), (std::vector<std::uint64_t>{5}));
  EXPECT_EQ(ParseSeeds("18446744073709551615"),
            (std::vector<std::uint64_t>{18446744073709551615ULL}));
  EXPECT_NE(ErrorOf([] { ParseSeeds("3..1"); }).find("--seeds '3..1': the range 3..1 is empty"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { ParseSeeds("1,2,1"); }).find("seed 1 appears twice"), std::string::npos);
  for (const char* bad : {"", "a", "1..", "-1", "1.5", "1,,2"})
    EXPECT_NE(ErrorOf([&] { ParseSeeds(bad); }).find("--seeds"), std::string::npos) << bad;
}

TEST(LatinHypercube, OnePointPerStratumInEveryDimension) {
  const auto pts = LatinHypercube(7, 3, 42);
  ASSERT_EQ(pts.size(), 7u);
  for (std::size_t d = 0; d < 3; ++d) {
    std::set<int> strata;
    for (const auto& p : pts) {
      ASSERT_GE(p[d], 0.0);
      ASSERT_LT(p[d], 1.0);
      strata.insert(static_cast<int>(p[d] * 7));
    }
    EXPECT_EQ(strata.size(), 7u) << "dimension " << d;
  }
  EXPECT_EQ(LatinHypercube(7, 3, 42), pts) << "deterministic for a seed";
  EXPECT_NE(LatinHypercube(7, 3, 43), pts);
}

TEST(DefineSweep, ListsRangesAndEnumsInCanonicalText) {
  const SweepDefinition d =
      DefineSweep(Circle(), {}, {"v=0.5,1,1.50", "omega=0.1:0.3:3", "drive.mode=all"}, {1, 2});
  ASSERT_EQ(d.axes.size(), 3u);
  EXPECT_EQ(d.axes[0].values, (std::vector<std::string>{"0.5", "1", "1.5"}));
  EXPECT_EQ(d.axes[1].values, (std::vector<std::string>{"0.1", "0.2", "0.3"}))
      << "tidy range values";
  EXPECT_EQ(d.axes[2].values, (std::vector<std::string>{"ideal", "traction"}));
  EXPECT_TRUE(d.axes[2].categorical());
  EXPECT_EQ(d.points.size(), 18u);
  EXPECT_EQ(d.runs(), 36u);
  // The first axis varies slowest, seeds fastest.
  EXPECT_EQ(d.Value(0, 0), "0.5");
  EXPECT_EQ(d.Value(1, 2), "traction");
  EXPECT_EQ(d.Value(2, 1), "0.2");
  EXPECT_EQ(d.Value(17, 0), "1.5");
  EXPECT_EQ(d.PointOf(5), 2u);
  EXPECT_EQ(d.SeedOf(5), 2u);
  const std::vector<Override> o = d.RunOverrides(5);
  ASSERT_EQ(o.size(), 4u);
  EXPECT_EQ(o[1].key + "=" + o[1].value, "omega=0.2");
  EXPECT_EQ(o[3].key + "=" + o[3].value, "seed=2");
  // The scenario's own seed when none is given; a log range.
  const SweepDefinition l = DefineSweep(Circle(), {}, {"v=log:0.01:1:3"}, {});
  EXPECT_EQ(l.seeds, (std::vector<std::uint64_t>{3}));
  EXPECT_EQ(l.axes[0].values, (std::vector<std::string>{"0.01", "0.1", "1"}));
  EXPECT_TRUE(l.axes[0].log_scale);
}

TEST(DefineSweep, RandomSamplesShareOneHypercubeWithinTheSliderRange) {
  const SweepDefinition d = DefineSweep(
      Circle(), {}, {"v=random:10", "omega=0.1,0.2", "sigma=random:10:0.2:0.4"}, {1}, 7);
  EXPECT_EQ(d.points.size(), 20u) << "the random axes are paired, the list is crossed with them";
  EXPECT_FALSE(d.IsGrid());
  std::set<int> strata;
  for (std::size_t i = 0; i < 10; ++i) {
    const double v = d.axes[0].Numeric(i), s = d.axes[2].Numeric(i);
    EXPECT_GE(v, 0.0);
    EXPECT_LE(v, 3.0);  // the declared slider of v
    EXPECT_GE(s, 0.2);
    EXPECT_LE(s, 0.4);
    strata.insert(static_cast<int>(v / 0.3));
  }
  EXPECT_EQ(strata.size(), 10u);
  EXPECT_EQ(d.points[0][0], d.points[0][2]);
  EXPECT_EQ(
      DefineSweep(Circle(), {}, {"v=random:10", "omega=0.1,0.2", "sigma=random:10:0.2:0.4"}, {1}, 7)
          .id,
      d.id);
  EXPECT_NE(
      DefineSweep(Circle(), {}, {"v=random:10", "omega=0.1,0.2", "sigma=random:10:0.2:0.4"}, {1}, 8)
          .id,
      d.id);
}

TEST(DefineSweep, ErrorsNameTheArgumentAndTheKey) {
  auto err = [](std::vector<std::string> vary) {
    return ErrorOf([&] { DefineSweep(Circle(), {}, vary, {}); });
  };
  EXPECT_EQ(err({"vv=1"}),
            "--vary vv=1: key 'vv': not a tunable of circle.yaml (tunables: v, omega, sigma, "
            "drive.mode, drive.v_max, drive.omega_max)");
  EXPECT_EQ(err({"drive.mod=1"}),
            "--vary drive.mod=1: key 'drive.mod': not a tunable of circle.yaml (similar: "
            "drive.mode, drive.v_max, drive.omega_max)");
  EXPECT_NE(err({"v=-1,1"}).find("--vary v=-1,1: key 'v': value '-1': must be >= 0"),
            std::string::npos);
  EXPECT_NE(err({"omega=9"}).find("must be in [-5, 5]"), std::string::npos);
  EXPECT_NE(err({"drive.mode=0:1:3"}).find("a range needs a numeric tunable"), std::string::npos);
  EXPECT_NE(err({"drive.mode=fast"}).find("'fast' is not one of: ideal, traction"),
            std::string::npos);
  EXPECT_NE(err({"v=1:2"}).find("expected LO:HI:N"), std::string::npos);
  EXPECT_NE(err({"v=log:0:1:3"}).find("a log range needs LO > 0"), std::string::npos);
  EXPECT_NE(err({"v=1,1"}).find("appears twice"), std::string::npos);
  EXPECT_NE(err({"v=random:3", "omega=random:4"}).find("needs the same N"), std::string::npos);
  EXPECT_NE(err({"v=random:3:-1:1"}).find("leaves the valid values"), std::string::npos);
  EXPECT_NE(err({"seed=1,2"}).find("varied with --seeds"), std::string::npos);
  EXPECT_NE(err({"v=1", "v=2"}).find("varied twice"), std::string::npos);
  EXPECT_NE(err({"v"}).find("expected KEY=SPEC"), std::string::npos);
}

TEST(SweepStore, ManifestAndRecordsRoundTripEveryByte) {
  const SweepDefinition d = DefineSweep(Circle(), CliOverrides({"sigma=0.2"}, -1),
                                        {"v=random:4", "drive.mode=ideal,traction"}, {1, 9});
  const SweepDefinition back = ParseManifest(ManifestText(d), "m");
  EXPECT_EQ(back.id, d.id);
  EXPECT_EQ(back.points, d.points);
  EXPECT_EQ(ManifestText(back), ManifestText(d));
  std::string tampered = ManifestText(d);
  tampered.replace(tampered.find("value ideal"), 11, "value xdeal");
  EXPECT_NE(ErrorOf([&] { ParseManifest(tampered, "m"); }).find("does not match its id"),
            std::string::npos);

  SweepRecord r;
  r.run = 5;
  r.status = "error";
  r.message = "a \\ b\nc, \"d\"\t e  ";
  r.metrics = {{"a.b c", 0.1}, {"nan", std::nan("")}, {"inf", -INFINITY}, {"tiny", 5e-324}};
  const SweepRecord r2 = ParseRecord(RecordText(d, r), d, "r");
  EXPECT_EQ(r2.run, 5u);
  EXPECT_EQ(r2.message, r.message);
  ASSERT_EQ(r2.metrics.size(), 4u);
  EXPECT_EQ(r2.metrics[0].first, "a.b c");
  // A value the run could not compute is written "-" and read back as NaN ("no value").
  EXPECT_TRUE(std::isnan(r2.metrics[1].second));
  EXPECT_TRUE(std::isnan(r2.metrics[2].second));
  EXPECT_NE(RecordText(d, r).find("\nm nan -\nm inf -\n"), std::string::npos) << RecordText(d, r);
  EXPECT_EQ(r2.metrics[3].second, 5e-324);
  EXPECT_EQ(RecordText(d, r2), RecordText(d, r));
  // A record of another sweep, or a truncated one, is refused.
  const SweepDefinition other = DefineSweep(Circle(), {}, {"v=1,2"}, {1});
  EXPECT_NE(ErrorOf([&] { ParseRecord(RecordText(other, r), d, "r"); }).find("another sweep"),
            std::string::npos);
  const std::string text = RecordText(d, r);
  EXPECT_NE(
      ErrorOf([&] { ParseRecord(text.substr(0, text.size() - 4), d, "r"); }).find("incomplete"),
      std::string::npos);
}

TEST(SweepStore, ShardsPartitionTheRuns) {
  std::vector<std::size_t> all;
  for (int k = 1; k <= 3; ++k)
    for (std::size_t r : ShardRuns(10, k, 3)) all.push_back(r);
  std::sort(all.begin(), all.end());
  ASSERT_EQ(all.size(), 10u);
  for (std::size_t i = 0; i < 10; ++i) EXPECT_EQ(all[i], i);
  int k = 0, n = 0;
  ParseShard("2/5", &k, &n);
  EXPECT_EQ(k, 2);
  EXPECT_EQ(n, 5);
  for (const char* bad : {"0/2", "3/2", "1", "a/b", "1/0"})
    EXPECT_NE(ErrorOf([&] { ParseShard(bad, &k, &n); }).find("--shard"), std::string::npos) << bad;
}

TEST(SweepStore, WriteManifestRefusesAnotherSweep) {
  const std::string dir = SweepDir("manifest");
  const SweepDefinition a = DefineSweep(Circle(), {}, {"v=1,2"}, {1});
  const SweepDefinition b = DefineSweep(Circle(), {}, {"v=1,3"}, {1});
  WriteManifest(dir, a);
  WriteManifest(dir, a);  // the same sweep: fine
  EXPECT_NE(
      ErrorOf([&] { WriteManifest(dir, b); }).find("holds another sweep: the values of v differ"),
      std::string::npos);
  fs::remove_all(dir);
}

TEST(TaskPool, EveryIndexOnceAndErrorsRethrown) {
  for (int threads : {1, 2, 4}) {
    TaskPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (int round = 0; round < 3; ++round) {
      std::vector<std::atomic<int>> hits(100);
      pool.ForEach(hits.size(), [&](std::size_t i) { ++hits[i]; });
      for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
    }
    // Once a task has thrown no further index starts (the others take a while, so that the
    // throw is seen before the hand-out could finish).
    std::atomic<int> ran{0};
    EXPECT_THROW(pool.ForEach(50,
                              [&](std::size_t i) {
                                ++ran;
                                if (i == 3) throw std::runtime_error("boom");
                                std::this_thread::sleep_for(std::chrono::milliseconds(2));
                              }),
                 std::runtime_error);
    EXPECT_LT(ran.load(), 50);
    std::atomic<int> started{0};
    pool.ForEach(
        100, [&](std::size_t) { ++started; }, [&] { return started.load() >= 10; });
    EXPECT_LT(started.load(), 100) << "a stop ends the hand-out";
  }
}

// Runs the whole sweep in memory and builds its tables.
SweepTables RunAll(const SweepDefinition& d, int threads, bool shuffle) {
  TaskPool pool(threads);
  std::vector<SweepRecord> recs;
  std::vector<std::size_t> runs(d.runs());
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = i;
  RunSweep(Circle(), d, runs, pool,
           [&](const SweepRecord& r, const SweepProgress&) { recs.push_back(r); });
  if (shuffle) std::shuffle(recs.begin(), recs.end(), std::mt19937(5));
  return BuildSweepTables(d, recs);
}

TEST(RunSweep, TablesDoNotDependOnThreadsOrOrder) {
  const SweepDefinition d = DefineSweep(Circle(), {}, {"v=0.5:1.5:3", "omega=0.2,3.5"}, {1, 2});
  const SweepTables a = RunAll(d, 1, false), b = RunAll(d, 3, true);
  EXPECT_EQ(a.runs_csv, b.runs_csv);
  EXPECT_EQ(a.aggregate_csv, b.aggregate_csv);
  // v + |omega| >= 4 breaks the kind's rule across keys: those runs are errors, the rest ran.
  EXPECT_NE(a.runs_csv.find(
                "\n11,1.5,3.5,2,,error,--vary omega=3.5: key 'omega': v + |omega| must be < 4\n"),
            std::string::npos)
      << a.runs_csv;
  EXPECT_EQ(CsvField("a, \"b\"\nc"), "\"a, \"\"b\"\"\nc\"");
  EXPECT_EQ(CsvField("plain"), "plain");
  EXPECT_EQ(a.runs_csv.substr(0, a.runs_csv.find('\n')), "run,v,omega,seed,x,status,message");
  EXPECT_NE(a.runs_csv.find("\n0,0.5,0.2,1,"), std::string::npos);
  // aggregate: the failed point has runs 2, failed 2, n 0 and empty statistics.
  EXPECT_EQ(a.aggregate_csv.substr(0, a.aggregate_csv.find('\n')),
            "point,v,omega,runs,failed,x.n,x.mean,x.std,x.min,x.max,x.median,x.q05,x.q95,x.sem,"
            "x.ci95_lo,x.ci95_hi");
  EXPECT_NE(a.aggregate_csv.find("\n5,1.5,3.5,2,2,0,,,,,,,,,,\n"), std::string::npos)
      << a.aggregate_csv;
  // The kind's x does not depend on the seed: std 0 over two seeds, min = mean = max.
  ASSERT_EQ(a.stats.size(), 6u);
  EXPECT_EQ(a.stats[0][0].n, 2u);
  EXPECT_EQ(a.stats[0][0].std, 0.0);
  EXPECT_EQ(a.stats[0][0].min, a.stats[0][0].mean);
  EXPECT_EQ(DefaultMetric(a), 0u);
  const std::string ranking = RankingText(d, a, 0);
  EXPECT_NE(ranking.find("points sorted by the mean of x"), std::string::npos);
}

TEST(RunSweep, ARunIsExactlyTheScenarioWithItsOverrides) {
  const SweepDefinition d =
      DefineSweep(Circle(), CliOverrides({"sigma=0.3"}, -1), {"v=0.7,1.1"}, {4, 5});
  for (std::size_t r = 0; r < d.runs(); ++r) {
    const auto rec = RunSweepRun(Circle(), d, r);
    ASSERT_TRUE(rec);
    EXPECT_EQ(rec->status, "completed");
    std::unique_ptr<Experiment> e = LoadExperimentFromText(
        testkind::kScenario, "circle.yaml", {"sigma=0.3", "v=" + d.Value(d.PointOf(r), 0)},
        static_cast<long long>(d.SeedOf(r)));
    while (!e->finished()) e->Step();
    EXPECT_EQ(rec->metrics, e->Results().Scalars());
  }
  // Stopped mid-run: nothing to record.
  EXPECT_FALSE(RunSweepRun(Circle(), d, 0, [] { return true; }));
}

TEST(MetricExpr, SumsOfWeightedPaths) {
  const auto t = ParseMetricExpr("links.R1-R2.a.phi + 10*links.R1-R2.a.l+ -0.5 * x + 1e+3*y");
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0].path, "links.R1-R2.a.phi");
  EXPECT_EQ(t[0].weight, 1.0);
  EXPECT_EQ(t[1].weight, 10.0);
  EXPECT_EQ(t[1].path, "links.R1-R2.a.l");
  EXPECT_EQ(t[2].weight, -0.5);
  EXPECT_EQ(t[3].weight, 1000.0);
  EXPECT_EQ(t[3].path, "y");
  for (const char* bad : {"", "a +", "*x", "a b", "2*", "a - b"})
    EXPECT_NE(ErrorOf([&] { ParseMetricExpr(bad); }).find("--metric"), std::string::npos) << bad;
}

TEST(TuneParam, BoundsFromTheDeclarationOrGiven) {
  const ParsedScenario p = ParseScenario(Circle(), {});
  const TuneParam v = ParseTuneParam("v", p.params);
  EXPECT_EQ(v.lo, 0.0);
  EXPECT_EQ(v.hi, 3.0);
  EXPECT_EQ(v.start, 1.2);
  const TuneParam w = ParseTuneParam("omega:-1:1", p.params);
  EXPECT_EQ(w.lo, -1.0);
  EXPECT_EQ(w.start, 0.5);
  auto err = [&](const char* a) { return ErrorOf([&] { ParseTuneParam(a, p.params); }); };
  const TuneParam mode = ParseTuneParam("drive.mode", p.params);
  EXPECT_EQ(mode.kind, TuneParam::Kind::kChoice);
  EXPECT_EQ(mode.choices, (std::vector<std::string>{"ideal", "traction"}));
  EXPECT_EQ(mode.Text(mode.FromUnit(0.49)), "ideal");
  EXPECT_EQ(mode.Text(mode.FromUnit(0.51)), "traction");
  EXPECT_EQ(mode.FromUnit(1.0), 1.0);
  EXPECT_NE(err("drive.mode:0:1").find("give the key alone"), std::string::npos);
  EXPECT_NE(
      err("v:-1:2").find("--param v:-1:2: key 'v': bound -1 is not a valid value: must be >= 0"),
      std::string::npos);
  EXPECT_NE(err("v:2:1").find("LO < HI"), std::string::npos);
  EXPECT_NE(err("vv").find("not a tunable"), std::string::npos);
  EXPECT_NE(err("v:1").find("KEY:LO:HI"), std::string::npos);
}

// Tuning v in [0.2, 2] for x after 1 s on the circle, over seeds 1 and 2.
TuneSettings CircleTune() {
  const ParsedScenario p = ParseScenario(Circle(), {});
  TuneSettings s;
  s.params = {ParseTuneParam("v:0.2:2", p.params)};
  s.objective = ParseMetricExpr("x");
  s.seeds = {1, 2};
  return s;
}

TEST(Tune, FindsTheMinimumAndIsDeterministic) {
  // x after 1 s on the circle is (v/ω) sin(ω): minimal at the smallest v.
  TuneSettings s = CircleTune();
  s.budget = 25;
  for (const char* alg : {"bobyqa", "neldermead", "cobyla"}) {
    s.algorithm = alg;
    TaskPool one(1), two(2);
    const TuneResult a = RunTune(Circle(), s, one), b = RunTune(Circle(), s, two);
    ASSERT_TRUE(a.has_best()) << alg;
    EXPECT_NEAR(a.history[a.best].values[0], 0.2, 1e-3) << alg;
    EXPECT_LE(a.history.size(), 25u);
    EXPECT_EQ(a.history[0].values[0], 1.2) << "starts at the scenario's value";
    EXPECT_EQ(TuneHistoryCsv(s, a), TuneHistoryCsv(s, b)) << alg;
  }
  // A term that names no metric fails at once, with the names there are.
  s.objective = ParseMetricExpr("xx");
  TaskPool pool(1);
  EXPECT_NE(ErrorOf([&] { RunTune(Circle(), s, pool); }).find("no metric 'xx' (similar: x)"),
            std::string::npos);
}

TEST(Tune, GlobalMethodsAndTwoStagePlansFindTheMinimumDeterministically) {
  TuneSettings s = CircleTune();
  s.budget = 45;
  for (const char* alg :
       {"direct-l", "crs2", "mlsl", "isres", "direct-l+bobyqa", "crs2+cobyla"}) {
    s.algorithm = alg;
    TaskPool one(1), two(2);
    const TuneResult a = RunTune(Circle(), s, one), b = RunTune(Circle(), s, two);
    ASSERT_TRUE(a.has_best()) << alg;
    EXPECT_NEAR(a.history[a.best].values[0], 0.2, 0.02) << alg;
    EXPECT_LE(a.history.size(), 45u) << alg;
    EXPECT_EQ(TuneHistoryCsv(s, a), TuneHistoryCsv(s, b)) << alg;
  }
  // The two stages: 40% to the global one, its method named on each row of history.csv.
  s.algorithm = "direct-l+bobyqa";
  TaskPool pool(2);
  const TuneResult r = RunTune(Circle(), s, pool);
  ASSERT_EQ(r.plan.size(), 2u);
  EXPECT_EQ(PlanText(r.plan), "direct-l 18 + bobyqa 27 evaluations");
  for (const TuneEvaluation& e : r.history) EXPECT_EQ(e.stage, e.index <= 18 ? 0u : 1u);
  EXPECT_NE(TuneHistoryCsv(s, r).find("\n19,bobyqa,"), std::string::npos);
  // A random method's history follows its search seed.
  s.algorithm = "crs2";
  const std::string seed1 = TuneHistoryCsv(s, RunTune(Circle(), s, pool));
  s.search_seed = 2;
  EXPECT_NE(TuneHistoryCsv(s, RunTune(Circle(), s, pool)), seed1);
}

TEST(Tune, ChoiceKeysAreSearchedByTheGlobalStageAndHeldForThePolish) {
  // x after 1 s: the traction drive is slower to reach the commanded speed, so with the smallest
  // v either mode could win; the search must try both and pick the better, and the polish (a
  // local method on v alone) must keep the mode the global stage chose.
  TuneSettings s = CircleTune();
  const ParsedScenario p = ParseScenario(Circle(), {});
  s.params.push_back(ParseTuneParam("drive.mode", p.params));
  s.algorithm = "direct-l+bobyqa";
  s.budget = 30;
  TaskPool pool(2);
  const TuneResult r = RunTune(Circle(), s, pool);
  ASSERT_TRUE(r.has_best());
  std::set<double> modes, polished_modes;
  for (const TuneEvaluation& e : r.history) {
    modes.insert(e.values[1]);
    if (e.stage == 1) polished_modes.insert(e.values[1]);
  }
  EXPECT_EQ(modes.size(), 2u) << "both choices tried";
  EXPECT_EQ(polished_modes, (std::set<double>{r.history[r.best].values[1]}))
      << "the polish holds the best choice";
  EXPECT_NE(TuneHistoryCsv(s, r).find(",ideal,"), std::string::npos) << "written by name";
  EXPECT_EQ(ReadTuneHistory(TuneHistoryCsv(s, r), s).back().values, r.history.back().values);
  for (const TuneEvaluation& e : r.history) EXPECT_EQ(e.values[1], std::round(e.values[1]));
  EXPECT_EQ(TuneOverrides(s, r.history[0].values)[1].value, "ideal");
  // Only choices: the global stage alone.
  s.params.erase(s.params.begin());
  EXPECT_EQ(PlanText(PlanTune("direct-l+bobyqa", 1, 30, 0)), "direct-l 30 evaluations");
}

TEST(TunePlan, RefusesUnknownMethodsWrongOrderAndSmallBudgets) {
  EXPECT_EQ(PlanText(PlanTune("bobyqa", 2, 60)), "bobyqa 60 evaluations");
  EXPECT_EQ(PlanText(PlanTune("isres+cobyla", 1, 60)), "isres 41 + cobyla 19 evaluations")
      << "the global stage gets what its first population needs when 40% is less";
  EXPECT_NE(ErrorOf([] { PlanTune("newton", 1, 60); })
                .find("--method 'newton': unknown method 'newton' (one of bobyqa, neldermead, "
                      "cobyla, direct-l, crs2, mlsl, isres, or GLOBAL+LOCAL"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { PlanTune("bobyqa+crs2", 1, 60); }).find("GLOBAL+LOCAL"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { PlanTune("crs2", 2, 30); })
                .find("--budget 30: too small for --method crs2 with 2 tunables (needs at least "
                      "31: 31 for crs2)"),
            std::string::npos);
}

TEST(Tune, ConstraintsParseAndKeepTheBestFeasiblePoint) {
  const TuneConstraint c = ParseTuneConstraint(" a.b >= -0.5 ");
  EXPECT_EQ(c.path, "a.b");
  EXPECT_FALSE(c.at_most);
  EXPECT_EQ(c.bound, -0.5);
  EXPECT_EQ(c.Text(), "a.b>=-0.5");
  EXPECT_EQ(c.Violation(-0.25), 0);
  EXPECT_EQ(c.Violation(-1), 1) << "relative to the bound's size";
  for (const char* bad : {"a.b", "a.b<=x", "<=1", "a b<=1", "a.b>=inf"})
    EXPECT_NE(ErrorOf([&] { ParseTuneConstraint(bad); }).find("--constraint '"), std::string::npos)
        << bad;

  // Unconstrained, x is smallest at v = 0.2; x >= half of x at the start (v = 1.2) moves the
  // best to the bound, with every method (COBYLA natively, the others inside AUGLAG).
  TuneSettings s = CircleTune();
  s.budget = 3;
  TaskPool pool(2);
  const double x_start = RunTune(Circle(), s, pool).history[0].objective;
  s.constraints = {ParseTuneConstraint("x>=" + FormatDouble(x_start / 2))};
  s.budget = 40;
  for (const char* alg : {"cobyla", "bobyqa", "neldermead", "direct-l+cobyla"}) {
    s.algorithm = alg;
    const TuneResult r = RunTune(Circle(), s, pool);
    ASSERT_TRUE(r.has_best()) << alg;
    const TuneEvaluation& best = r.history[r.best];
    EXPECT_GE(best.objective, x_start / 2) << alg;
    EXPECT_LE(best.objective, x_start / 2 * 1.05) << alg << ": near the bound";
    for (const TuneEvaluation& e : r.history) {
      if (e.feasible()) {
        EXPECT_GE(e.objective, best.objective) << alg;
      }
    }
    EXPECT_NE(TuneHistoryCsv(s, r).find(",feasible,"), std::string::npos);
  }
  // A bound no point meets: no best, and the closest point is kept.
  s.constraints = {ParseTuneConstraint("x<=-1")};
  s.algorithm = "cobyla";
  const TuneResult none = RunTune(Circle(), s, pool);
  EXPECT_FALSE(none.has_best());
  for (const TuneEvaluation& e : none.history)
    EXPECT_GE(e.violation, none.history[none.best].violation);
  // A constraint on a metric the runs do not have: refused at evaluation 1.
  s.constraints = {ParseTuneConstraint("xx<=1")};
  EXPECT_NE(ErrorOf([&] { RunTune(Circle(), s, pool); })
                .find("--constraint: the runs have no metric 'xx' (similar: x)"),
            std::string::npos);
}

TEST(TuneValidation, HeldOutSeedsComparePairedAndRefuseOverlap) {
  EXPECT_NE(ErrorOf([] { CheckHoldout({4, 5, 6}, {1, 2, 3, 4}); })
                .find("--holdout: seed 4 is also in --seeds"),
            std::string::npos);
  TuneSettings s = CircleTune();
  TaskPool pool(2);
  const auto v = ValidateTune({Circle()}, s, {1.2}, {0.2}, {7, 8, 9}, pool);
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->compared, 3u);
  EXPECT_EQ(v->best_better, 3u) << "x is smaller at the smaller speed on every seed";
  EXPECT_LT(v->difference.ci95_hi, 0);
  EXPECT_NEAR(v->best_stats.mean / v->start_stats.mean, 0.2 / 1.2, 0.05);
  const std::string csv = TuneValidationCsv(*v);
  EXPECT_EQ(csv.rfind("scenario,seed,objective_start,objective_best,difference,best_feasible\n"
                      "circle,7,",
                      0),
            0u);
  EXPECT_NE(TuneValidationText(*v).find("best is better on 3 of 3 runs"), std::string::npos);
}

TEST(Tune, OverFoldsEveryScenarioAndSeedIntoTheObjective) {
  EXPECT_EQ(ParseTuneOver("quantile:0.9").Text(), "quantile:0.9");
  EXPECT_EQ(ParseTuneOver("max").Of({1, 5, 2}), 5);
  EXPECT_EQ(ParseTuneOver("mean").Of({1, 5, 3}), 3);
  EXPECT_EQ(ParseTuneOver("quantile:0.5").Of({4, 1, 2}), 2);
  for (const char* bad : {"", "min", "quantile:1", "quantile:0", "quantile:x"})
    EXPECT_NE(ErrorOf([&] { ParseTuneOver(bad); }).find("--over '"), std::string::npos) << bad;
  // Two scenarios (the circle at two turn rates): the objective is the fold of all four runs,
  // and max is never below mean.
  TuneSettings s = CircleTune();
  s.budget = 3;
  const ScenarioSource fast = ScenarioSource::FromText(
      std::string(testkind::kScenario), "circle_fast.yaml", "");
  TaskPool pool(2);
  const TuneResult one = RunTune(Circle(), s, pool);
  const TuneResult two = RunTune({Circle(), fast}, s, pool);
  EXPECT_EQ(two.history[0].objective, one.history[0].objective)
      << "the same scenario twice folds to the same mean";
  s.over = ParseTuneOver("max");
  const TuneResult worst = RunTune({Circle(), fast}, s, pool);
  EXPECT_GE(worst.history[0].objective, two.history[0].objective);
  // Scenarios of one kind have every key (a scenario without one: tests/app/study_test.cpp).
  EXPECT_EQ(ErrorOf([&] { CheckTunedKeys({Circle(), fast}, s); }), "");
}

TEST(TuneHistory, ReadsBackEveryCompleteRowAndDropsATornOne) {
  TuneSettings s = CircleTune();
  s.constraints = {ParseTuneConstraint("x>=0.1"), ParseTuneConstraint("x<=5")};
  s.budget = 6;
  TaskPool pool(1);
  TuneResult r = RunTune(Circle(), s, pool);
  r.history[1].failed_runs = 1;  // a message with every CSV hazard
  r.history[1].message = "seed 2: error: \"a, b\"\nnext line";
  r.history[1].objective = std::numeric_limits<double>::infinity();
  const std::string csv = TuneHistoryCsv(s, r);
  const std::vector<TuneEvaluation> back = ReadTuneHistory(csv, s);
  ASSERT_EQ(back.size(), r.history.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].values, r.history[i].values);
    EXPECT_EQ(back[i].objective, r.history[i].objective);
    EXPECT_EQ(back[i].message, r.history[i].message);
    EXPECT_EQ(back[i].feasible(), r.history[i].feasible());
    EXPECT_EQ(back[i].violation, r.history[i].violation) << i;
  }
  // A kill while the last row was written: that row is left out, the rest read back.
  EXPECT_EQ(ReadTuneHistory(csv.substr(0, csv.size() - 5), s).size(), r.history.size() - 1);
  // Another tune's history is refused.
  s.objective = ParseMetricExpr("2*x");
  EXPECT_EQ(ReadTuneHistory(csv, s).size(), r.history.size()) << "same columns";
  s.params[0].key = "omega";
  EXPECT_NE(ErrorOf([&] { ReadTuneHistory(csv, s); }).find("another tune's history"),
            std::string::npos);
}

TEST(Tune, FailedEvaluationsAreRecordedNotFatal) {
  // omega near 3.9 with v up to 3 breaks the rule across keys for part of the box.
  const ParsedScenario p = ParseScenario(Circle(), CliOverrides({"omega=2.5"}, -1));
  TuneSettings s;
  s.sets = CliOverrides({"omega=2.5"}, -1);
  s.params = {ParseTuneParam("v:0.5:3", p.params)};
  s.objective = ParseMetricExpr("-1*x");
  s.seeds = {1};
  s.budget = 15;
  TaskPool pool(2);
  const TuneResult r = RunTune(Circle(), s, pool);
  ASSERT_TRUE(r.has_best());
  bool saw_failure = false;
  for (const TuneEvaluation& e : r.history) saw_failure = saw_failure || e.failed();
  EXPECT_TRUE(saw_failure);
  EXPECT_LT(r.history[r.best].values[0], 1.5);
  EXPECT_NE(TuneHistoryCsv(s, r).find(",inf,"), std::string::npos);
}

}  // namespace
}  // namespace formsim::sim
