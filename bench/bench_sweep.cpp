// The sweep engine (issue 7): a 200-run sweep of the paper scenario (40 values of R2's k_phi x
// 5 seeds) on one and on two threads, against the same 200 runs done one after the other the
// bare way (parse, build, step to the end, results). The difference per run is what the sweep
// machinery costs (task pool, run overrides, records handed over, tables built at the end);
// records on disk (one atomic, synced file per run) are measured by the CLI (docs/benchmarks.md).
#include <benchmark/benchmark.h>

#include "sim/study/sweep.hpp"
#include "sim/study/sweep_tables.hpp"

using namespace formsim::sim;

namespace {

const ScenarioSource& Source() {
  static const ScenarioSource s = ScenarioSource::FromFile(
      std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/formation_traj2_ukf.yaml");
  return s;
}

SweepDefinition Sweep200() {
  return DefineSweep(Source(), {}, {"robots.R2.follow.k_phi=0.02:0.4:40"}, ParseSeeds("1..5"));
}

void BM_Sweep200(benchmark::State& state) {
  const SweepDefinition def = Sweep200();
  std::vector<std::size_t> runs(def.runs());
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = i;
  TaskPool pool(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    std::vector<SweepRecord> recs;
    RunSweep(Source(), def, runs, pool,
             [&](const SweepRecord& r, const SweepProgress&) { recs.push_back(r); });
    benchmark::DoNotOptimize(BuildSweepTables(def, recs).aggregate_csv.size());
  }
  state.counters["runs_per_s"] = benchmark::Counter(static_cast<double>(def.runs()),
                                                    benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Sweep200)
    ->ArgName("jobs")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

// The same 200 runs, each exactly as `formsim run -q` steps it, one after the other, no sweep.
void BM_Bare200(benchmark::State& state) {
  const SweepDefinition def = Sweep200();
  for (auto _ : state) {
    for (std::size_t r = 0; r < def.runs(); ++r) {
      std::unique_ptr<Experiment> e = BuildExperiment(ParseScenario(Source(), def.RunOverrides(r)));
      while (!e->finished()) e->Step();
      benchmark::DoNotOptimize(e->Results().Scalars().size());
    }
  }
  state.counters["runs_per_s"] = benchmark::Counter(static_cast<double>(def.runs()),
                                                    benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Bare200)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// One run's load path alone: ParseScenario (the text is read once; parsed per run) + build.
void BM_ParseAndBuild(benchmark::State& state) {
  const SweepDefinition def = Sweep200();
  for (auto _ : state)
    benchmark::DoNotOptimize(BuildExperiment(ParseScenario(Source(), def.RunOverrides(7))));
}
BENCHMARK(BM_ParseAndBuild)->Unit(benchmark::kMicrosecond);

// Of which the YAML parse of the scenario's text.
void BM_YamlParse(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(LoadYamlText(Source().text(), Source().file()));
}
BENCHMARK(BM_YamlParse)->Unit(benchmark::kMicrosecond);

}  // namespace
