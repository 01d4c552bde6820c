#pragma once
/// \file `formsim.tune`: the tune of `formsim tune` (sim::DefineTune, sim::RunTune) run in this
/// process without the GIL, its tables returned as the texts the CLI writes.

#include <pybind11/pybind11.h>

namespace formsim::python {

/// Adds tune to `m`.
void BindTune(pybind11::module_& m);

}  // namespace formsim::python
