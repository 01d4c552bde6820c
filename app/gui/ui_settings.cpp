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
                                   (s.degrees ? "deg" : "rad") + "\n");
  } catch (const std::exception& e) {
    return std::string("cannot write the settings: ") + e.what();
  }
  return "";
}

}  // namespace formsim::app
