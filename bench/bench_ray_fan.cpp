// One laser scan's ray casts on the inspection scenario's world (issue 28 item 2: most of an
// inspection run): 720 beams of 20 m from points along the route, each through World::RayCast
// (Box2D's broad-phase tree per ray) or through one RayFan per scan (the same hits, tested in
// tests/sim/test_ray_fan.cpp). Counter: beams_per_s.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "sim/core/ray_fan.hpp"
#include "sim/scenario/scenario.hpp"

using namespace formsim;
using namespace formsim::sim;

namespace {

constexpr int kBeams = 720;

void BM_LaserScanRays(benchmark::State& state) {
  const bool fan = state.range(0) != 0;
  const auto exp = LoadExperiment(std::string(FORMSIM_SOURCE_DIR) +
                                  "/assets/scenarios/inspection_u_route.yaml");
  const World& world = exp->world();
  const Robot* robot = world.robots().front().get();
  int scan = 0;
  double sum = 0;
  for (auto _ : state) {
    // Ten origins on the first straight and the turn, one scan each in turn.
    const Vec2 origin{3.3 + 0.3 * (scan % 10), 2.0 + 1.9 * (scan % 10)};
    ++scan;
    const RayFan* f = nullptr;
    std::unique_ptr<RayFan> keep;
    if (fan) keep = std::make_unique<RayFan>(world, origin, 20.0, false, robot), f = keep.get();
    for (int k = 0; k < kBeams; ++k) {
      const double a = 2.0 * M_PI * k / kBeams;
      const Vec2 to = origin + Vec2{std::cos(a), std::sin(a)} * 20.0;
      const RayHit h = f ? f->Cast(to) : world.RayCast(origin, to, false, robot);
      sum += h.distance;
    }
  }
  benchmark::DoNotOptimize(sum);
  state.counters["beams_per_s"] =
      benchmark::Counter(kBeams, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_LaserScanRays)->ArgName("fan")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
