#pragma once
/// \file A lesson: a scenario file with a `lesson:` block beside its scenario keys
/// (assets/lessons/NAME.yaml). The block is text for the GUI's Lesson panel; every command
/// that runs scenarios runs a lesson file as the scenario it holds (finding lesson files:
/// scenario_files.hpp).
///
///   lesson:
///     title: "The l-φ law and its time constant"      (required)
///     goal: "..."                                      (required)
///     watch: "..."                                     (required: what to watch)
///     try_next: "..."                                  (required: what to try next)
///     equations: ["l̇ = −k_l (l − l_des)", ...]          (optional, readable text / Unicode)

#include <string>
#include <vector>

#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

struct LessonDef {
  bool present = false;  ///< the scenario had a lesson: block
  std::string title, goal, watch, try_next;
  std::vector<std::string> equations;
};

/// Reads a `lesson:` block strictly (unknown keys and empty texts are errors). Throws
/// ScenarioError naming file:line:key.
LessonDef ReadLesson(YamlReader& block);

}  // namespace formsim::sim
