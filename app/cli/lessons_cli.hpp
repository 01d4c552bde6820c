#pragma once
/// \file `formsim lessons check [NAME...] [--seeds 1..N] [--jobs N]`: runs the checks of every
/// shipped lesson (or of those named) and prints one line per check: lesson, id, the measured
/// value on each seed, the relation, holds / FAILS. Exits 1 when any check fails.
///
/// `lessons check --set PATH=VALUE` (repeatable) applies an edit to every run first: a deliberate
/// error in the scenario, which some check of the lesson must catch (tests/app: the mutation
/// test).
///
/// `formsim lessons show NAME [--seed N] [--jobs N]`: runs the lesson's checks on one seed
/// (default 1) and prints its text as a student reads it, every `{check}` replaced by the value
/// measured and its verdict (sim::RenderLessonText, the window's renderer), then one line per
/// check. Exits 1 when a check does not hold on that seed.

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
  CLI::App* show_ = nullptr;
  std::string show_name_;
  std::string show_seed_ = "1";  ///< --seed, parsed by ParseSeeds (one seed)
  int RunShow();
  std::vector<std::string> names_;
  std::string seeds_;
  std::vector<std::string> sets_;  ///< --set: edits applied to every run (a mutation)
  int jobs_ = 0;  ///< 0: every hardware thread
};

}  // namespace formsim::app
