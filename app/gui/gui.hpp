#pragma once
/// \file `formsim gui`: the interactive window (GLFW, OpenGL 3.3 core) around AppUi.

#include <set>
#include <string>
#include <vector>

#include "app/render/theme.hpp"

namespace formsim::app {

struct GuiOptions {
  std::string scenario;  ///< empty: the first shipped formation scenario
  std::string lesson;    ///< a lesson name or path (instead of scenario); opens on its Lesson tab
  std::string seed;  ///< empty: the scenario's

  std::vector<std::string> sets;
  int width = 1600, height = 900;
  std::string screenshot;  ///< saved after the last frame (with --exit-after) and on 's'
  long exit_after = -1;    ///< frames; -1 runs until the window closes
  bool exit_when_finished = false;
  bool paused = false;
  double speed = 1.0;  ///< 0 = as fast as possible
  /// Scripted edits "FRAME:key=value" applied as if made with a slider (tests, demos); a
  /// shorthand for the script action "FRAME edit key=value".
  std::vector<std::string> edits;
  /// A script file: one action per line, "FRAME ACTION [ARGS]" (see ScriptAction).
  std::string script;
  std::string out_dir;  ///< write timeseries.csv and summary.json here on exit
  /// Record the session (every edit with its step, resets, seeds, loads, pins, branches) into
  /// this file on exit; also the default of the "Save session" button.
  std::string session_file;
  bool timing = false;  ///< print frame-time statistics on exit
  ThemeId theme = ThemeId::kLight;
  /// --overlay: the scene's overlays in the window (else the defaults).
  std::set<std::string> overlays;
  bool overlays_given = false;
};

/// One scripted GUI action: at frame `frame`, `action` ("edit k=v", "reset", "reset-seed 7",
/// "reload", "load NAME", "open PATH", "save PATH", "play", "pause", "step",
/// "screenshot PATH", "action ID", "pin", "seeds 20", "scrub 3.5", "branch", ... see
/// AppUi::RunScriptAction), run through the same commands as the mouse and keyboard. `wait`
/// holds the script (and the frame count of --exit-after) until the background work is done.
struct ScriptAction {
  long frame = 0;
  std::string action;
  std::string where;  ///< "script.txt:3" or "--edit", for messages
};
/// Reads a script file (blank lines and lines starting with # are skipped). Throws
/// std::runtime_error naming file:line for a malformed line.
std::vector<ScriptAction> ReadScript(const std::string& file);

/// Runs the GUI. Returns the process exit code; throws on setup errors (no display...).
int RunGui(const GuiOptions& opt);

}  // namespace formsim::app
