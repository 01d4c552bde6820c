// libFuzzer harness for `--set` and GUI edits: the first byte picks a shipped scenario, the
// rest is a list of "path=value" lines applied as --set overrides (then, if it loads, as live
// GUI edits of a running session). Errors must be messages, never crashes.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/scenario/scenario_files.hpp"
#include "tests/fuzz/fuzz_lines.hpp"
#include "sim/session/session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace formsim::sim;
  // The shipped scenarios up to 100 kB: the generated formation_swarm_1000 (200 kB, 1000 robots)
  // takes seconds per load under the sanitizers, and an input loads it up to 18 times (each edit
  // re-reads the whole scenario), which libFuzzer reports as a slow unit. Its keys are those of
  // formation_swarm_100 (the same generator), which stays in.
  static const std::vector<std::string> scenarios = [] {
    std::vector<std::string> out;
    for (const std::string& f : ShippedScenarios())
      if (std::filesystem::file_size(f) <= 100000) out.push_back(f);
    return out;
  }();
  if (size < 1 || scenarios.empty()) return 0;
  const std::string& file = scenarios[data[0] % scenarios.size()];
  const std::vector<std::string> lines = formsim::fuzz::InputLines(data, size, 16);
  try {
    Session s(file, lines, -1);
    for (int k = 0; k < 100 && !s.exp().finished(); ++k) s.Step();
  } catch (const std::exception&) {
  }
  // The same assignments as GUI edits of a running session.
  try {
    Session s(file, std::vector<std::string>{}, -1);
    for (const std::string& l : lines) {
      const auto eq = l.find('=');
      if (eq == std::string::npos) continue;
      s.Edit(l.substr(0, eq), l.substr(eq + 1));
      for (int k = 0; k < 20 && !s.exp().finished(); ++k) s.Step();
    }
    (void)s.Reset();
    for (int k = 0; k < 20 && !s.exp().finished(); ++k) s.Step();
  } catch (const std::exception&) {
  }
  return 0;
}
