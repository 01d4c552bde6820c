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
#include "python/src/py_session.hpp"
#include "sim/core/recorder.hpp"
#include "sim/session/session.hpp"

namespace py = pybind11;

namespace formsim::python {
namespace {

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

py::list Tunables(PySession& s) {
  py::list out;
  const auto waiting = s.session().waiting_for_reset();
  for (const sim::Param& p : s.session().params().all()) {
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

// Every recorded row, rows x columns, as a read-only view of the recorder's rows (no copy):
// the array owns a reference to the buffer (Recorder::SharedRows), which later steps, a reset
// or the Sim's end never change or free; a row that needs room moves the recorder on to a new
// buffer instead.
py::array_t<double> Data(PySession& s) {
  const sim::Recorder& rec = s.exp().recorder();
  const std::size_t rows = rec.rows(), cols = rec.columns();
  auto* rows_ref = new std::shared_ptr<const std::vector<double>>(rec.SharedRows());
  py::capsule owner(rows_ref, [](void* p) {
    delete static_cast<std::shared_ptr<const std::vector<double>>*>(p);
  });
  static const double kEmpty = 0;  // numpy needs a pointer for an empty array too
  const double* first = rows == 0 ? &kEmpty : (*rows_ref)->data();
  py::array_t<double> out({rows, cols}, {cols * sizeof(double), sizeof(double)}, first, owner);
  py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return out;
}

py::list Events(PySession& s) {
  py::list out;
  for (const sim::Event& e : s.exp().events().list()) {
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
           "limit), without the GIL. Returns the steps taken, or -(steps + 1) when this call "
           "stopped the run at a numerical fault.")
      .def("edit", &PySession::Edit, py::arg("key"), py::arg("value"),
           "Edits tunable `key` to `value` (YAML text) as the window does. Returns '' or the "
           "reason it was refused (nothing changed then).")
      .def("reset", &PySession::Reset, py::arg("seed"),
           "Restarts the run with every accepted edit (and `seed` when given). Returns '' or "
           "the reason it failed (the run then stays as it was).")
      .def("tunables", &Tunables, "Every tunable as a dict, in declaration order.")
      .def(
          "columns", [](PySession& s) { return s.exp().recorder().names(); }, "The recorded channels: the CSV's column names.")
      .def("data", &Data,
           "The recorded rows as a rows x columns float64 array: a read-only view of the "
           "recorder's rows that later steps do not change (no copy).")
      .def("events", &Events, "The stored events, oldest first, as dicts.")
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
      .def_property_readonly("seed", [](PySession& s) { return s.session().seed(); })
      .def_property_readonly("file", [](PySession& s) { return s.session().file(); })
      .def_property_readonly("name", [](PySession& s) { return s.exp().setup().name; })
      .def_property_readonly("type", [](PySession& s) { return s.exp().setup().type; });
}

}  // namespace formsim::python
