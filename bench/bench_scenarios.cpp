// Simulation speed, no rendering: the shipped scenarios and generated formations of 10 to 10,000
// robots (sim/formation/cascade_generator.hpp). Counters: steps_per_s and realtime_x (simulated
// seconds per wall-clock second: every benchmark uses real time, since the step's independent
// work runs on all cores and CPU time would add up the threads). Where the time goes is measured
// by the same cascades with the estimators off (truth), on one thread, and with Box2D alone.
#include <benchmark/benchmark.h>

#include "control/formation/link_predict_lanes.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/core/thread_pool.hpp"
#include "sim/core/unicycle_drive.hpp"
#include "sim/formation/cascade_generator.hpp"

using namespace formsim;
using namespace formsim::sim;
namespace formation_lanes = formsim::control::formation;

namespace {

void RunSteps(benchmark::State& state, Experiment& e, long steps) {
  for (long k = 0; k < steps; ++k) e.Step();
  // Per-iteration amounts divided by the time per iteration.
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["realtime_x"] =
      benchmark::Counter(steps * e.dt(), benchmark::Counter::kIsIterationInvariantRate);
}


// Any shipped scenario run to its end (the AGV, inspection and velocity scenarios, issues 4-6).
void BM_ShippedScenario(benchmark::State& state, const std::string& name) {
  const std::string file = std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/" + name + ".yaml";
  // Only the steps are timed: the previous run is destroyed while the timer is paused (tearing
  // down a 10,000-robot experiment takes about 0.2 s, which is not simulation).
  std::unique_ptr<Experiment> e;
  for (auto _ : state) {
    state.PauseTiming();
    e.reset();
    e = LoadExperiment(file);
    const long steps = static_cast<long>(e->setup().duration / e->dt() + 0.5);
    state.ResumeTiming();
    RunSteps(state, *e, steps);
  }
}
// The paper scenario with a UKF per link (issue 2: goal >= 1000x real time).
BENCHMARK_CAPTURE(BM_ShippedScenario, formation_traj2_ukf, std::string("formation_traj2_ukf"))
    ->Unit(benchmark::kMillisecond)->UseRealTime();
// The paper scenario with its three links predicted one by one, no SIMD lanes (see
// BM_CascadeUkfScalarLanes).
void BM_ShippedScenarioScalarLanes(benchmark::State& state, const std::string& name) {
  const auto saved = formation_lanes::CurrentLanePath();
  formation_lanes::SetLanePath(formation_lanes::LanePath::kScalar);
  BM_ShippedScenario(state, name);
  formation_lanes::SetLanePath(saved);
}
BENCHMARK_CAPTURE(BM_ShippedScenarioScalarLanes, formation_traj2_ukf, std::string("formation_traj2_ukf"))
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ShippedScenario, agv_fused, std::string("agv_fused"))
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ShippedScenario, velocity_constant, std::string("velocity_constant"))
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ShippedScenario, inspection_u_route, std::string("inspection_u_route"))
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ShippedScenario, formation_swarm_100, std::string("formation_swarm_100"))
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ShippedScenario, formation_swarm_1000, std::string("formation_swarm_1000"))
    ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// Generated formation of N robots, one simulated second after the first (the start-up
// transient), estimator per follower as given, `threads` threads (0: all cores).
void BM_Cascade(benchmark::State& state, bool ukf, int threads) {
  const int n = static_cast<int>(state.range(0));
  // Loaded and run through its first second once; each iteration runs a copy of that state
  // forward by 100 steps (recording is I/O, measured separately: one row per second).
  const std::string text = formation::MakeCascadeScenario(n, ukf);
  std::unique_ptr<Experiment> e;  // destroyed while paused, as in BM_ShippedScenario
  for (auto _ : state) {
    state.PauseTiming();
    e.reset();
    e = LoadExperimentFromText(text, "cascade", {"record_every=100"});
    e->SetThreads(threads > 0 ? threads : ThreadPool::HardwareThreads());
    for (int k = 0; k < 100; ++k) e->Step();
    state.ResumeTiming();
    RunSteps(state, *e, 100);
  }
  state.counters["threads"] = threads > 0 ? threads : ThreadPool::HardwareThreads();
}
void BM_CascadeUkf(benchmark::State& s) { BM_Cascade(s, true, 0); }
void BM_CascadeTruth(benchmark::State& s) { BM_Cascade(s, false, 0); }
void BM_CascadeUkfOneThread(benchmark::State& s) { BM_Cascade(s, true, 1); }
// Two threads whatever the machine (on the project's 2-core VM the same as all cores).
void BM_CascadeUkfTwoThreads(benchmark::State& s) {
  BM_Cascade(s, true, 2);
}
// The same with every link predicted by its own Predict, no SIMD lanes (the reference whose
// bits the lanes give, control/formation/link_predict_lanes.hpp): what the lanes gain.
void BM_CascadeUkfScalar(benchmark::State& s, int threads) {
  const auto saved = formation_lanes::CurrentLanePath();
  formation_lanes::SetLanePath(formation_lanes::LanePath::kScalar);
  BM_Cascade(s, true, threads);
  formation_lanes::SetLanePath(saved);
}
void BM_CascadeUkfScalarLanes(benchmark::State& s) { BM_CascadeUkfScalar(s, 0); }
void BM_CascadeUkfScalarLanesOneThread(benchmark::State& s) { BM_CascadeUkfScalar(s, 1); }
// 10 to 10,000 robots, in milliseconds of real time.
void RobotCounts(benchmark::internal::Benchmark* b) {
  for (int n : {10, 100, 1000, 10000}) b->Arg(n);
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}
BENCHMARK(BM_CascadeUkf)->Apply(RobotCounts);
BENCHMARK(BM_CascadeTruth)->Apply(RobotCounts);
BENCHMARK(BM_CascadeUkfOneThread)->Apply(RobotCounts);
BENCHMARK(BM_CascadeUkfTwoThreads)->Apply(RobotCounts);
BENCHMARK(BM_CascadeUkfScalarLanes)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CascadeUkfScalarLanesOneThread)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime();

// Box2D alone: N robots with ideal drives in a loose grid, no controllers, no recording.
void BM_Box2DOnly(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    World world;
    std::vector<UnicycleDrive*> drives;
    for (int i = 0; i < n; ++i) {
      RobotDef def = DefaultRobotDef();
      def.name = "R" + std::to_string(i);
      def.pose = {0.5 * (i % 40), 0.5 * (i / 40), 0.0};
      Robot& r = world.CreateRobot(def);
      auto d = std::make_unique<UnicycleDrive>(UnicycleDriveDef{});
      d->SetCommand(1.0, 0.2);
      drives.push_back(d.get());
      r.SetDrive(std::move(d));
    }
    state.ResumeTiming();
    for (int k = 0; k < 100; ++k) world.Step(0.01);
  }
  state.counters["realtime_x"] = benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Box2DOnly)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime();

// Recording and CSV writing of the paper scenario (the I/O share).
void BM_PaperScenarioCsv(benchmark::State& state) {
  const std::string file = std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/formation_traj2_ukf.yaml";
  auto e = LoadExperiment(file);
  while (!e->finished()) e->Step();
  for (auto _ : state) e->recorder().WriteCsv("/tmp/formsim_bench.csv");
  state.counters["rows"] = static_cast<double>(e->recorder().rows());
}
BENCHMARK(BM_PaperScenarioCsv)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
