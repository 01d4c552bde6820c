#include "python/src/tune_binding.hpp"

#include <pybind11/stl.h>

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sim/core/task_pool.hpp"
#include "sim/study/tune.hpp"
#include "sim/study/tune_history.hpp"
#include "sim/study/tune_request.hpp"
#include "sim/study/tune_validation.hpp"

namespace py = pybind11;

namespace formsim::python {
namespace {

// The tune's results: history.csv and validation.csv as formsim tune writes them, and the best
// point (the closest one to feasible when none is).
py::dict Tune(const sim::TuneRequest& request, int jobs) {
  if (jobs < 1 || jobs > 1024)
    throw std::runtime_error("jobs: expected 1 ... 1024, got " + std::to_string(jobs));
  const sim::TuneDefinition def = sim::DefineTune(request);
  const sim::TuneSettings& s = def.settings;
  sim::TuneResult r;
  std::optional<sim::TuneValidation> validation;
  std::atomic<bool> interrupted{false};
  {
    py::gil_scoped_release free;
    sim::TaskPool pool(jobs);
    // Ctrl-C: looked at after each evaluation; the tune ends there, as formsim tune does.
    auto progress = [&](const sim::TuneEvaluation&, const sim::TuneEvaluation&) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        PyErr_Clear();
        interrupted = true;
      }
    };
    auto stop = [&] { return interrupted.load(); };
    r = sim::RunTune(def.sources, s, pool, progress, stop);
    if (!def.holdout.empty() && r.has_best() && !interrupted)
      validation = sim::ValidateTune(def.sources, s, r.history.front().values,
                                     r.history[r.best].values, def.holdout, pool, stop);
  }
  if (interrupted) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  py::dict out;
  out["history_csv"] = sim::TuneHistoryCsv(s, r);
  out["validation_csv"] = validation ? py::object(py::str(sim::TuneValidationCsv(*validation)))
                                     : py::object(py::none());
  out["stop_reason"] = r.stop_reason;
  out["has_best"] = r.has_best();
  py::dict best;
  if (!r.history.empty()) {
    const sim::TuneEvaluation& e = r.history[r.best];
    for (std::size_t i = 0; i < s.params.size(); ++i) {
      const sim::TuneParam& p = s.params[i];
      if (p.kind == sim::TuneParam::Kind::kChoice)
        best[py::str(p.key)] = p.Text(e.values[i]);
      else if (p.kind == sim::TuneParam::Kind::kInteger)
        best[py::str(p.key)] = static_cast<long long>(e.values[i]);
      else
        best[py::str(p.key)] = e.values[i];
    }
    out["objective"] = e.objective;
    out["evaluation"] = e.index;
  } else {
    out["objective"] = py::none();
    out["evaluation"] = py::none();
  }
  out["best"] = best;
  return out;
}

}  // namespace

void BindTune(py::module_& m) {
  m.def(
      "tune",
      [](const std::string& scenario, const std::vector<std::string>& scenarios,
         const std::vector<std::string>& sets, const std::string& over,
         const std::vector<std::string>& params, const std::string& metric,
         const std::vector<std::string>& constraints, const std::optional<std::string>& seeds,
         int budget, const std::string& method, std::uint64_t search_seed,
         const std::optional<std::string>& holdout, int jobs) {
        return Tune(sim::MakeTuneRequest(scenario, scenarios, sets, over, params, metric,
                                         constraints, seeds, budget, method, search_seed, holdout),
                    jobs);
      },
      py::arg("scenario"), py::arg("scenarios"), py::arg("sets"), py::arg("over"),
      py::arg("params"), py::arg("metric"), py::arg("constraints"), py::arg("seeds"),
      py::arg("budget"), py::arg("method"), py::arg("search_seed"), py::arg("holdout"),
      py::arg("jobs"),
      "Runs `formsim tune` with these flags' texts (without the GIL). Returns a dict: "
      "history_csv, validation_csv (None without holdout), best {key: value}, objective, "
      "evaluation, has_best, stop_reason.");
}

}  // namespace formsim::python
