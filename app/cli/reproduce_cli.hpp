#pragma once
/// \file `formsim reproduce PAPER [--seeds 1..10] [--out DIR]` (a registered paper: formation,
/// agv, inspection, velocity): runs a paper's cases (sim/<kind>/<kind>_paper.cpp) through the sweep
/// engine for every seed and prints the paper's tables (docs/papers/) for it, every number read from the runs'
/// metrics. Writes into --out one sweep folder per case (manifest, records, runs.csv,
/// aggregate.csv), tables.md (what it printed), cells.csv (each cell with the metric and statistics
/// it shows) and the paper's bar charts (PNG and SVG).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace formsim::app {

class ReproduceCommand {
 public:
  /// Adds `reproduce` to `app`.
  explicit ReproduceCommand(CLI::App& app);
  bool parsed() const { return cmd_->parsed(); }
  /// Runs it. Returns the exit code: 0; 3 when a run stopped on a numerical fault or error (the
  /// tables are printed and written all the same, with the failures named); 4 when a figure
  /// could not be written; 128 + signal when interrupted. Throws on bad input.
  int Run();

 private:
  CLI::App* cmd_ = nullptr;
  std::string paper_;
  std::string seeds_ = "1..10";
  std::string out_;
  std::string tables_;
  std::string titles_ = "full";  ///< --titles full|short|none of the figures
  std::vector<std::string> sets_;
  int jobs_ = 0;  ///< 0: every hardware thread
  bool quiet_ = false;
};

}  // namespace formsim::app
