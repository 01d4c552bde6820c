#include "sim/study/sweep.hpp"

#include <mutex>
#include <stdexcept>
#include <string>

#include "sim/core/run_output.hpp"

namespace formsim::sim {

std::optional<SweepRecord> RunScenarioOnce(const ScenarioSource& source,
                                           const std::vector<Override>& overrides,
                                           const std::function<bool()>& stop,
                                           const std::function<void(const Experiment&)>& inspect) {
  SweepRecord rec;
  try {
    std::unique_ptr<Experiment> exp = BuildExperiment(ParseScenario(source, overrides));
    exp->mutable_recorder().SetHistoryLimit(kRunHistoryRows);
    // The loop of `formsim run`, polling for a stop as often as it does.
    while (!exp->finished()) {
      exp->Step();
      if ((exp->steps() & 63) == 0 && stop && stop()) return std::nullopt;
    }
    rec.status = exp->status();
    rec.message = exp->stop_reason();
    FillRecordMetrics(exp->Results(), &rec);
    if (inspect) inspect(*exp);
  } catch (const std::exception& e) {
    rec.status = "error";
    rec.message = e.what();
    rec.metrics.clear();
    rec.settings.clear();
    rec.info.clear();
  }
  return rec;
}

std::optional<SweepRecord> RunSweepRun(const std::vector<ScenarioSource>& sources,
                                       const SweepDefinition& def, std::size_t run,
                                       const std::function<bool()>& stop,
                                       const RunInspector& inspect) {
  if (sources.size() != def.scenarios.size())
    throw std::runtime_error("the sweep has " + std::to_string(def.scenarios.size()) +
                             " scenarios, " + std::to_string(sources.size()) + " were given");
  std::function<void(const Experiment&)> see;
  if (inspect) see = [&](const Experiment& exp) { inspect(run, exp); };
  std::optional<SweepRecord> rec =
      RunScenarioOnce(sources[def.ScenarioOf(run)], def.RunOverrides(run), stop, see);
  if (rec) rec->run = run;
  return rec;
}

std::optional<SweepRecord> RunSweepRun(const ScenarioSource& source, const SweepDefinition& def,
                                       std::size_t run, const std::function<bool()>& stop,
                                       const RunInspector& inspect) {
  return RunSweepRun(std::vector<ScenarioSource>{source}, def, run, stop, inspect);
}

SweepProgress RunSweep(
    const ScenarioSource& source, const SweepDefinition& def, const std::vector<std::size_t>& runs,
    TaskPool& pool, const std::function<void(const SweepRecord&, const SweepProgress&)>& on_record,
    const std::function<bool()>& stop, const RunInspector& inspect) {
  return RunSweep(std::vector<ScenarioSource>{source}, def, runs, pool, on_record, stop, inspect);
}

SweepProgress RunSweep(
    const std::vector<ScenarioSource>& sources, const SweepDefinition& def,
    const std::vector<std::size_t>& runs, TaskPool& pool,
    const std::function<void(const SweepRecord&, const SweepProgress&)>& on_record,
    const std::function<bool()>& stop, const RunInspector& inspect) {
  SweepProgress progress;
  progress.total = runs.size();
  std::mutex mu;
  pool.ForEach(
      runs.size(),
      [&](std::size_t i) {
        const std::optional<SweepRecord> rec = RunSweepRun(sources, def, runs[i], stop, inspect);
        if (!rec) return;
        std::lock_guard<std::mutex> lock(mu);
        ++progress.done;
        if (rec->failed()) ++progress.failed;
        if (on_record) on_record(*rec, progress);
      },
      stop);
  return progress;
}

}  // namespace formsim::sim
