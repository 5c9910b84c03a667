#include "vtrack/core/text_file.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "vtrack/core/errors.hpp"

namespace vtrack::core {

int flow_nesting(const std::string& text) {
  int depth = 0, deepest = 0;
  char quote = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == '\\' && quote == '"') ++i;
      else if (c == quote) quote = 0;
      continue;
    }
    if (c == '"' || c == '\'') quote = c;
    else if (c == '[' || c == '{') deepest = std::max(deepest, ++depth);
    else if (c == ']' || c == '}') depth = std::max(0, depth - 1);
  }
  return deepest;
}

std::string read_text_file(const std::string& path, const std::string& what,
                           std::size_t max_bytes, int max_flow_nesting) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    throw IoError(fs::exists(path, error) ? what + " '" + path + "' is not a regular file"
                                          : "no such " + what + ": '" + path + "'");
  }
  const auto size = fs::file_size(path, error);
  if (error || size > max_bytes) {
    throw IoError(what + " '" + path + "' is larger than " + std::to_string(max_bytes) + " bytes");
  }
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (!in && !in.eof()) throw IoError("cannot read " + what + " '" + path + "'");
  std::string text = buffer.str();
  if (text.size() > max_bytes) {  // grew since file_size
    throw IoError(what + " '" + path + "' is larger than " + std::to_string(max_bytes) + " bytes");
  }
  if (max_flow_nesting >= 0 && flow_nesting(text) > max_flow_nesting) {
    throw IoError("cannot parse " + what + " '" + path + "': nested deeper than " +
                  std::to_string(max_flow_nesting) + " levels");
  }
  return text;
}

}  // namespace vtrack::core
