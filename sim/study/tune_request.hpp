#pragma once
/// \file What `formsim tune` is asked, as the texts of its flags, turned into the tune with
/// every check the CLI makes before anything runs: the scenarios, the settings (tunables,
/// metric, constraints, seeds, budget, method), the plan of stages and the holdout seeds. One
/// definition for the CLI (app/cli/study_cli.cpp) and the Python module (formsim.tune).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sim/scenario/scenario.hpp"
#include "sim/study/tune.hpp"
#include "sim/study/tune_plan.hpp"

namespace formsim::sim {

/// The flags of `formsim tune`, as text.
struct TuneRequest {
  std::string scenario;                        ///< the positional scenario (name or path)
  std::vector<std::string> scenarios;          ///< --scenario (more scenarios, or @FILE)
  std::vector<std::string> sets;               ///< --set KEY=VALUE
  std::string over = "mean";                   ///< --over
  std::vector<std::string> params;             ///< --param KEY or KEY:LO:HI
  std::string metric;                          ///< --metric
  std::vector<std::string> constraints;        ///< --constraint
  std::optional<std::string> seeds;            ///< --seeds (none: the scenario's own seed)
  int budget = 60;                             ///< --budget
  std::string algorithm = kDefaultTuneMethod;  ///< --method
  std::uint64_t search_seed = 1;               ///< --search-seed
  std::optional<std::string> holdout;          ///< --holdout
};

/// A tune ready to run.
struct TuneDefinition {
  std::vector<ScenarioSource> sources;  ///< the first is the positional scenario
  TuneSettings settings;
  std::vector<TuneStage> plan;
  std::vector<std::uint64_t> holdout;  ///< empty without --holdout
};

/// Reads the scenarios and checks every flag, naming it when refused (ScenarioError or
/// std::runtime_error), before anything runs.
TuneDefinition DefineTune(const TuneRequest& request);

/// A request from the flags' values, in the order of TuneRequest's fields: the one place that
/// says which value goes where, for `formsim tune`'s flags and formsim.tune's arguments alike.
TuneRequest MakeTuneRequest(std::string scenario, std::vector<std::string> scenarios,
                            std::vector<std::string> sets, std::string over,
                            std::vector<std::string> params, std::string metric,
                            std::vector<std::string> constraints, std::optional<std::string> seeds,
                            int budget, std::string algorithm, std::uint64_t search_seed,
                            std::optional<std::string> holdout);

}  // namespace formsim::sim
