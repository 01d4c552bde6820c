#include "python/src/errors.hpp"

#include <new>
#include <stdexcept>

#include "sim/core/yaml_reader.hpp"

namespace py = pybind11;

namespace formsim::python {
namespace {

// The exception type, created once by RegisterErrors (the module lives as long as the process).
PyObject* g_error = nullptr;

// Sets formsim.Error(message) with its attributes as the pending Python exception.
void SetError(const std::string& message, const std::string& location, const std::string& key,
              const std::string& reason) {
  py::gil_scoped_acquire gil;
  py::object type = py::reinterpret_borrow<py::object>(g_error);
  py::object exc = type(message);
  exc.attr("location") = location;
  exc.attr("key") = key;
  exc.attr("reason") = reason;
  PyErr_SetObject(g_error, exc.ptr());
}

}  // namespace

void RegisterErrors(py::module_& m) {
  static py::exception<std::runtime_error> error(m, "Error", PyExc_ValueError);
  error.attr("__module__") = "formsim";
  error.attr("__doc__") =
      "A refused input: an unknown scenario or key, a value the loader refuses (with its "
      "reason), an unreadable file. A ValueError. Attributes: location (file:line or the "
      "--set / edit that put the value there), key, reason (the message without them); empty "
      "when the refusal has none.";
  g_error = error.ptr();
  py::register_local_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (TypeError, ValueError ...): let its translator set them
    } catch (const py::error_already_set&) {
      throw;
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "formsim: out of memory");
    } catch (const sim::ScenarioError& e) {
      SetError(e.what(), e.location(), e.key(), e.reason());
    } catch (const std::exception& e) {
      SetError(e.what(), "", "", e.what());
    }
  });
}

void RaiseError(const std::string& message) {
  SetError(message, "", "", message);
  throw py::error_already_set();
}

}  // namespace formsim::python
