#pragma once
/// \file A scenario with overrides written back into the file's own text: only the changed
/// values are rewritten (comments and layout kept, numbers as their shortest round-trip text),
/// relative file paths are adjusted to the target folder, and the result is read back to check
/// that every tunable and the seed come out the same. Used by the GUI's Save
/// (Session::TunedYaml) and by `formsim tune`'s best.yaml.

#include <string>
#include <vector>

#include "sim/scenario/scenario.hpp"

namespace formsim::sim {

/// The last override of each key, in the order of those last occurrences, all from the start
/// of the run (step -1).
std::vector<Override> LastValuePerKey(const std::vector<Override>& overrides);

/// The text of `source` with `overrides` applied, as it would be written to `path`. When the
/// file's text cannot be patched in place the whole tree is written (comments lost; `note`
/// then says so). Throws when the result would not load back with the same values.
std::string TunedScenarioText(const ScenarioSource& source, const std::vector<Override>& overrides,
                              const std::string& path, std::string* note = nullptr);

}  // namespace formsim::sim
