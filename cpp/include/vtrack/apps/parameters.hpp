#pragma once
// Parameters by name, for configuration files (`vtrack track --config params.yml`) and Python
// keyword arguments: one table per parameter struct, so the CLI, config files and Python accept
// exactly the same names.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "vtrack/apps/hog_detector.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/filters/multi_bernoulli.hpp"
#include "vtrack/image/kde_background.hpp"

namespace vtrack::apps {

using ParameterValue = std::variant<bool, long long, double, std::string>;

// Every parameter of the struct with its current value, in a fixed order.
std::vector<std::pair<std::string, ParameterValue>> parameter_values(
    const filters::MultiBernoulliParams& params);
std::vector<std::pair<std::string, ParameterValue>> parameter_values(
    const image::KdeBackgroundParams& params);
std::vector<std::pair<std::string, ParameterValue>> parameter_values(
    const BoxTrackerParams& params);
std::vector<std::pair<std::string, ParameterValue>> parameter_values(const HogParams& params);

// Sets one parameter. A real parameter takes a real or an integer, an integer parameter an
// integer, a flag a bool, a name a string. Returns false for a name the struct does not have;
// InvalidArgument naming the parameter for a value of the wrong kind. Ranges are checked by the
// struct's validate().
bool set_parameter(filters::MultiBernoulliParams& params, const std::string& name,
                   const ParameterValue& value);
bool set_parameter(image::KdeBackgroundParams& params, const std::string& name,
                   const ParameterValue& value);
bool set_parameter(BoxTrackerParams& params, const std::string& name, const ParameterValue& value);
bool set_parameter(HogParams& params, const std::string& name, const ParameterValue& value);

// A configuration file (YAML or JSON, read with OpenCV's FileStorage): a map of sections, each a
// map of parameter names to values, plus an optional top-level `seed`.
struct ConfigFile {
  std::string path;
  std::optional<std::uint64_t> seed;
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, ParameterValue>>>> sections;
};

// Parses `path`. IoError for a missing or unparsable file; InvalidArgument for a top-level key
// other than `sections` (and `seed` when allow_seed), a section that is not a map, a value that
// is not a number, true/false or a name, or a seed that is not a non-negative integer.
ConfigFile read_config_file(const std::string& path, const std::vector<std::string>& sections,
                            bool allow_seed);

// Sets every parameter of section `section` (if present) with `set` (a set_parameter overload);
// InvalidArgument naming an unknown parameter and the section.
void apply_config_section(
    const ConfigFile& config, const std::string& section,
    const std::function<bool(const std::string&, const ParameterValue&)>& set);

template <typename Params>
void apply_config_section(const ConfigFile& config, const std::string& section, Params& params) {
  apply_config_section(config, section, [&](const std::string& name, const ParameterValue& v) {
    return set_parameter(params, name, v);
  });
}

}  // namespace vtrack::apps
