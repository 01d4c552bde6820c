// libFuzzer harness: any bytes as a scenario file, read through the one load path and, when it
// loads, built and stepped for a few hundred steps (fewer for many bodies). A scenario error or a refused value is the
// expected outcome for most inputs; a crash, an abort (Box2D's assertions), a sanitizer report
// or a hang is a bug. Every crash found becomes a fixture in tests/fixtures/invalid/.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include <box2d/box2d.h>

#include "sim/core/world.hpp"
#include "sim/scenario/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace formsim::sim;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Relative paths (the inspection rule base) resolve as for a shipped scenario.
    const ScenarioSource src =
        ScenarioSource::FromText(text, "fuzz.yaml", std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios");
    const ParsedScenario parsed = ParseScenario(src, {});
    auto exp = BuildExperiment(parsed);
    // A few hundred steps, fewer for a large world: a body-step budget keeps a 100-robot input
    // near a second under the sanitizers (300 steps of it took 7 s, and CI's load doubles that).
    const int bodies = std::max(1, exp->world().b2().GetBodyCount());
    const int steps = std::clamp(6000 / bodies, 20, 300);
    for (int k = 0; k < steps && !exp->finished(); ++k) exp->Step();
    (void)exp->Summary().Dump();
  } catch (const std::exception&) {
    // Refused with a message: fine.
  }
  return 0;
}
