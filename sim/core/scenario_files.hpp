#pragma once
/// \file Finding scenario files: a path, or the name of a shipped scenario in assets/scenarios.

#include <string>
#include <vector>

namespace formsim::sim {

/// The folder holding the shipped scenarios (FORMSIM_SOURCE_DIR/assets/scenarios, or
/// $FORMSIM_ASSETS/scenarios when set).
std::string ScenarioDir();
/// Resolves "formation_traj1", "formation_traj1.yaml" or a path to an existing file.
/// Throws std::runtime_error listing close names when nothing matches.
std::string ResolveScenario(const std::string& name_or_path);
/// Every shipped scenario file, sorted by name.
std::vector<std::string> ShippedScenarios();

}  // namespace formsim::sim
