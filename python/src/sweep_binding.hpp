#pragma once
/// \file A sweep in pieces a cluster can share out (formsim/dask.py): define it once (the
/// scenario's text and the sweep manifest, both plain text a worker can be sent), run any one
/// of its runs anywhere (a record as `formsim sweep` writes it), and make the tables from the
/// records. Each piece is the code `formsim sweep` runs, so the tables are the same bytes.

#include <pybind11/pybind11.h>

namespace formsim::python {

/// Adds sweep_define, sweep_run and sweep_tables to `m`.
void BindSweep(pybind11::module_& m);

}  // namespace formsim::python
