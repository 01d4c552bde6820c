#include "python/src/session_binding.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "python/src/errors.hpp"
#include "sim/core/recorder.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"

namespace py = pybind11;

namespace formsim::python {
namespace {

// Steps between two looks at Python's signal handlers (Ctrl-C) during a long call.
constexpr long kSignalCheckSteps = 1024;

const char* KindName(sim::Param::Kind k) {
  switch (k) {
    case sim::Param::Kind::kDouble:
      return "float";
    case sim::Param::Kind::kInt:
      return "int";
    case sim::Param::Kind::kBool:
      return "bool";
    case sim::Param::Kind::kChoice:
      return "choice";
  }
  return "float";
}

// A tunable's value as the Python type its kind names.
py::object ParamValue(const sim::Param& p) {
  switch (p.kind) {
    case sim::Param::Kind::kInt:
      return py::int_(static_cast<long long>(p.value));
    case sim::Param::Kind::kBool:
      return py::bool_(p.value != 0.0);
    case sim::Param::Kind::kChoice:
      return py::str(p.Text());
    case sim::Param::Kind::kDouble:
      break;
  }
  return py::float_(p.value);
}

class PySession {
 public:
  // `sets`: (key, YAML text) in order, as `--set key=value`; `seed`: as `--seed` (decimal text).
  PySession(const std::string& name_or_path,
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

  sim::Experiment& exp() { return session_->exp(); }

  // Steps until `n` steps were taken, the run ended or the time reached `until` (NaN: no
  // limit), without the GIL. Returns the number of steps taken. Ctrl-C stops the loop (the run
  // stays where it is, valid) with KeyboardInterrupt.
  long Advance(long n, double until) {
    if (n < 0) RaiseError("step: n must be >= 0, got " + std::to_string(n));
    long done = 0;
    bool interrupted = false;
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
    return done;
  }

  // "" or the reason (naming the key) the edit was refused.
  std::string Edit(const std::string& key, const std::string& value) {
    std::string why = session_->Edit(key, value, "Python edit");
    if (why.empty()) {
      session_->ApplyPending();  // live edits now (between two steps), so tunables shows them
      return why;
    }
    if (why.find(key) == std::string::npos) why = key + ": " + why;
    return why;
  }

  std::string Reset(const std::optional<std::uint64_t>& seed) {
    if (seed) return session_->Reset(*seed);
    return session_->Reset();
  }

  py::list Tunables() const {
    py::list out;
    const auto waiting = session_->waiting_for_reset();
    for (const sim::Param& p : session_->params().all()) {
      py::dict d;
      d["key"] = p.key;
      d["value"] = ParamValue(p);
      d["kind"] = KindName(p.kind);
      d["range"] = py::make_tuple(p.tune.lo, p.tune.hi);
      d["validity"] = p.tune.ValidityText();
      d["unit"] = p.tune.unit;
      d["label"] = p.tune.label;
      d["group"] = p.tune.group;
      d["help"] = p.tune.help;
      d["live"] = p.tune.live;
      d["choices"] = p.choices;
      const auto it = waiting.find(p.key);
      d["pending"] = it == waiting.end() ? py::object(py::none()) : py::object(py::str(it->second));
      out.append(d);
    }
    return out;
  }

  std::vector<std::string> Columns() { return exp().recorder().names(); }

  // Every recorded row, rows x columns, copied into one array (the recorder keeps growing as
  // the run goes on, so a view could be left pointing at freed memory).
  py::array_t<double> Data() {
    const sim::Recorder& rec = exp().recorder();
    const std::size_t rows = rec.rows(), cols = rec.columns();
    py::array_t<double> out({rows, cols});
    double* dst = out.mutable_data();
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < cols; ++c) dst[r * cols + c] = rec.At(r, static_cast<int>(c));
    return out;
  }

  py::list Events() {
    py::list out;
    for (const sim::Event& e : exp().events().list()) {
      py::dict d;
      d["t"] = e.time;
      d["kind"] = e.kind;
      d["robots"] = e.robots;
      if (!e.subject.empty()) d["subject"] = e.subject;
      d["message"] = e.message;
      out.append(d);
    }
    return out;
  }

  std::unique_ptr<sim::Session> session_;
};

}  // namespace

void BindSession(py::module_& m) {
  py::class_<PySession>(m, "Session",
                        "A scenario loaded through the one load path (sim::Session); use "
                        "formsim.load(), which wraps it in a formsim.Sim.")
      .def(py::init<const std::string&, const std::vector<std::pair<std::string, std::string>>&,
                    const std::optional<std::string>&, int>(),
           py::arg("name_or_path"), py::arg("sets"), py::arg("seed"), py::arg("threads"))
      .def("advance", &PySession::Advance, py::arg("n"), py::arg("until"),
           "Steps at most n steps, until the run ends or the time reaches `until` (NaN: no "
           "limit), without the GIL. Returns the steps taken.")
      .def("edit", &PySession::Edit, py::arg("key"), py::arg("value"),
           "Edits tunable `key` to `value` (YAML text) as the window does. Returns '' or the "
           "reason it was refused (nothing changed then).")
      .def("reset", &PySession::Reset, py::arg("seed"),
           "Restarts the run with every accepted edit (and `seed` when given). Returns '' or "
           "the reason it failed (the run then stays as it was).")
      .def("tunables", &PySession::Tunables, "Every tunable as a dict, in declaration order.")
      .def("columns", &PySession::Columns, "The recorded channels: the CSV's column names.")
      .def("data", &PySession::Data,
           "The recorded rows as a rows x columns float64 array (a copy).")
      .def("events", &PySession::Events, "The stored events, oldest first, as dicts.")
      .def(
          "summary_json", [](PySession& s) { return s.exp().Summary().Dump(); },
          "summary.json's text.")
      .def(
          "summary_text", [](PySession& s) { return s.exp().SummaryText(); },
          "What `formsim run` prints: the results' tables and the event counts.")
      .def_property_readonly("time", [](PySession& s) { return s.exp().time(); })
      .def_property_readonly("steps", [](PySession& s) { return s.exp().steps(); })
      .def_property_readonly("dt", [](PySession& s) { return s.exp().dt(); })
      .def_property_readonly("duration", [](PySession& s) { return s.exp().setup().duration; })
      .def_property_readonly("finished", [](PySession& s) { return s.exp().finished(); })
      .def_property_readonly("status", [](PySession& s) { return s.exp().status(); })
      .def_property_readonly("stop_reason", [](PySession& s) { return s.exp().stop_reason(); })
      .def_property_readonly("seed", [](PySession& s) { return s.session_->seed(); })
      .def_property_readonly("file", [](PySession& s) { return s.session_->file(); })
      .def_property_readonly("name", [](PySession& s) { return s.exp().setup().name; })
      .def_property_readonly("type", [](PySession& s) { return s.exp().setup().type; });
}

}  // namespace formsim::python
