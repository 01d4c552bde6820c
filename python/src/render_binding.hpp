#pragma once
/// \file Pictures of a Session (Sim.render, Sim.figure): the world view as an HxWx3 uint8 array
/// and a figure's file bytes, drawn by the app's offscreen renderer and figure writers
/// (app/export/pictures.hpp) without the GIL.

#include <pybind11/pybind11.h>

namespace formsim::python {

/// Adds render_world, figure_names and figure_bytes to `m` (after BindSession).
void BindRender(pybind11::module_& m);

}  // namespace formsim::python
