#pragma once
// Parameters by name, for configuration files (`vtrack track --config params.yml`) and Python
// keyword arguments: one table per parameter struct, so the CLI, config files and Python accept
// exactly the same names.
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "vtrack/filters/multi_bernoulli.hpp"
#include "vtrack/image/kde_background.hpp"

namespace vtrack::apps {

using ParameterValue = std::variant<bool, long long, double, std::string>;

// Every parameter of the struct with its current value, in a fixed order.
std::vector<std::pair<std::string, ParameterValue>> parameter_values(
    const filters::MultiBernoulliParams& params);
std::vector<std::pair<std::string, ParameterValue>> parameter_values(
    const image::KdeBackgroundParams& params);

// Sets one parameter. A real parameter takes a real or an integer, an integer parameter an
// integer, a flag a bool, a name a string. Returns false for a name the struct does not have;
// InvalidArgument naming the parameter for a value of the wrong kind. Ranges are checked by the
// struct's validate().
bool set_parameter(filters::MultiBernoulliParams& params, const std::string& name,
                   const ParameterValue& value);
bool set_parameter(image::KdeBackgroundParams& params, const std::string& name,
                   const ParameterValue& value);

}  // namespace vtrack::apps
