#pragma once
/// \file formsim.Error: every refusal of the loader, the session or the files becomes this one
/// Python exception (a ValueError) carrying the loader's reason, so bad input never takes the
/// interpreter down.

#include <pybind11/pybind11.h>

#include <string>

namespace formsim::python {

/// Creates `_core.Error` in `m` (shown as formsim.Error) and registers the translation of C++
/// exceptions: sim::ScenarioError and std::exception become formsim.Error (a ScenarioError's
/// location, key and reason as attributes), std::bad_alloc MemoryError; pybind11's own
/// exceptions (TypeError for a wrong argument type) stay what they are.
void RegisterErrors(pybind11::module_& m);

/// Raises formsim.Error with `message` (throws pybind11::error_already_set).
[[noreturn]] void RaiseError(const std::string& message);

}  // namespace formsim::python
