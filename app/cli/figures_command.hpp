#pragma once
/// \file `formsim figures [SCENARIO...] --out DIR`: every figure of every given scenario (default:
/// all shipped), plus the whole-run world view, in the chosen formats, one scenario per core.
/// Each scenario runs in a worker process through exactly the export path of `formsim run
/// --plots --snapshot` (so its figures are the same files), while this process shows the
/// progress of all of them.

#include <string>
#include <vector>

namespace formsim::app {

struct FiguresOptions {
  std::vector<std::string> scenarios;  ///< names or paths; empty: every shipped scenario
  std::string out_dir;                 ///< DIR/<scenario>/<figure>.<format>
  std::string formats = "png";         ///< --plot-format
  std::string plot_size = "960x600";   ///< --plot-size
  std::string size = "1280x720";       ///< --size: the world view
  double dpi = 96;
  std::string theme = "light";
  std::string titles = "full";  ///< --titles full|short|none
  std::string log_y;            ///< --log-y NAME,...: figures with a log y axis
  int jobs = 0;  ///< worker processes; 0: one per core
  bool quiet = false;
};

/// Runs the command; returns the exit code (0, 2 bad input, 3 a run stopped early, 4 an export
/// failed). Throws std::runtime_error for bad options, before anything is simulated.
int FiguresCommand(const FiguresOptions& opt);

}  // namespace formsim::app
