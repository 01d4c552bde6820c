#include "sim/scenario/scenario_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace formsim::sim {

namespace {

// A path that exists but is no regular file (/dev/zero, a FIFO, a folder) is handed on as it is,
// so that the reader refuses it by name and kind (bounded_file.hpp), not as "not found".
bool GivenAsPath(const std::string& name) {
  std::error_code ec;
  return fs::is_regular_file(name, ec) ||
         (name.find('/') != std::string::npos && fs::exists(fs::symlink_status(name, ec)));
}

// A folder of the shipped assets ($FORMSIM_ASSETS or the source tree's assets/).
std::string AssetDir(const std::string& sub) {
  if (const char* env = std::getenv("FORMSIM_ASSETS")) return std::string(env) + "/" + sub;
  return std::string(FORMSIM_SOURCE_DIR) + "/assets/" + sub;
}

std::vector<std::string> YamlFilesIn(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ".yaml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

std::string ScenarioDir() { return AssetDir("scenarios"); }
std::vector<std::string> ShippedScenarios() { return YamlFilesIn(ScenarioDir()); }
std::string LessonDir() { return AssetDir("lessons"); }
std::vector<std::string> ShippedLessons() { return YamlFilesIn(LessonDir()); }

std::string ResolveLesson(const std::string& name) {
  if (GivenAsPath(name)) return name;
  for (const std::string& candidate : {LessonDir() + "/" + name, LessonDir() + "/" + name + ".yaml"})
    if (fs::is_regular_file(candidate)) return candidate;
  std::string known;
  for (const auto& f : ShippedLessons()) known += "\n  " + fs::path(f).stem().string();
  throw std::runtime_error("lesson '" + name + "' not found (not a file, not in " + LessonDir() + ")" +
                           (known.empty() ? std::string() : "; the lessons are:" + known));
}

std::string ResolveScenario(const std::string& name) {
  if (GivenAsPath(name)) return name;
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
