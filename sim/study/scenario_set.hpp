#pragma once
/// \file The scenarios of a study over several scenarios (`formsim sweep` and `formsim tune`
/// with `--scenario A --scenario B` or `--scenario @LIST`): reading the list, naming each
/// scenario by its file's stem (the `scenario` column of a sweep's tables, the legends of its
/// figures, tune's best_<stem>.yaml), and checking up front that each has the keys the study
/// sets.

#include <string>
#include <vector>

#include "sim/core/param_table.hpp"
#include "sim/scenario/scenario.hpp"

namespace formsim::sim {

/// The largest `--scenario @LIST` file read: 1 MiB.
constexpr std::uintmax_t kMaxScenarioListBytes = std::uintmax_t{1} << 20;

/// The positional scenario (when not empty) and every `--scenario` value, in order; `@FILE` is a
/// list, one name or path per line (`#` starts a comment, blank lines are skipped), which must be
/// a regular file of at most kMaxScenarioListBytes naming at least one scenario. Each scenario is
/// resolved (ResolveScenario) and read. Throws std::runtime_error naming `--scenario` and the
/// value: a missing or unreadable list, an empty one, a scenario named twice, two scenarios whose
/// files have the same stem (they would share a name); ScenarioError for an unreadable scenario.
/// `command` ("formsim sweep") names the command when no scenario is given at all.
std::vector<ScenarioSource> ReadScenarioSet(const std::string& positional,
                                            const std::vector<std::string>& flags,
                                            const std::string& command);

/// A scenario's name in tables and legends: its file's stem (`formation_traj1`).
std::string ScenarioStem(const ScenarioSource& source);

/// Checks that every scenario after the first has each of `keys` (tunables of the first,
/// read with `sets`) as a tunable of the same kind, and, for enums, the same choices. Throws
/// ScenarioError naming `--scenario FILE` and the key; `role` says what the key is for
/// ("tuned", "--vary").
void CheckScenarioKeys(const std::vector<ScenarioSource>& sources,
                       const std::vector<Override>& sets, const std::vector<const Param*>& keys,
                       const std::string& role);

}  // namespace formsim::sim
