#pragma once
/// \file `formsim gui`: the interactive window (GLFW, OpenGL 3.3 core) around AppUi.

#include <string>
#include <vector>

namespace formsim::app {

struct GuiOptions {
  std::string scenario;  ///< empty: the first shipped formation scenario
  long long seed = -1;
  std::vector<std::string> sets;
  int width = 1600, height = 900;
  std::string screenshot;  ///< saved after the last frame (with --exit-after) and on 's'
  long exit_after = -1;    ///< frames; -1 runs until the window closes
  bool exit_when_finished = false;
  bool paused = false;
  double speed = 1.0;  ///< 0 = as fast as possible
  /// Scripted edits "FRAME:key=value" applied as if made with a slider (tests, demos).
  std::vector<std::string> edits;
  std::string out_dir;  ///< write timeseries.csv and summary.json here on exit
  bool timing = false;  ///< print frame-time statistics on exit
};

/// Runs the GUI. Returns the process exit code; throws on setup errors (no display...).
int RunGui(const GuiOptions& opt);

}  // namespace formsim::app
