#include "vtrack/apps/parameters.hpp"

#include <algorithm>
#include <filesystem>
#include <type_traits>

#include <opencv2/core.hpp>

#include "vtrack/core/errors.hpp"

namespace vtrack::apps {
namespace {

using filters::MultiBernoulliParams;
using image::KdeBackgroundParams;

// A parameter: how to read it from and write it to its struct.
template <typename Params>
struct Field {
  std::variant<double Params::*, int Params::*, bool Params::*> member{};
  // Fields of a nested struct (the likelihood's) go through an accessor instead.
  double* (*nested_double)(Params&) = nullptr;
  int* (*nested_int)(Params&) = nullptr;
};

const std::vector<std::pair<std::string, Field<MultiBernoulliParams>>>& mb_fields() {
  using P = MultiBernoulliParams;
  using F = Field<P>;
  static const std::vector<std::pair<std::string, F>> table = {
      {"delta_f", F{{}, [](P& p) { return &p.likelihood.delta_f; }}},
      {"delta_b", F{{}, [](P& p) { return &p.likelihood.delta_b; }}},
      {"closing_size", F{{}, nullptr, [](P& p) { return &p.likelihood.closing_size; }}},
      {"survival_probability", F{&P::survival_probability}},
      {"sigma_x", F{&P::sigma_x}},
      {"sigma_y", F{&P::sigma_y}},
      {"sigma_w", F{&P::sigma_w}},
      {"sigma_h", F{&P::sigma_h}},
      {"width_mean", F{&P::width_mean}},
      {"width_std", F{&P::width_std}},
      {"height_mean", F{&P::height_mean}},
      {"height_std", F{&P::height_std}},
      {"width_min", F{&P::width_min}},
      {"width_max", F{&P::width_max}},
      {"height_min", F{&P::height_min}},
      {"height_max", F{&P::height_max}},
      {"quarter_birth", F{&P::quarter_birth}},
      {"birth_probability", F{&P::birth_probability}},
      {"birth_particles", F{&P::birth_particles}},
      {"cover_existence", F{&P::cover_existence}},
      {"established_age", F{&P::established_age}},
      {"adaptive_birth", F{&P::adaptive_birth}},
      {"adaptive_birth_probability", F{&P::adaptive_birth_probability}},
      {"adaptive_birth_log_likelihood", F{&P::adaptive_birth_log_likelihood}},
      {"adaptive_birth_stride", F{&P::adaptive_birth_stride}},
      {"adaptive_birth_max", F{&P::adaptive_birth_max}},
      {"min_particles", F{&P::min_particles}},
      {"max_particles", F{&P::max_particles}},
      {"prune_threshold", F{&P::prune_threshold}},
      {"merge_overlap", F{&P::merge_overlap}},
      {"estimate_threshold", F{&P::estimate_threshold}},
      {"max_existence", F{&P::max_existence}},
      {"confirm_frames", F{&P::confirm_frames}},
      {"lost_memory", F{&P::lost_memory}},
      {"relabel_overlap", F{&P::relabel_overlap}},
      {"velocity_smoothing", F{&P::velocity_smoothing}},
      {"box_scale_w", F{&P::box_scale_w}},
      {"box_scale_h", F{&P::box_scale_h}},
      {"box_offset_x", F{&P::box_offset_x}},
      {"box_offset_y", F{&P::box_offset_y}},
  };
  return table;
}

const std::vector<std::pair<std::string, Field<KdeBackgroundParams>>>& kde_fields() {
  using P = KdeBackgroundParams;
  using F = Field<P>;
  static const std::vector<std::pair<std::string, F>> table = {
      {"n_samples", F{&P::n_samples}}, {"period", F{&P::period}},   {"sigma_r", F{&P::sigma_r}},
      {"sigma_g", F{&P::sigma_g}},     {"sigma_I", F{&P::sigma_I}}, {"closing", F{&P::closing}},
      {"threads", F{&P::threads}},    {"update_threshold", F{&P::update_threshold}},
      {"update_max_skips", F{&P::update_max_skips}},
      {"illumination_compensation", F{&P::illumination_compensation}},
  };
  return table;
}

const std::vector<std::pair<std::string, Field<BoxTrackerParams>>>& box_fields() {
  using P = BoxTrackerParams;
  using F = Field<P>;
  static const std::vector<std::pair<std::string, F>> table = {
      {"detection_probability", F{&P::detection_probability}},
      {"survival_probability", F{&P::survival_probability}},
      {"outside_survival_probability", F{&P::outside_survival_probability}},
      {"outside_detection_probability", F{&P::outside_detection_probability}},
      {"clutter_rate", F{&P::clutter_rate}},
      {"sigma_accel", F{&P::sigma_accel}},
      {"sigma_size", F{&P::sigma_size}},
      {"detection_sd_centre", F{&P::detection_sd_centre}},
      {"detection_sd_size", F{&P::detection_sd_size}},
      {"birth_sd_centre", F{&P::birth_sd_centre}},
      {"birth_sd_velocity", F{&P::birth_sd_velocity}},
      {"birth_sd_size", F{&P::birth_sd_size}},
      {"birth_rate", F{&P::birth_rate}},
      {"birth_max_existence", F{&P::birth_max_existence}},
      {"hypothesis_budget", F{&P::hypothesis_budget}},
      {"gate_threshold", F{&P::gate_threshold}},
      {"min_confidence", F{&P::min_confidence}},
      {"min_age", F{&P::min_age}},
      {"gibbs_ranking", F{&P::gibbs_ranking}},
      {"seed", F{&P::seed}},
  };
  return table;
}

const std::vector<std::pair<std::string, Field<HogParams>>>& hog_fields() {
  using P = HogParams;
  using F = Field<P>;
  static const std::vector<std::pair<std::string, F>> table = {
      {"hit_threshold", F{&P::hit_threshold}}, {"win_stride", F{&P::win_stride}},
      {"padding", F{&P::padding}},             {"scale", F{&P::scale}},
      {"upscale", F{&P::upscale}},             {"group_threshold", F{&P::group_threshold}},
      {"min_score", F{&P::min_score}},         {"person_fraction", F{&P::person_fraction}},
  };
  return table;
}

template <typename Params>
ParameterValue read(const Field<Params>& f, Params& p) {
  if (f.nested_double) return *f.nested_double(p);
  if (f.nested_int) return static_cast<long long>(*f.nested_int(p));
  return std::visit(
      [&](auto member) -> ParameterValue {
        using T = std::remove_reference_t<decltype(p.*member)>;
        if constexpr (std::is_same_v<T, int>) return static_cast<long long>(p.*member);
        else return p.*member;
      },
      f.member);
}

[[noreturn]] void wrong_kind(const std::string& name, const char* expected) {
  throw InvalidArgument("parameter " + name + " must be " + expected);
}

double as_real(const std::string& name, const ParameterValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<long long>(&v)) return static_cast<double>(*i);
  wrong_kind(name, "a number");
}

int as_integer(const std::string& name, const ParameterValue& v) {
  if (const auto* i = std::get_if<long long>(&v)) {
    if (*i < -2147483647LL || *i > 2147483647LL) wrong_kind(name, "an integer within int range");
    return static_cast<int>(*i);
  }
  wrong_kind(name, "an integer");
}

template <typename Params>
void write(const std::string& name, const Field<Params>& f, Params& p, const ParameterValue& v) {
  if (f.nested_double) {
    *f.nested_double(p) = as_real(name, v);
    return;
  }
  if (f.nested_int) {
    *f.nested_int(p) = as_integer(name, v);
    return;
  }
  std::visit(
      [&](auto member) {
        using T = std::remove_reference_t<decltype(p.*member)>;
        if constexpr (std::is_same_v<T, bool>) {
          const auto* b = std::get_if<bool>(&v);
          if (!b) wrong_kind(name, "true or false");
          p.*member = *b;
        } else if constexpr (std::is_same_v<T, int>) {
          p.*member = as_integer(name, v);
        } else {
          p.*member = as_real(name, v);
        }
      },
      f.member);
}

template <typename Params, typename Table>
std::vector<std::pair<std::string, ParameterValue>> values_of(Params params, const Table& table) {
  std::vector<std::pair<std::string, ParameterValue>> out;
  for (const auto& [name, field] : table) out.emplace_back(name, read(field, params));
  return out;
}

template <typename Params, typename Table>
bool set_in(Params& params, const Table& table, const std::string& name, const ParameterValue& v) {
  for (const auto& [field_name, field] : table) {
    if (field_name == name) {
      write(name, field, params, v);
      return true;
    }
  }
  return false;
}

ParameterValue node_value(const std::string& name, const cv::FileNode& node) {
  if (node.isInt()) return static_cast<long long>(static_cast<int>(node));
  if (node.isReal()) return static_cast<double>(node);
  if (node.isString()) {
    const std::string s = static_cast<std::string>(node);
    if (s == "true") return true;
    if (s == "false") return false;
    return s;
  }
  throw InvalidArgument("parameter " + name + " must be a number, true/false or a name");
}

}  // namespace

ConfigFile read_config_file(const std::string& path, const std::vector<std::string>& sections,
                            bool allow_seed) {
  if (!std::filesystem::is_regular_file(path)) throw IoError("no such config file: '" + path + "'");
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw IoError("cannot parse config file '" + path + "': " + e.err);
  }
  if (!fs.isOpened()) throw IoError("cannot parse config file '" + path + "' (YAML or JSON)");
  std::string expected = allow_seed ? "seed" : "";
  for (const auto& s : sections) expected += (expected.empty() ? "" : ", ") + s;
  ConfigFile config;
  config.path = path;
  for (const auto& node : fs.root()) {
    const std::string key = node.name();
    if (allow_seed && key == "seed") {
      if (!node.isInt() || static_cast<int>(node) < 0) {
        throw InvalidArgument("config seed must be a non-negative integer");
      }
      config.seed = static_cast<std::uint64_t>(static_cast<int>(node));
      continue;
    }
    if (std::find(sections.begin(), sections.end(), key) == sections.end()) {
      throw InvalidArgument("unknown config section '" + key + "' (expected " + expected + ")");
    }
    if (node.empty()) continue;
    if (!node.isMap()) throw InvalidArgument("config section '" + key + "' must be a map");
    std::vector<std::pair<std::string, ParameterValue>> values;
    for (const auto& item : node) values.emplace_back(item.name(), node_value(item.name(), item));
    config.sections.emplace_back(key, std::move(values));
  }
  return config;
}

void apply_config_section(
    const ConfigFile& config, const std::string& section,
    const std::function<bool(const std::string&, const ParameterValue&)>& set) {
  for (const auto& [name, values] : config.sections) {
    if (name != section) continue;
    for (const auto& [parameter, value] : values) {
      if (!set(parameter, value)) {
        throw InvalidArgument("unknown parameter '" + parameter + "' in config section '" +
                              section + "'");
      }
    }
  }
}

std::vector<std::pair<std::string, ParameterValue>> parameter_values(
    const MultiBernoulliParams& params) {
  auto out = values_of(params, mb_fields());
  out.emplace_back("resampling", std::string(core::to_string(params.resampling)));
  return out;
}

std::vector<std::pair<std::string, ParameterValue>> parameter_values(
    const KdeBackgroundParams& params) {
  return values_of(params, kde_fields());
}

bool set_parameter(MultiBernoulliParams& params, const std::string& name,
                   const ParameterValue& value) {
  if (name == "resampling") {
    const auto* s = std::get_if<std::string>(&value);
    if (!s) wrong_kind(name, "a scheme name");
    params.resampling = core::parse_resampling_scheme(*s);
    return true;
  }
  return set_in(params, mb_fields(), name, value);
}

bool set_parameter(KdeBackgroundParams& params, const std::string& name,
                   const ParameterValue& value) {
  return set_in(params, kde_fields(), name, value);
}

std::vector<std::pair<std::string, ParameterValue>> parameter_values(
    const BoxTrackerParams& params) {
  return values_of(params, box_fields());
}

std::vector<std::pair<std::string, ParameterValue>> parameter_values(const HogParams& params) {
  return values_of(params, hog_fields());
}

bool set_parameter(BoxTrackerParams& params, const std::string& name, const ParameterValue& value) {
  return set_in(params, box_fields(), name, value);
}

bool set_parameter(HogParams& params, const std::string& name, const ParameterValue& value) {
  return set_in(params, hog_fields(), name, value);
}

}  // namespace vtrack::apps
