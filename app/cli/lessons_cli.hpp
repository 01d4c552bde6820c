#pragma once
/// \file `formsim lessons check [NAME...] [--seeds 1..N] [--jobs N]`: runs the checks of every
/// shipped lesson (or of those named) and prints one line per check: lesson, id, the measured
/// value on each seed, the relation, holds / FAILS. Exits 1 when any check fails.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace formsim::app {

class LessonsCommand {
 public:
  /// Adds `lessons` (with its subcommand `check`) to `app`.
  explicit LessonsCommand(CLI::App& app);
  bool parsed() const { return cmd_->parsed(); }
  /// Runs it. Returns 0 when every check holds, 1 when one fails. Throws on bad input (an
  /// unknown lesson, bad seeds).
  int Run();

 private:
  CLI::App* cmd_ = nullptr;
  CLI::App* check_ = nullptr;
  std::vector<std::string> names_;
  std::string seeds_;
  int jobs_ = 0;  ///< 0: every hardware thread
};

}  // namespace formsim::app
