#include "args.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include <unistd.h>

#include "params.hpp"

namespace vtrack::bindings {
namespace {

bool is_int(const py::handle& v) {
  return !py::isinstance<py::bool_>(v) && PyIndex_Check(v.ptr());
}

}  // namespace

std::int64_t int_arg(const py::handle& value, const char* name, std::int64_t lo, std::int64_t hi) {
  if (!is_int(value)) {
    throw py::type_error(std::string(name) + " must be an int, got " + type_name(value));
  }
  const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (i < py::int_(lo) || i > py::int_(hi)) {
    // No upper bound but the type's: "k must be >= 1", not "in [1, 9223372036854775807]".
    const std::string range = hi == std::numeric_limits<std::int64_t>::max()
                                  ? ">= " + std::to_string(lo)
                                  : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    throw py::value_error(std::string(name) + " must be " + range + ", got " +
                          py::str(i).cast<std::string>());
  }
  return i.cast<std::int64_t>();
}

double real_arg(const py::handle& value, const char* name, bool allow_nan) {
  if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) ||
      !PyNumber_Check(value.ptr()) || !PyObject_HasAttrString(value.ptr(), "__float__")) {
    throw py::type_error(std::string(name) + " must be a number, got " + type_name(value));
  }
  const double v = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  if (std::isnan(v) && !allow_nan) throw py::value_error(std::string(name) + " must not be NaN");
  return v;
}

std::string str_arg(const py::handle& value, const char* name) {
  if (!py::isinstance<py::str>(value)) {
    throw py::type_error(std::string(name) + " must be a str, got " + type_name(value));
  }
  return value.cast<std::string>();
}

std::string path_arg(const py::handle& value, const char* name) {
  const py::module_ os = py::module_::import("os");
  if (!py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value) &&
      !py::isinstance(value, os.attr("PathLike"))) {
    throw py::type_error(std::string(name) + " must be a path (str or os.PathLike), got " +
                         type_name(value));
  }
  // os.fsencode: the bytes the OS sees (surrogate-escaped names round-trip).
  const std::string path = os.attr("fsencode")(value).cast<py::bytes>();
  if (path.empty()) throw py::value_error(std::string(name) + " must not be empty");
  if (path.find('\0') != std::string::npos) {
    throw py::value_error(std::string(name) + " contains a NUL byte");
  }
  return path;
}

void throw_memory_error(const std::string& what) {
  PyErr_SetString(PyExc_MemoryError,
                  ("cannot allocate " + what + ": more than this machine's memory allows").c_str());
  throw py::error_already_set();
}

void check_allocation(double bytes, const std::string& what) {
  const double physical =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (physical > 0 && bytes > physical) {
    char text[96];
    std::snprintf(text, sizeof text, " (%.3g GiB; this machine has %.3g GiB)", bytes / 1073741824.0,
                  physical / 1073741824.0);
    throw_memory_error(what + text);
  }
}

PythonInterrupts::PythonInterrupts()
    : scope_([last = std::chrono::steady_clock::time_point{}]() mutable {
        const auto now = std::chrono::steady_clock::now();
        if (now - last < std::chrono::milliseconds(50)) return;
        last = now;
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      }) {}

}  // namespace vtrack::bindings
