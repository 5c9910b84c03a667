#include "params.hpp"

#include <climits>
#include <cmath>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/limits.hpp"

namespace vtrack::bindings {
namespace {

bool is_integer(const py::handle& v) {
  return !py::isinstance<py::bool_>(v) && PyIndex_Check(v.ptr());
}

// Numbers as Python and NumPy give them (int, float, np.int64, np.float32...), never bool or str.
bool is_number(const py::handle& v) {
  return !py::isinstance<py::bool_>(v) && !py::isinstance<py::str>(v) && PyNumber_Check(v.ptr()) &&
         PyObject_HasAttrString(v.ptr(), "__float__");
}

[[noreturn]] void wrong_type(const std::string& name, const char* expected, const py::handle& v) {
  throw py::type_error(name + " must be " + expected + ", got " + type_name(v));
}

}  // namespace

core::ParameterValue parameter_from_python(const std::string& name, core::ParameterKind kind,
                                           std::size_t size, const py::handle& v) {
  using core::ParameterKind;
  switch (kind) {
    case ParameterKind::flag:
      if (!py::isinstance<py::bool_>(v)) wrong_type(name, "a bool", v);
      return v.cast<bool>();
    case ParameterKind::integer: {
      if (!is_integer(v)) wrong_type(name, "an int", v);
      const py::int_ i = py::reinterpret_borrow<py::object>(v);
      if (i < py::int_(INT_MIN) || i > py::int_(INT_MAX)) {
        throw py::value_error(name + " must be an int in [" + std::to_string(INT_MIN) + ", " +
                              std::to_string(INT_MAX) + "], got " + py::str(i).cast<std::string>());
      }
      return std::int64_t{i.cast<long long>()};
    }
    case ParameterKind::seed: {
      if (!is_integer(v)) wrong_type(name, "an int", v);
      const py::int_ i = py::reinterpret_borrow<py::object>(v);
      if (i < py::int_(0) || i > py::int_(std::numeric_limits<std::uint64_t>::max())) {
        throw py::value_error(name + " must be an int in [0, 2**64 - 1], got " +
                              py::str(i).cast<std::string>());
      }
      return std::uint64_t{i.cast<unsigned long long>()};
    }
    case ParameterKind::real:
      if (!is_number(v)) wrong_type(name, "a number", v);
      return py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>();
    case ParameterKind::choice:
      if (!py::isinstance<py::str>(v)) wrong_type(name, "a str", v);
      return v.cast<std::string>();
    case ParameterKind::reals: {
      if (py::isinstance<py::str>(v) || !PySequence_Check(v.ptr())) {
        wrong_type(name, "a sequence of numbers", v);
      }
      const auto seq = py::reinterpret_borrow<py::sequence>(v);
      if (seq.size() != size) {
        throw py::value_error(name + " must hold " + std::to_string(size) + " numbers, got " +
                              std::to_string(seq.size()));
      }
      std::vector<double> out;
      for (const auto& item : seq) {
        if (!is_number(item)) wrong_type(name, "a sequence of numbers", item);
        out.push_back(py::float_(py::reinterpret_borrow<py::object>(item)).cast<double>());
      }
      return out;
    }
  }
  throw py::type_error(name + ": unsupported parameter kind");
}

py::object parameter_to_python(const core::ParameterValue& value) {
  struct Visitor {
    py::object operator()(bool b) const { return py::bool_(b); }
    py::object operator()(std::int64_t i) const { return py::int_(i); }
    py::object operator()(std::uint64_t u) const { return py::int_(u); }
    py::object operator()(double d) const { return py::float_(d); }
    py::object operator()(const std::string& s) const { return py::str(s); }
    py::object operator()(const std::vector<double>& r) const {
      py::tuple t(r.size());
      for (std::size_t i = 0; i < r.size(); ++i) t[i] = py::float_(r[i]);
      return std::move(t);
    }
  };
  return std::visit(Visitor{}, value);
}

void throw_unknown_keyword(const std::string& name, const std::string& what,
                           const std::vector<std::string>& names) {
  throw py::type_error(core::unknown_parameter_message(name, what, names));
}

std::string keyword_text(const py::dict& params) {
  std::string out;
  for (const auto& item : params) {
    out += (out.empty() ? "" : ", ") + py::str(item.first).cast<std::string>() + "=" +
           py::repr(item.second).cast<std::string>();
  }
  return out;
}

std::pair<int, int> image_size_from(const py::handle& obj) {
  if (py::isinstance<py::str>(obj) || !PySequence_Check(obj.ptr()) || py::len(obj) != 2) {
    throw py::type_error("image_size must be a (width, height) pair of ints, got " +
                         py::repr(obj).cast<std::string>());
  }
  const auto s = py::reinterpret_borrow<py::sequence>(obj);
  int size[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    const char* name = i == 0 ? "image_size[0] (width)" : "image_size[1] (height)";
    if (!is_integer(s[i])) wrong_type(name, "an int", s[i]);
    const py::int_ v = py::reinterpret_borrow<py::object>(s[i]);
    // OpenCV's image dimensions are ints; a side beyond 2^20 px is no camera's.
    if (v < py::int_(1) || v > py::int_(core::kMaxImageSide)) {
      throw py::value_error(std::string(name) + " must be in [1, " +
                            std::to_string(core::kMaxImageSide) + "], got " +
                            py::str(v).cast<std::string>());
    }
    size[i] = v.cast<int>();
  }
  return {size[0], size[1]};
}

}  // namespace vtrack::bindings
