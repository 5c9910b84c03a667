#pragma once
// Keyword parameters <-> the components' parameter tables (core/parameters.hpp), shared by every
// binding: Python keywords take exactly the names config files and `--set` take, with the same
// range checks (the struct's validate()), and each component gets the same `default_params()` and
// `.params`.
#include <string>

#include "common.hpp"
#include "vtrack/core/parameters.hpp"

namespace vtrack::bindings {

// `value` as the kind of parameter `entry` takes: TypeError naming it for another Python type
// (bool for a number, str for a flag, ...), ValueError for an integer out of range.
core::ParameterValue parameter_from_python(const std::string& name, core::ParameterKind kind,
                                           std::size_t size, const py::handle& value);
// A parameter value as Python gives it back (bool, int, float, str, tuple of floats).
py::object parameter_to_python(const core::ParameterValue& value);

// TypeError "unknown <what> parameter 'x' (did you mean 'y'?)".
[[noreturn]] void throw_unknown_keyword(const std::string& name, const std::string& what,
                                        const std::vector<std::string>& names);

// Sets every keyword of `kwargs` on `params` through its table (TypeError for an unknown name or
// a value of the wrong type), then validates the whole struct (ValueError naming a parameter out
// of range).
template <class Params>
Params params_from_kwargs(const py::dict& kwargs, const std::string& what, Params params = {}) {
  const auto& table = Params::table();
  for (const auto& item : kwargs) {
    const std::string name = py::str(item.first).cast<std::string>();
    const auto* entry = table.find(name);
    if (!entry) throw_unknown_keyword(name, what, table.names());
    entry->set(params, parameter_from_python(name, entry->kind, entry->size, item.second));
  }
  validate(params);
  return params;
}

// Every parameter of `params` as a dict of keyword arguments.
template <class Params>
py::dict params_dict(const Params& params) {
  py::dict d;
  for (const auto& [name, value] : Params::table().values(params)) {
    d[name.c_str()] = parameter_to_python(value);
  }
  return d;
}

// The two members every parameterised class has: the classmethod default_params() and the
// property params (the values in force). `get` returns the object's params struct.
template <class Params, class Class, class Get>
void def_params(py::class_<Class>& cls, Get get) {
  cls.def_property_readonly(
         "params", [get](const Class& c) { return params_dict<Params>(get(c)); },
         "The parameters in force, as a dict of keyword arguments.")
      .def_static(
          "default_params", []() { return params_dict(Params{}); },
          "The default keyword parameters, as a dict (the papers' defaults; see the C++ header).");
}

// "name=value, ..." of a params dict, for __repr__.
std::string keyword_text(const py::dict& params);

// (width, height) as two positive ints: TypeError for another shape or type, ValueError for a
// value <= 0 or above the largest image OpenCV handles.
std::pair<int, int> image_size_from(const py::handle& obj);

}  // namespace vtrack::bindings
