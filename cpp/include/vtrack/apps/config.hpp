#pragma once
// Configuration files: YAML or JSON (yaml-cpp reads both), a map of sections, each a map of
// parameter names to values, plus an optional top-level `seed`:
//
//   seed: 7
//   background: {n_samples: 10, bandwidth: [0.03, 0.03, 0.06]}
//   tracker: {delta_f: 0.1, resampling: residual}
//
// The reader knows nothing of parameters: it returns each section's (name, value) pairs, and the
// pipeline sets them through the components' parameter tables (core/parameters.hpp), exactly as
// it sets `--set name=value` and Python keywords.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "vtrack/core/parameters.hpp"

namespace vtrack::apps {

using ParameterValues = std::vector<std::pair<std::string, core::ParameterValue>>;

struct Config {
  std::string path;  // where it was read from ("" for a config built in memory)
  std::optional<std::uint64_t> seed;
  std::vector<std::pair<std::string, ParameterValues>> sections;

  // The values of `section` (empty when absent).
  const ParameterValues& section(const std::string& name) const;
};

// Limits that keep a hostile file from costing more than a config file should: its size, and the
// nesting of flow collections ([ ] and { }) checked before the YAML parser sees it.
constexpr std::size_t kMaxConfigBytes = 1 << 20;
constexpr int kMaxConfigNesting = 16;

// Reads `path`. IoError for a missing, unreadable, oversized or not regular file, for a YAML/JSON
// syntax error ("path: line L, column C: ...") and for more than one YAML document;
// InvalidArgument "path: line L: ..." for a document that is not a map of sections, a section
// that is not a map, a name that is not a plain scalar, a duplicated name, a seed that is not an
// integer in [0, 2^64 - 1], or a value that is not a number, true/false, a name or a list of
// numbers. Sections are kept in file order; which sections a pipeline accepts is its business.
Config read_config(const std::string& path);

}  // namespace vtrack::apps
