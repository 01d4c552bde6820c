/// \file The extension `formsim._core`: the C++ side of the Python package `formsim`
/// (formsim/__init__.py holds the public API and its documentation).

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <tuple>
#include <vector>

#include "python/src/errors.hpp"
#ifdef FORMSIM_PYTHON_PICTURES
#include "python/src/render_binding.hpp"
#endif
#include "python/src/session_binding.hpp"
#include "python/src/sweep_binding.hpp"
#include "python/src/tune_binding.hpp"
#include "sim/core/provenance.hpp"
#include "sim/scenario/scenario_files.hpp"

namespace py = pybind11;

namespace {

using Listing = std::tuple<std::string, std::string, std::string>;

// (name, type, description) of every file, as `formsim list` shows them.
std::vector<Listing> List(const std::vector<std::string>& files,
                          formsim::sim::ScenarioListing (*describe)(const std::string&)) {
  std::vector<Listing> out;
  for (const auto& file : files) {
    const auto s = describe(file);
    out.emplace_back(s.name, s.type, s.description);
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "The C++ side of formsim (use the package formsim, not this module).";
  formsim::python::RegisterErrors(m);
  formsim::python::BindSession(m);
  formsim::python::BindSweep(m);
  formsim::python::BindTune(m);
#ifdef FORMSIM_PYTHON_PICTURES
  formsim::python::BindRender(m);
#endif
  m.def(
      "scenarios",
      [] { return List(formsim::sim::ShippedScenarios(), &formsim::sim::DescribeScenario); },
      "The shipped scenarios as (name, type, description), by name.");
  m.def(
      "lessons", [] { return List(formsim::sim::ShippedLessons(), &formsim::sim::DescribeLesson); },
      "The shipped lessons as (name, type, title), by name.");
  m.def("resolve", &formsim::sim::ResolveScenario, py::arg("name_or_path"),
        "The scenario file a name or path stands for (as `formsim run` resolves it).");
  m.def("version", &formsim::sim::FormsimVersion, "The version formsim was built as.");
}
