// libFuzzer harness for sweep specs: the first byte picks a shipped scenario, the first line is
// the --seeds text, the second the --shard text, every further line a --vary KEY=SPEC. They go
// through ParseSeeds, ParseShard and DefineSweep (the run count from the specs first, then the
// axes) as `formsim sweep` does, and a sweep that is defined must agree with itself: its count
// from the specs, its manifest read back, its shards covering every run once. Errors must be
// messages; a crash, a sanitizer report, a hang or a disagreement is a bug.
// Seeds: tests/fuzz/sweep_spec_seeds.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/scenario/scenario_files.hpp"
#include "sim/study/sweep_spec.hpp"
#include "sim/study/sweep_store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace formsim::sim;
  // The shipped scenarios up to 100 kB (as fuzz_set: the 1000-robot swarm takes seconds to load
  // under the sanitizers), read once.
  static const std::vector<ScenarioSource> scenarios = [] {
    std::vector<ScenarioSource> out;
    for (const std::string& f : ShippedScenarios())
      if (std::filesystem::file_size(f) <= 100000) out.push_back(ScenarioSource::FromFile(f));
    return out;
  }();
  if (size < 1 || scenarios.empty()) return 0;
  const ScenarioSource& source = scenarios[data[0] % scenarios.size()];
  std::vector<std::string> lines(1);
  for (std::size_t i = 1; i < size; ++i) {
    if (data[i] == '\n')
      lines.emplace_back();
    else
      lines.back() += static_cast<char>(data[i]);
  }
  if (lines.size() > 10) lines.resize(10);
  std::vector<std::uint64_t> seeds;
  int k = 1, n = 1;
  try {
    if (!lines[0].empty()) seeds = ParseSeeds(lines[0]);
  } catch (const std::exception&) {
    return 0;
  }
  try {
    if (lines.size() > 1 && !lines[1].empty()) ParseShard(lines[1], &k, &n);
  } catch (const std::exception&) {
    k = n = 1;
  }
  const std::vector<std::string> vary(lines.begin() + std::min<std::size_t>(2, lines.size()),
                                      lines.end());
  SweepDefinition def;
  try {
    // A smaller cap than the CLI's default keeps each input fast; the count is checked the same.
    def = DefineSweep(source, {}, vary, seeds, 1, 20000);
  } catch (const std::exception&) {
    return 0;
  }
  // The count from the specs alone is the count of the sweep built.
  static std::vector<ParamTable> params(scenarios.size());  // each scenario's, parsed once
  ParamTable& table = params[data[0] % scenarios.size()];
  if (table.size() == 0) table = ParseScenario(source, {}).params;
  const std::size_t counted = CountSweepRuns(table, vary, seeds.size());
  if (counted != def.runs()) std::abort();
  // The manifest reads back to the same sweep.
  const SweepDefinition back = ParseManifest(ManifestText(def), "fuzz.manifest");
  if (back.id != def.id || back.runs() != def.runs()) std::abort();
  // Shard k of n, and all shards together, cover every run once.
  std::size_t covered = 0;
  for (int s = 1; s <= n && s <= 64; ++s) covered += ShardRuns(def.runs(), s, n).size();
  if (n <= 64 && covered != def.runs()) std::abort();
  for (std::size_t r : ShardRuns(def.runs(), k, n))
    if (r >= def.runs() || static_cast<int>(r % static_cast<std::size_t>(n)) != k - 1) std::abort();
  for (std::size_t r = 0; r < def.runs() && r < 64; ++r) (void)def.RunOverrides(r);
  return 0;
}
