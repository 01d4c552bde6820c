// A structural change of a running formation (the GUI's formation editor): Session::Restructure
// writes the edits into the text, rewrites it by the command, reads it with the loader and builds
// the new run from the robots' current poses. Measured on generated cascades of N robots (the
// formation_swarm_* scenarios' generator) after one step, for a shape change (every robot
// placed, the whole graph rebuilt) and for the follower added at the back.
#include <benchmark/benchmark.h>

#include "sim/session/session.hpp"
#include "sim/formation/cascade_generator.hpp"
#include "sim/formation/formation_editing.hpp"

using namespace formsim::sim;

namespace {

void Restructure(benchmark::State& state, const std::string& command) {
  const int n = static_cast<int>(state.range(0));
  const ScenarioSource src = ScenarioSource::FromText(formation::MakeCascadeScenario(n, false),
                                                      "cascade", "");
  for (auto _ : state) {
    state.PauseTiming();
    Session s(src, {});
    s.Step();
    state.ResumeTiming();
    const std::string err = formation::Restructure(s, command);
    if (!err.empty()) state.SkipWithError(err.c_str());
  }
}

void BM_RestructureShape(benchmark::State& state) { Restructure(state, "shape wedge 0.6"); }
BENCHMARK(BM_RestructureShape)->Arg(7)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_RestructureAdd(benchmark::State& state) {
  Restructure(state, "add l_phi R1 -30 0 Rnew");
}
BENCHMARK(BM_RestructureAdd)->Arg(7)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
