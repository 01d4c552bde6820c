#include "python/src/render_binding.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "app/export/pictures.hpp"
#include "python/src/py_session.hpp"

namespace py = pybind11;

namespace formsim::python {
namespace {

py::array_t<std::uint8_t> RenderWorld(PySession& s, int width, int height, const std::string& theme,
                                      const std::string& overlays, bool legend) {
  std::vector<std::uint8_t> rgb;
  {
    py::gil_scoped_release free;
    rgb = app::RenderWorldRgb(s.exp(), width, height, theme, overlays, legend);
  }
  py::array_t<std::uint8_t> out({height, width, 3});
  std::memcpy(out.mutable_data(), rgb.data(), rgb.size());
  return out;
}

py::bytes FigureBytes(PySession& s, const std::string& name, const std::string& format,
                      const std::string& theme) {
  std::string bytes;
  {
    py::gil_scoped_release free;
    bytes = app::FigureBytes(s.exp(), name, format, theme);
  }
  return py::bytes(bytes);
}

}  // namespace

void BindRender(py::module_& m) {
  m.def("render_world", &RenderWorld, py::arg("session"), py::arg("width"), py::arg("height"),
        py::arg("theme"), py::arg("overlays"), py::arg("legend"),
        "The world view as `formsim run --snapshot F.png` draws it: a height x width x 3 uint8 "
        "array (without the GIL).");
  m.def(
      "figure_names", [](PySession& s) { return app::FigureNames(s.exp()); }, py::arg("session"),
      "The names of the run's figures now, as --plots names its files.");
  m.def("figure_bytes", &FigureBytes, py::arg("session"), py::arg("name"), py::arg("format"),
        py::arg("theme"),
        "The bytes of a figure's file as `formsim run --plots` writes it (without the GIL).");
}

}  // namespace formsim::python
