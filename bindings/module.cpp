// vtrack._core: the compiled half of the Python package. Conversion and validation only.
#include <cstring>
#include <new>

#include "common.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/version.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "Compiled core of vtrack (use the public API in `vtrack`).";
  m.attr("__version__") = vtrack::kVersion;
  // C++ errors become Python exceptions that are also the built-in ones users expect to catch.
  auto& invalid = pybind11::register_exception<vtrack::InvalidArgument>(m, "InvalidArgument",
                                                                        PyExc_ValueError);
  invalid.attr("__doc__") = "A value passed to vtrack is out of range or inconsistent (a ValueError).";
  auto& io_error = pybind11::register_exception<vtrack::IoError>(m, "IoError", PyExc_OSError);
  io_error.attr("__doc__") = "A file or video could not be read or written (an OSError).";
  // Registered after InvalidArgument, so that pybind11 tries it first (it derives from it).
  auto& invalid_type = pybind11::register_exception<vtrack::InvalidType>(m, "InvalidType",
                                                                         PyExc_TypeError);
  invalid_type.attr("__doc__") =
      "An unknown parameter name, or a value of the wrong kind for a parameter (a TypeError).";
  // Messages quote file contents and paths, which need not be UTF-8 (a det file with a stray
  // \xff byte): decoded with backslash escapes, so the message arrives instead of a
  // UnicodeDecodeError that hides it. Registered last, so tried first.
  static PyObject* const types[] = {invalid_type.ptr(), invalid.ptr(), io_error.ptr()};
  pybind11::register_exception_translator([](std::exception_ptr thrown) {
    auto raise = [](PyObject* type, const char* what) {
      PyObject* message = PyUnicode_DecodeUTF8(what, static_cast<Py_ssize_t>(std::strlen(what)),
                                               "backslashreplace");
      PyErr_SetObject(type, message);
      Py_XDECREF(message);
    };
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const vtrack::InvalidType& e) {
      raise(types[0], e.what());
    } catch (const vtrack::InvalidArgument& e) {
      raise(types[1], e.what());
    } catch (const vtrack::IoError& e) {
      raise(types[2], e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError,
                      "out of memory (std::bad_alloc): a size, count or budget is larger than "
                      "this machine's memory allows");
    }
  });
  vtrack::apps::quiet_video_backend_logs();
  vtrack::bindings::bind_core(m);
  vtrack::bindings::bind_tracks(m);
  vtrack::bindings::bind_image(m);
  vtrack::bindings::bind_color(m);
  vtrack::bindings::bind_models(m);
  vtrack::bindings::bind_filters(m);
  vtrack::bindings::bind_glmb(m);
  vtrack::bindings::bind_multi_bernoulli(m);
  vtrack::bindings::bind_reclustering_sir(m);
  vtrack::bindings::bind_apps(m);
  vtrack::bindings::bind_detections(m);
  vtrack::bindings::bind_vehicles(m);
  vtrack::bindings::bind_smc(m);
  vtrack::bindings::bind_follow(m);
}
