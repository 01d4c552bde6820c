#pragma once
/// \file The study commands: `formsim sweep` (every combination of varied tunables for every
/// seed, on all cores, resumable, in shards or as one job line per run), `formsim sweep
/// collect` (merges shards into the tables a one-process sweep writes) and `formsim tune`
/// (derivative-free optimisation of tunables for a metric averaged over seeds).

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "sim/study/tune_plan.hpp"

namespace formsim::app {

class StudyCommands {
 public:
  /// Adds `sweep` (with `sweep collect`) and `tune` to `app`.
  explicit StudyCommands(CLI::App& app);
  /// True when one of the commands was given on the command line.
  bool parsed() const;
  /// Runs the command given. Returns the exit code (0, 2 bad input or failed writes, 128 +
  /// signal when interrupted). Throws on bad input (the caller prints it and exits 2).
  int Run();

 private:
  /// `sweep` and `sweep collect` with their flags.
  void AddSweepCommands(CLI::App& app);
  /// `tune` with its flags.
  void AddTuneCommand(CLI::App& app);

  struct SweepPlan;  // the sweep the flags plan (study_cli.cpp)
  int Sweep();
  SweepPlan PlanSweep() const;
  int SweepOneRun(const SweepPlan& plan);
  int PrintSweepJobs(const SweepPlan& plan);
  void PrintSweepHeader(const SweepPlan& plan, std::size_t pending) const;
  int RunPlannedSweep(const SweepPlan& plan);
  int Collect();
  int Tune();

  CLI::App* sweep_ = nullptr;
  CLI::App* collect_ = nullptr;
  CLI::App* tune_ = nullptr;

  // sweep
  std::string scenario_;
  std::vector<std::string> scenarios_;  ///< --scenario A --scenario B (@FILE: a list)
  std::vector<std::string> vary_, sets_;
  std::string seeds_;
  std::string sample_seed_ = "1";
  int jobs_ = 0;  ///< 0: every hardware thread
  std::string out_;
  std::string metric_;
  std::string band_ = "ci95";  ///< --band sd|ci95|minmax: the spread shaded around the mean
  std::string titles_ = "full";  ///< --titles full|short|none of the figures
  std::string shard_;
  bool resume_ = false;
  bool print_jobs_ = false;
  long long run_ = -1;  ///< --run I: only run I (a job line); given when sweep_->count("--run")
  long long max_runs_ = 100000;  ///< --max-runs N: the largest sweep planned (kDefaultMaxSweepRuns)
  bool quiet_ = false;
  bool no_figures_ = false;
  // collect
  std::vector<std::string> collect_dirs_;
  std::string collect_out_, collect_metric_;
  std::string collect_band_ = "ci95";
  std::string collect_titles_ = "full";
  bool collect_quiet_ = false;
  // tune
  std::string tune_scenario_;
  std::vector<std::string> tune_scenarios_;  ///< --scenario A --scenario B (@FILE: a list)
  std::string over_ = "mean";
  std::vector<std::string> params_, tune_sets_;
  std::string tune_metric_, tune_seeds_, tune_out_, holdout_;
  std::vector<std::string> constraints_;
  std::string algorithm_ = sim::kDefaultTuneMethod;
  std::string tune_titles_ = "full";
  std::string search_seed_ = "1";  ///< --search-seed, read by ParseSeedFlag
  int budget_ = 60;
  int tune_jobs_ = 0;
  bool tune_quiet_ = false;
  bool tune_resume_ = false;
};

}  // namespace formsim::app
