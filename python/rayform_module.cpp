// The `rayform` Python module: its errors, then its parts (scene_object.cpp,
// render_call.cpp, file_calls.cpp). Docs: docs/python.md; stubs: rayform.pyi.
#include "module_parts.h"
#include "rayform/base/error.h"

#include <pybind11/numpy.h>

namespace rayform::python {

std::string path_argument(const py::handle& value, const char* what) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__")) {
    py::object p = value.attr("__fspath__")();
    if (py::isinstance<py::str>(p)) return p.cast<std::string>();
  }
  throw py::type_error(std::string(what) + ": expected a path (str or os.PathLike), got " +
                       py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

}  // namespace rayform::python

PYBIND11_MODULE(rayform, m) {
  namespace py = pybind11;
  using namespace rayform::python;
  m.doc() =
      "rayform: read course .txt, OBJ and glTF scenes and render them into NumPy arrays, with the command line's "
      "defaults (docs/python.md).";
  m.attr("__version__") = RAYFORM_VERSION;
  // rayform::Error (a bad file, a failed render or write): the one line the
  // command line prints. UsageError (options that do not combine): ValueError.
  static py::exception<rayform::Error> error(m, "Error", PyExc_RuntimeError);
  error.doc() =
      "A file that cannot be read or written, or a render that failed: str(e) is the one line the command line "
      "prints (file, line:column or JSON path, what was expected).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const rayform::Error& e) {
      error(e.what());
    } catch (const rayform::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  // NumPy's C API, looked up once here while the import holds the GIL: a
  // first lookup in render() (a function-local static that imports numpy)
  // deadlocks when two threads make it at once.
  py::array_t<float>(std::vector<py::ssize_t>{0});
  py::array_t<uint8_t>(std::vector<py::ssize_t>{0});
  add_scene(m);
  add_render(m);
  add_files(m);
}
