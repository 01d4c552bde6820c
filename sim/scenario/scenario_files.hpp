#pragma once
/// \file Finding scenario files: a path, or the name of a shipped scenario in assets/scenarios
/// or of a lesson in assets/lessons.

#include <string>
#include <vector>

namespace formsim::sim {

/// The folder holding the shipped scenarios: AssetDir("scenarios") (asset_dirs.hpp: installed
/// share/formsim, then $FORMSIM_ASSETS, then the source tree).
std::string ScenarioDir();
/// Resolves "formation_traj1", "formation_traj1.yaml" or a path to an existing file.
/// Throws std::runtime_error listing close names when nothing matches.
std::string ResolveScenario(const std::string& name_or_path);
/// Every shipped scenario file, sorted by name.
std::vector<std::string> ShippedScenarios();

/// The folder of the shipped lessons (scenarios with a `lesson:` block, lesson.hpp):
/// AssetDir("lessons").
std::string LessonDir();
/// Every shipped lesson file, sorted by name.
std::vector<std::string> ShippedLessons();
/// Resolves a lesson name ("lphi_time_constant", with or without .yaml) or a path. Throws
/// std::runtime_error listing the shipped lessons when nothing matches.
std::string ResolveLesson(const std::string& name_or_path);

/// One line of `formsim list` (and of the Python module's scenarios() and lessons()).
struct ScenarioListing {
  std::string name;         ///< the file's stem: what `formsim run NAME` takes
  std::string type;         ///< the experiment kind, "?" when the file does not say
  std::string description;  ///< a scenario's `description`, a lesson's `lesson.title`; when
                            ///< the file cannot be read: "(unreadable: reason)"
};
/// The listing of a scenario file (`description:`).
ScenarioListing DescribeScenario(const std::string& file);
/// The listing of a lesson file (`lesson: title:`).
ScenarioListing DescribeLesson(const std::string& file);

}  // namespace formsim::sim
