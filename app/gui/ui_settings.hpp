#pragma once
/// \file Settings of the window kept between runs: the UI scale, the angle unit and each
/// lesson's progress, in $XDG_CONFIG_HOME/formsim/settings.yaml (or ~/.config/formsim/settings.yaml).

#include <map>
#include <set>
#include <string>

namespace formsim::app {

/// How far a student has come in one lesson (step and option numbers 1-based, as the script
/// actions `lesson-step N` and `lesson-predict K` count).
struct LessonProgress {
  int step = 1;                  ///< the step shown
  std::set<int> done;            ///< steps done (their action run, or left with Next)
  std::map<int, int> predicted;  ///< step -> the option chosen
  bool operator==(const LessonProgress& o) const {
    return step == o.step && done == o.done && predicted == o.predicted;
  }
};

struct UiSettings {
  float ui_scale = 1.0f;  ///< fonts and line widths, 1 ... 3
  bool degrees = true;    ///< angles shown in degrees (stored values stay radians)
  /// Lesson name (its file's stem) -> progress.
  std::map<std::string, LessonProgress> lessons;
};

/// Largest step or option number kept in the settings file (larger ones are dropped on reading;
/// the window clamps to the lesson's steps).
constexpr int kMaxLessonNumber = 1000;

/// Smallest and largest UI scale.
constexpr float kMinUiScale = 1.0f, kMaxUiScale = 3.0f;

/// The settings file's path ("" when neither XDG_CONFIG_HOME nor HOME is set).
std::string UiSettingsPath();
/// Reads the settings; a missing file gives the defaults, an unreadable or invalid one the
/// defaults and a `warning` naming file:line and the key (an invalid lesson entry is dropped
/// alone, the others kept).
UiSettings LoadUiSettings(std::string* warning = nullptr);
/// Writes the settings (temp file + rename, the folder made when missing). Returns "" or why not.
std::string SaveUiSettings(const UiSettings& s);

}  // namespace formsim::app
