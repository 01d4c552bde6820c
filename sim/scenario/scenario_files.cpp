#include "sim/scenario/scenario_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "sim/core/yaml_reader.hpp"
#include "sim/scenario/asset_dirs.hpp"

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

namespace {
// Reads type and the one-line text at `path` (a list of keys) of `file`.
ScenarioListing Describe(const std::string& file, const std::vector<const char*>& path) {
  ScenarioListing out{fs::path(file).stem().string(), "?", ""};
  try {
    YAML::Node root = LoadYamlFile(file);
    if (root["type"]) out.type = root["type"].as<std::string>();
    // reset(), not operator=: assigning a YAML::Node writes into the node it refers to.
    YAML::Node node = root;
    for (const char* key : path) {
      if (!node[key]) return out;
      node.reset(node[key]);
    }
    out.description = node.as<std::string>();
  } catch (const std::exception& e) {
    out.description = std::string("(unreadable: ") + e.what() + ")";
  }
  return out;
}
}  // namespace

ScenarioListing DescribeScenario(const std::string& file) {
  return Describe(file, {"description"});
}

ScenarioListing DescribeLesson(const std::string& file) {
  return Describe(file, {"lesson", "title"});
}

}  // namespace formsim::sim
