// vtrack._core: the compiled half of the Python package. Conversion and validation only.
#include "common.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/version.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "Compiled core of vtrack (use the public API in `vtrack`).";
  m.attr("__version__") = vtrack::kVersion;
  // C++ errors become Python exceptions that are also the built-in ones users expect to catch.
  pybind11::register_exception<vtrack::InvalidArgument>(m, "InvalidArgument", PyExc_ValueError);
  pybind11::register_exception<vtrack::IoError>(m, "IoError", PyExc_OSError);
  vtrack::bindings::bind_core(m);
  vtrack::bindings::bind_image(m);
  vtrack::bindings::bind_filters(m);
  vtrack::bindings::bind_apps(m);
}
