#pragma once
/// \file `formsim replay FILE [--out DIR] [--frames DIR] [--video F] [--plots DIR]`: a session
/// record of the GUI (`formsim gui --session FILE`, "Save session") done again headless through
/// sim::Session, writing what `formsim run` writes: timeseries.csv and summary.json of the run
/// the record ends with (byte-identical to the GUI's `--out`), and with export flags its frames,
/// video and figures (the last run replayed once more from its log, with the pictures).

#include <CLI/CLI.hpp>
#include <string>

#include "app/export/export.hpp"

namespace formsim::app {

class ReplayCommand {
 public:
  /// Adds `replay` to `app`.
  explicit ReplayCommand(CLI::App& app);
  bool parsed() const { return cmd_->parsed(); }
  /// Runs it. Returns the exit code as `formsim run` does (0; 3 the last run stopped on a
  /// numerical fault; 4 an export failed). Throws on bad input (the caller prints it, exits 2).
  int Run();

 private:
  CLI::App* cmd_ = nullptr;
  std::string file_, out_, size_ = "1280x720", plot_size_ = "960x600", plot_format_ = "png";
  std::string theme_ = "light";
  ExportOptions exp_;
  bool quiet_ = false;
};

}  // namespace formsim::app
