#pragma once
// Keyword parameters <-> the name tables of apps/parameters.hpp, shared by the bindings of the
// parameter structs, so Python keywords, config files and `--set` accept the same names.
#include <algorithm>
#include <string>

#include "common.hpp"

namespace vtrack::bindings {

// Sets the keyword parameters `values` on `params` by name; TypeError "unknown <what> parameter
// '<name>'" for an unknown name, TypeError naming the parameter for a value of the wrong kind.
template <typename Params>
void set_from_kwargs(Params& params, const py::dict& values, const std::string& what) {
  const auto defaults = apps::parameter_values(params);
  for (const auto& item : values) {
    const std::string name = py::str(item.first).cast<std::string>();
    const auto it = std::find_if(defaults.begin(), defaults.end(),
                                 [&](const auto& d) { return d.first == name; });
    if (it == defaults.end()) throw py::type_error("unknown " + what + " parameter '" + name + "'");
    apps::set_parameter(params, name, parameter_from_python(name, item.second, it->second));
  }
}

// Every parameter of `params` as a dict of keyword arguments.
template <typename Params>
py::dict params_dict(const Params& params) {
  py::dict d;
  for (const auto& [name, value] : apps::parameter_values(params)) {
    d[name.c_str()] = std::visit([](const auto& v) { return py::cast(v); }, value);
  }
  return d;
}

}  // namespace vtrack::bindings
