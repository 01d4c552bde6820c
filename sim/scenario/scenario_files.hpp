#pragma once
/// \file Finding scenario files: a path, or the name of a shipped scenario in assets/scenarios
/// or of a lesson in assets/lessons.

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

/// The folder of the shipped lessons (scenarios with a `lesson:` block, lesson.hpp):
/// FORMSIM_SOURCE_DIR/assets/lessons, or $FORMSIM_ASSETS/lessons when set.
std::string LessonDir();
/// Every shipped lesson file, sorted by name.
std::vector<std::string> ShippedLessons();
/// Resolves a lesson name ("lphi_time_constant", with or without .yaml) or a path. Throws
/// std::runtime_error listing the shipped lessons when nothing matches.
std::string ResolveLesson(const std::string& name_or_path);

}  // namespace formsim::sim
