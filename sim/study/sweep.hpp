#pragma once
/// \file Running a sweep in-process: each run is the scenario's text (read once) parsed with the
/// run's overrides ({--set..., key=value..., seed}) through the one load path, built, and
/// stepped to its end exactly as `formsim run` steps it; its metrics are Metrics::Scalars() of
/// Results(). Runs go to a TaskPool; a run's result depends on its overrides alone, so the
/// records are the same with any number of threads and in any order of completion.

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "sim/scenario/scenario.hpp"
#include "sim/study/sweep_store.hpp"
#include "sim/core/task_pool.hpp"

namespace formsim::sim {

/// Sees a finished run of a sweep (its index and experiment) on the worker that ran it.
using RunInspector = std::function<void(std::size_t run, const Experiment& exp)>;

/// Runs one parameterisation of `source` to its end and returns its record (run index 0):
/// status "completed", "numerical_fault" (message: the fault) or "error" (a scenario error or
/// an exception while building or stepping; message: what it said). When `stop()` turns true
/// mid-run the run is abandoned and std::nullopt returned. `inspect`, when given, sees the
/// finished experiment before it is destroyed (e.g. to keep its recorded series).
std::optional<SweepRecord> RunScenarioOnce(
    const ScenarioSource& source, const std::vector<Override>& overrides,
    const std::function<bool()>& stop = {},
    const std::function<void(const Experiment&)>& inspect = {});

/// Run `run` of `def` (RunScenarioOnce of its scenario, sources[def.ScenarioOf(run)], with the
/// run's overrides). `sources` are the sweep's scenarios in order (throws when their number is
/// not the definition's).
std::optional<SweepRecord> RunSweepRun(const std::vector<ScenarioSource>& sources,
                                       const SweepDefinition& def, std::size_t run,
                                       const std::function<bool()>& stop = {},
                                       const RunInspector& inspect = {});
/// A sweep of one scenario.
std::optional<SweepRecord> RunSweepRun(const ScenarioSource& source, const SweepDefinition& def,
                                       std::size_t run, const std::function<bool()>& stop = {},
                                       const RunInspector& inspect = {});

/// Where a sweep stands.
struct SweepProgress {
  std::size_t total = 0;   ///< runs asked for
  std::size_t done = 0;    ///< recorded so far (failed ones included)
  std::size_t failed = 0;  ///< recorded with status other than completed
};

/// Runs `runs` of `def` on `pool`. Each finished run is handed to `on_record` at once (calls
/// are serialised; completion order varies, the records do not). Runs abandoned because
/// `stop()` turned true are not handed over. Returns the final progress. `inspect` sees each
/// finished experiment (on the worker that ran it) before its record is handed over.
SweepProgress RunSweep(
    const std::vector<ScenarioSource>& sources, const SweepDefinition& def,
    const std::vector<std::size_t>& runs, TaskPool& pool,
    const std::function<void(const SweepRecord&, const SweepProgress&)>& on_record,
    const std::function<bool()>& stop = {}, const RunInspector& inspect = {});
/// A sweep of one scenario.
SweepProgress RunSweep(
    const ScenarioSource& source, const SweepDefinition& def, const std::vector<std::size_t>& runs,
    TaskPool& pool, const std::function<void(const SweepRecord&, const SweepProgress&)>& on_record,
    const std::function<bool()>& stop = {}, const RunInspector& inspect = {});

}  // namespace formsim::sim
