#pragma once
/// \file Settings of the window kept between runs: the UI scale and the angle unit, in
/// $XDG_CONFIG_HOME/formsim/settings.yaml (or ~/.config/formsim/settings.yaml).

#include <string>

namespace formsim::app {

struct UiSettings {
  float ui_scale = 1.0f;  ///< fonts and line widths, 1 ... 3
  bool degrees = true;    ///< angles shown in degrees (stored values stay radians)
};

/// Smallest and largest UI scale.
constexpr float kMinUiScale = 1.0f, kMaxUiScale = 3.0f;

/// The settings file's path ("" when neither XDG_CONFIG_HOME nor HOME is set).
std::string UiSettingsPath();
/// Reads the settings; a missing file gives the defaults, an unreadable or invalid one the
/// defaults and a `warning` naming file:line and the key.
UiSettings LoadUiSettings(std::string* warning = nullptr);
/// Writes the settings (temp file + rename, the folder made when missing). Returns "" or why not.
std::string SaveUiSettings(const UiSettings& s);

}  // namespace formsim::app
