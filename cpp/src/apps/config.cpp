#include "vtrack/apps/config.hpp"

#include <set>
#include <vector>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/text_file.hpp"

namespace vtrack::apps {
namespace {

std::string at(const std::string& path, const YAML::Node& node) {
  return path + ": line " + std::to_string(node.Mark().line + 1) + ": ";
}

// A map key: a name, never a list or map (whose Scalar() would silently be "").
std::string key_of(const std::string& path, const YAML::Node& key) {
  if (!key.IsScalar()) {
    throw InvalidArgument(at(path, key) + "a section or parameter name must be a plain name, "
                          "not a list or map");
  }
  return key.Scalar();
}

core::ParameterValue scalar_value(const std::string& where, const std::string& name,
                                  const YAML::Node& node) {
  if (node.IsNull()) throw InvalidArgument(where + "parameter " + name + " has no value");
  if (node.IsSequence()) {
    std::vector<double> reals;
    for (const auto& item : node) {
      const core::ParameterValue v = item.IsScalar() && item.Tag() != "!"
                                         ? core::parse_parameter_text(item.Scalar())
                                         : core::ParameterValue(std::string());
      if (std::holds_alternative<std::string>(v) || std::holds_alternative<bool>(v) ||
          std::holds_alternative<std::vector<double>>(v)) {
        throw InvalidArgument(where + "parameter " + name + " must be a list of numbers");
      }
      reals.push_back(core::real_value(name, v));
    }
    return reals;
  }
  if (!node.IsScalar()) {
    throw InvalidArgument(where + "parameter " + name +
                          " must be a number, true/false, a name or a list of numbers");
  }
  // A quoted scalar ("0.1", 'abc') is a name, never a number: YAML and JSON both say so.
  if (node.Tag() == "!") return node.Scalar();
  const std::string& text = node.Scalar();
  if (text == "True" || text == "TRUE") return true;
  if (text == "False" || text == "FALSE") return false;
  const core::ParameterValue v = core::parse_parameter_text(text);
  if (std::holds_alternative<std::vector<double>>(v)) return text;  // "1,2" unquoted: a name
  return v;
}

std::uint64_t seed_from(const std::string& where, const YAML::Node& node) {
  const core::ParameterValue v =
      node.IsScalar() && node.Tag() != "!" ? core::parse_parameter_text(node.Scalar())
                                           : core::ParameterValue(std::string("?"));
  try {
    return core::seed_value("seed", v);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(where + e.what());
  }
}

YAML::Node load(const std::string& path) {
  const std::string text =
      core::read_text_file(path, "config file", kMaxConfigBytes, kMaxConfigNesting);
  try {
    const std::vector<YAML::Node> documents = YAML::LoadAll(text);
    if (documents.size() > 1) {
      throw IoError("cannot parse config file '" + path + "': it holds " +
                    std::to_string(documents.size()) + " YAML documents (---), one is read");
    }
    return documents.empty() ? YAML::Node() : documents.front();
  } catch (const YAML::DeepRecursion& e) {
    throw IoError("cannot parse config file '" + path + "': line " +
                  std::to_string(e.mark.line + 1) + ": nested too deeply");
  } catch (const YAML::Exception& e) {
    throw IoError("cannot parse config file '" + path + "': line " +
                  std::to_string(e.mark.line + 1) + ", column " +
                  std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
}

}  // namespace

const ParameterValues& Config::section(const std::string& name) const {
  static const ParameterValues none;
  for (const auto& [section_name, values] : sections) {
    if (section_name == name) return values;
  }
  return none;
}

Config read_config(const std::string& path) {
  const YAML::Node root = load(path);
  Config config;
  config.path = path;
  if (root.IsNull()) return config;  // an empty file sets nothing
  if (!root.IsMap()) {
    throw InvalidArgument(at(path, root) + "a config file must be a map of sections");
  }
  std::set<std::string> seen;
  for (const auto& item : root) {
    const std::string key = key_of(path, item.first);
    if (!seen.insert(key).second) {
      throw InvalidArgument(at(path, item.first) + "'" + key + "' appears twice");
    }
    if (key == "seed") {
      config.seed = seed_from(at(path, item.second), item.second);
      continue;
    }
    if (item.second.IsNull()) continue;  // "tracker:" with nothing under it
    if (!item.second.IsMap()) {
      throw InvalidArgument(at(path, item.second) + "section '" + key + "' must be a map");
    }
    ParameterValues values;
    std::set<std::string> names;
    for (const auto& parameter : item.second) {
      const std::string name = key_of(path, parameter.first);
      if (!names.insert(name).second) {
        throw InvalidArgument(at(path, parameter.first) + "parameter '" + name +
                              "' appears twice in section '" + key + "'");
      }
      values.emplace_back(name, scalar_value(at(path, parameter.second), name, parameter.second));
    }
    config.sections.emplace_back(key, std::move(values));
  }
  return config;
}

}  // namespace vtrack::apps
