#include "sim/core/scenario_files.hpp"

#include "sim/core/lesson.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace formsim::sim {

std::string ScenarioDir() {
  if (const char* env = std::getenv("FORMSIM_ASSETS")) return std::string(env) + "/scenarios";
  return std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios";
}

std::vector<std::string> ShippedScenarios() {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(ScenarioDir(), ec))
    if (e.is_regular_file() && e.path().extension() == ".yaml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string ResolveScenario(const std::string& name) {
  if (fs::is_regular_file(name)) return name;
  // Shipped scenarios first, then the lessons (each a scenario too).
  for (const std::string& candidate :
       {ScenarioDir() + "/" + name, ScenarioDir() + "/" + name + ".yaml", LessonDir() + "/" + name,
        LessonDir() + "/" + name + ".yaml"})
    if (fs::is_regular_file(candidate)) return candidate;
  std::string msg = "scenario '" + name + "' not found (not a file, not in " + ScenarioDir() + ")";
  std::string close;
  for (const auto& f : ShippedScenarios()) {
    const std::string stem = fs::path(f).stem().string();
    if (stem.find(name) != std::string::npos || name.find(stem) != std::string::npos)
      close += "\n  " + stem;
  }
  if (!close.empty())
    msg += "; did you mean:" + close;
  else
    msg += "; `formsim list` shows the shipped ones";
  throw std::runtime_error(msg);
}

}  // namespace formsim::sim
