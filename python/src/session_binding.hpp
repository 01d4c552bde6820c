#pragma once
/// \file `_core.Session`: a sim::Session (the one load path of `formsim run` and the window) as
/// Python sees it. The public class `formsim.Sim` (formsim/_sim.py) wraps it.

#include <pybind11/pybind11.h>

namespace formsim::python {

/// Adds the class `Session` to `m`.
void BindSession(pybind11::module_& m);

}  // namespace formsim::python
