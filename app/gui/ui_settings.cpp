#include "app/gui/ui_settings.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "sim/core/bounded_file.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/core/yaml_reader.hpp"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

// A whole number in [1, kMaxLessonNumber], or 0.
int LessonNumber(const YAML::Node& n) {
  double v = 0;
  if (!n.IsScalar() || !sim::ParseFiniteDouble(n.Scalar(), &v) || v != std::floor(v) || v < 1 ||
      v > kMaxLessonNumber)
    return 0;
  return static_cast<int>(v);
}

// One lesson's entry: {step: N, done: [N, ...], predicted: {STEP: OPTION, ...}}; "" or why not.
std::string ReadProgress(const YAML::Node& n, LessonProgress* out) {
  if (!n.IsMap()) return "expected {step, done, predicted}";
  for (const auto& kv : n) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "";
    const YAML::Node& v = kv.second;
    if (key == "step") {
      if ((out->step = LessonNumber(v)) == 0) return "step must be a whole number >= 1";
    } else if (key == "done") {
      if (!v.IsSequence()) return "done must be a list of step numbers";
      for (const YAML::Node& d : v) {
        const int s = LessonNumber(d);
        if (s == 0) return "done must be a list of step numbers";
        out->done.insert(s);
      }
    } else if (key == "predicted") {
      if (!v.IsMap()) return "predicted must map step numbers to option numbers";
      for (const auto& p : v) {
        const int s = LessonNumber(p.first), o = LessonNumber(p.second);
        if (s == 0 || o == 0) return "predicted must map step numbers to option numbers";
        out->predicted[s] = o;
      }
    } else {
      return "unknown key '" + key + "' (step, done, predicted)";
    }
  }
  return "";
}

// A lesson's name as the settings file keeps it (a file stem; anything else is never written).
bool IsLessonName(const std::string& s) {
  if (s.empty() || s.size() > 128) return false;
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
          c == '-'))
      return false;
  return true;
}

std::string ProgressYaml(const std::map<std::string, LessonProgress>& lessons) {
  if (lessons.empty()) return "";
  std::string y = "lessons:\n";
  for (const auto& [name, p] : lessons) {
    if (!IsLessonName(name)) continue;
    y += "  " + name + ": {step: " + std::to_string(p.step) + ", done: [";
    bool first = true;
    for (int d : p.done) y += (first ? "" : ", ") + std::to_string(d), first = false;
    y += "], predicted: {";
    first = true;
    for (const auto& [s, o] : p.predicted)
      y += (first ? "" : ", ") + std::to_string(s) + ": " + std::to_string(o), first = false;
    y += "}}\n";
  }
  return y;
}

}  // namespace

std::string UiSettingsPath() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg != nullptr && *xdg != '\0') return (fs::path(xdg) / "formsim" / "settings.yaml").string();
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0')
    return (fs::path(home) / ".config" / "formsim" / "settings.yaml").string();
  return "";
}

UiSettings LoadUiSettings(std::string* warning) {
  UiSettings s;
  const std::string path = UiSettingsPath();
  std::error_code ec;
  if (path.empty() || !fs::exists(path, ec)) return s;
  auto warn = [&](const YAML::Node& n, const std::string& key, const std::string& why) {
    if (warning != nullptr)
      *warning = path + ":" + std::to_string(n.Mark().line + 1) + ": key '" + key + "': " + why +
                 " (the default is used)";
  };
  try {
    // Bounded like every file formsim reads (a regular file, at most 4 MiB, aliases counted).
    const YAML::Node root = sim::LoadYamlText(sim::ReadBoundedFile(path), path);
    if (!root.IsMap()) return s;
    if (const YAML::Node n = root["ui_scale"]) {
      double v = 0;
      if (!n.IsScalar() || !sim::ParseFiniteDouble(n.Scalar(), &v) || v < kMinUiScale || v > kMaxUiScale)
        warn(n, "ui_scale", "must be a number in [1, 3]");
      else
        s.ui_scale = static_cast<float>(v);
    }
    if (const YAML::Node n = root["angle_unit"]) {
      if (n.IsScalar() && (n.Scalar() == "deg" || n.Scalar() == "rad"))
        s.degrees = n.Scalar() == "deg";
      else
        warn(n, "angle_unit", "must be deg or rad");
    }
    if (const YAML::Node n = root["lessons"]) {
      if (!n.IsMap()) warn(n, "lessons", "must map lesson names to their progress");
      for (const auto& kv : n.IsMap() ? n : YAML::Node()) {
        const std::string name = kv.first.IsScalar() ? kv.first.Scalar() : "";
        LessonProgress p;
        const std::string why = IsLessonName(name) ? ReadProgress(kv.second, &p) : "not a lesson's name";
        if (why.empty())
          s.lessons[name] = p;
        else
          warn(kv.first, "lessons." + name, why);
      }
    }
  } catch (const std::exception& e) {
    if (warning != nullptr) {
      const std::string what = e.what();  // the file's own errors name it already
      *warning = (what.rfind(path, 0) == 0 ? what : path + ": " + what) + " (defaults used)";
    }
  }
  return s;
}

std::string SaveUiSettings(const UiSettings& s) {
  const std::string path = UiSettingsPath();
  if (path.empty()) return "no settings folder (neither XDG_CONFIG_HOME nor HOME is set)";
  try {
    fs::create_directories(fs::path(path).parent_path());
    sim::WriteFileAtomic(path, "# formsim window settings (written by the GUI)\nui_scale: " +
                                   sim::FormatDouble(s.ui_scale) + "\nangle_unit: " +
                                   (s.degrees ? "deg" : "rad") + "\n" +
                                   ProgressYaml(s.lessons));
  } catch (const std::exception& e) {
    return std::string("cannot write the settings: ") + e.what();
  }
  return "";
}

}  // namespace formsim::app
