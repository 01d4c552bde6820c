#include "python/src/py_session.hpp"

#include <pybind11/pybind11.h>

#include "python/src/errors.hpp"
#include "sim/scenario/scenario_files.hpp"

namespace py = pybind11;

namespace formsim::python {
namespace {

// Steps between two looks at Python's signal handlers (Ctrl-C) during a long call.
constexpr long kSignalCheckSteps = 1024;

}  // namespace

PySession::PySession(const std::string& name_or_path,
                     const std::vector<std::pair<std::string, std::string>>& sets,
                     const std::optional<std::string>& seed, int threads) {
  std::vector<sim::Override> overrides;
  for (const auto& [key, value] : sets) overrides.push_back({key, value, "--set", -1});
  if (seed) overrides.push_back({"seed", *seed, "--seed", -1});
  session_ = std::make_unique<sim::Session>(sim::ResolveScenario(name_or_path), overrides);
  if (threads > 0) {
    session_->SetRunSetup([threads](sim::Experiment& e) { e.SetThreads(threads); });
  }
}

long PySession::Advance(long n, double until) {
  if (n < 0) RaiseError("step: n must be >= 0, got " + std::to_string(n));
  long done = 0;
  bool interrupted = false;
  const bool was_faulted = session_->exp().status() == "numerical_fault";
  {
    py::gil_scoped_release free;
    sim::Experiment* e = &session_->exp();
    const double half_dt = 0.5 * e->dt();
    while (done < n && !e->finished() && !(e->time() >= until - half_dt)) {
      session_->Step();
      ++done;
      if (done % kSignalCheckSteps == 0) {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) {
          interrupted = true;
          break;
        }
      }
    }
  }
  if (interrupted) throw py::error_already_set();
  if (!was_faulted && session_->exp().status() == "numerical_fault") return -(done + 1);
  return done;
}

std::string PySession::Edit(const std::string& key, const std::string& value) {
  std::string why = session_->Edit(key, value, "Python edit");
  if (why.empty()) {
    session_->ApplyPending();  // live edits now (between two steps), so tunables shows them
    return why;
  }
  if (why.find(key) == std::string::npos) why = key + ": " + why;
  return why;
}

std::string PySession::Reset(const std::optional<std::uint64_t>& seed) {
  if (seed) return session_->Reset(*seed);
  return session_->Reset();
}

}  // namespace formsim::python
