#include "vtrack/core/text_file.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstdint>
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

std::size_t invalid_utf8_offset(const std::string& text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  std::size_t i = 0;
  while (i < n) {
    const unsigned char c = s[i];
    // The sequence length and the smallest code point it may encode (no overlong forms).
    int length = 0;
    std::uint32_t code = 0, least = 0;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      length = 2, code = c & 0x1Fu, least = 0x80;
    } else if ((c & 0xF0) == 0xE0) {
      length = 3, code = c & 0x0Fu, least = 0x800;
    } else if ((c & 0xF8) == 0xF0) {
      length = 4, code = c & 0x07u, least = 0x10000;
    } else {
      return i;
    }
    if (i + static_cast<std::size_t>(length) > n) return i;
    for (int k = 1; k < length; ++k) {
      if ((s[i + k] & 0xC0) != 0x80) return i;
      code = (code << 6) | (s[i + k] & 0x3Fu);
    }
    if (code < least || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return i;
    i += static_cast<std::size_t>(length);
  }
  return std::string::npos;
}

int stray_comma_line(const std::string& text) {
  int depth = 0, line = 1;
  char quote = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      continue;  // quoted scalars may span lines: `quote` stays
    }
    if (quote) {
      if (c == '\\' && quote == '"') ++i;
      else if (c == quote) quote = 0;
      continue;
    }
    if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\n' || text[i - 1] == '\t')) {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;  // a comment to the line's end
      continue;
    }
    if (c == ',' && depth == 0) return line;
    if (c == '"' || c == '\'') quote = c;
    else if (c == '[' || c == '{') ++depth;
    else if (c == ']' || c == '}') depth = std::max(0, depth - 1);
  }
  return 0;
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
  // YAML and JSON are Unicode text; a stray byte would otherwise reach the parser's messages and
  // Python's str() undecoded.
  if (const std::size_t bad = invalid_utf8_offset(text); bad != std::string::npos) {
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(bad), '\n');
    throw IoError("cannot read " + what + " '" + path + "': line " + std::to_string(line) +
                  " is not UTF-8 text");
  }
  if (max_flow_nesting >= 0) {
    // YAML admits no control characters but tab, CR and LF (yaml-cpp hung on "\0,").
    const auto control = std::find_if(text.begin(), text.end(), [](char c) {
      const auto u = static_cast<unsigned char>(c);
      return (u < 0x20 && c != '\t' && c != '\n' && c != '\r') || u == 0x7f;
    });
    if (control != text.end()) {
      throw IoError("cannot parse " + what + " '" + path + "': line " +
                    std::to_string(1 + std::count(text.begin(), control, '\n')) +
                    " holds a control character");
    }
    // yaml-cpp loops forever, allocating, on some ',' outside flow collections (",", "- 1\n,",
    // "&a,"). Parameters never need one there (lists are [a, b]), so every such ',' is refused
    // before the parser sees it; a comma inside a plain string value is the price.
    if (const int line = stray_comma_line(text)) {
      throw IoError("cannot parse " + what + " '" + path + "': line " + std::to_string(line) +
                    ": ',' outside [ ] or { }");
    }
  }
  if (max_flow_nesting >= 0 && flow_nesting(text) > max_flow_nesting) {
    throw IoError("cannot parse " + what + " '" + path + "': nested deeper than " +
                  std::to_string(max_flow_nesting) + " levels");
  }
  return text;
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> comma_fields(const std::string& line) {
  std::vector<std::string> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

double number_field(const std::string& field, const std::string& name, const std::string& where) {
  const std::string text = trimmed(field);
  char* end = nullptr;
  const double v = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) {
    throw InvalidArgument(where + name + " is not a number: '" + text + "'");
  }
  return v;
}

}  // namespace vtrack::core
