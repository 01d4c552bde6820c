#include "sim/core/lesson.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace formsim::sim {

LessonDef ReadLesson(YamlReader& b) {
  LessonDef l;
  l.present = true;
  auto text = [&](const char* key) {
    const std::string s = b.RequiredString(key);
    if (s.find_first_not_of(" \t\n") == std::string::npos) b.Fail(key, "must not be empty");
    return s;
  };
  l.title = text("title");
  l.goal = text("goal");
  l.watch = text("watch");
  l.try_next = text("try_next");
  l.equations = b.Strings("equations", {});
  for (const std::string& e : l.equations)
    if (e.find_first_not_of(" \t\n") == std::string::npos) b.Fail("equations", "an equation is empty");
  b.Finish();
  return l;
}

std::string LessonDir() {
  if (const char* env = std::getenv("FORMSIM_ASSETS")) return std::string(env) + "/lessons";
  return std::string(FORMSIM_SOURCE_DIR) + "/assets/lessons";
}

std::vector<std::string> ShippedLessons() {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(LessonDir(), ec))
    if (e.is_regular_file() && e.path().extension() == ".yaml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string ResolveLesson(const std::string& name) {
  if (fs::is_regular_file(name)) return name;
  for (const std::string& candidate : {LessonDir() + "/" + name, LessonDir() + "/" + name + ".yaml"})
    if (fs::is_regular_file(candidate)) return candidate;
  std::string known;
  for (const auto& f : ShippedLessons()) known += "\n  " + fs::path(f).stem().string();
  throw std::runtime_error("lesson '" + name + "' not found (not a file, not in " + LessonDir() + ")" +
                           (known.empty() ? std::string() : "; the lessons are:" + known));
}

}  // namespace formsim::sim
