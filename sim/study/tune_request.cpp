#include "sim/study/tune_request.hpp"

#include <stdexcept>
#include <utility>

#include "sim/study/scenario_set.hpp"
#include "sim/study/sweep_spec.hpp"
#include "sim/study/tune_validation.hpp"

namespace formsim::sim {

TuneDefinition DefineTune(const TuneRequest& request) {
  TuneDefinition d;
  d.sources = ReadScenarioSet(request.scenario, request.scenarios, "formsim tune");
  TuneSettings& s = d.settings;
  s.sets = CliOverrides(request.sets, -1);
  s.over = ParseTuneOver(request.over);
  const ParsedScenario base = ParseScenario(d.sources.front(), s.sets);
  for (const std::string& p : request.params) {
    s.params.push_back(ParseTuneParam(p, base.params));
    for (std::size_t i = 0; i + 1 < s.params.size(); ++i)
      if (s.params[i].key == s.params.back().key)
        throw std::runtime_error("--param " + p + ": tuned twice");
  }
  CheckTunedKeys(d.sources, s);
  s.objective = ParseMetricExpr(request.metric);
  for (const std::string& c : request.constraints) s.constraints.push_back(ParseTuneConstraint(c));
  s.seeds =
      request.seeds ? ParseSeeds(*request.seeds) : std::vector<std::uint64_t>{base.setup.seed};
  s.budget = request.budget;
  s.algorithm = request.algorithm;
  s.search_seed = request.search_seed;
  if (request.budget < 1 || request.budget > 100000)
    throw std::runtime_error("--budget must be in 1 ... 100000");
  d.plan = PlanTune(s.algorithm, static_cast<int>(s.params.size()), s.budget);
  if (request.holdout) {
    d.holdout = ParseSeeds(*request.holdout, "--holdout");
    CheckHoldout(d.holdout, s.seeds);
  }
  return d;
}

TuneRequest MakeTuneRequest(std::string scenario, std::vector<std::string> scenarios,
                            std::vector<std::string> sets, std::string over,
                            std::vector<std::string> params, std::string metric,
                            std::vector<std::string> constraints, std::optional<std::string> seeds,
                            int budget, std::string algorithm, std::uint64_t search_seed,
                            std::optional<std::string> holdout) {
  TuneRequest r;
  r.scenario = std::move(scenario);
  r.scenarios = std::move(scenarios);
  r.sets = std::move(sets);
  r.over = std::move(over);
  r.params = std::move(params);
  r.metric = std::move(metric);
  r.constraints = std::move(constraints);
  r.seeds = std::move(seeds);
  r.budget = budget;
  r.algorithm = std::move(algorithm);
  r.search_seed = search_seed;
  r.holdout = std::move(holdout);
  return r;
}

}  // namespace formsim::sim
