// vtrack._core: the compiled half of the Python package. Conversion and validation only.
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
  vtrack::apps::quiet_video_backend_logs();
  vtrack::bindings::bind_core(m);
  vtrack::bindings::bind_tracks(m);
  vtrack::bindings::bind_image(m);
  vtrack::bindings::bind_color(m);
  vtrack::bindings::bind_models(m);
  vtrack::bindings::bind_filters(m);
  vtrack::bindings::bind_glmb(m);
  vtrack::bindings::bind_multi_bernoulli(m);
  vtrack::bindings::bind_apps(m);
  vtrack::bindings::bind_detections(m);
  vtrack::bindings::bind_vehicles(m);
  vtrack::bindings::bind_smc(m);
}
