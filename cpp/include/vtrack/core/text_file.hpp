#pragma once
// Small text files a user names (config files, camera files, vehicle model files), read whole
// with the checks such a file needs before a parser sees it.
#include <cstddef>
#include <string>
#include <vector>

namespace vtrack::core {

// Reads `path` whole. IoError, naming `what` (e.g. "config file") and the path, when it is
// missing, not a regular file (a folder, /dev/zero, a FIFO: reading one would never end or mean
// nothing), larger than `max_bytes`, unreadable, or (max_flow_nesting >= 0) when its YAML/JSON
// flow collections, [ ] and { } outside quotes, nest deeper than max_flow_nesting: recursive
// parsers would otherwise exhaust the stack on a hostile file. Also when it is not UTF-8 text,
// and for YAML (max_flow_nesting >= 0) when it holds a control character or a stray ','
// (stray_comma_line), naming the line.
std::string read_text_file(const std::string& path, const std::string& what,
                           std::size_t max_bytes, int max_flow_nesting = -1);

// The offset of the first byte that does not start a valid UTF-8 sequence (overlong forms,
// surrogates and code points beyond U+10FFFF are invalid), or std::string::npos.
std::size_t invalid_utf8_offset(const std::string& text);

// The first line (1-based; 0 for none) with a ',' outside [ ] and { }, quotes and comments:
// yaml-cpp never returns from parsing some of them (",", "- 1\n,", "&a,"), and parameter files
// need none (lists are written [a, b]).
int stray_comma_line(const std::string& text);

// The deepest nesting of [ ] and { } outside quoted strings.
int flow_nesting(const std::string& text);

// Comma-separated text rows (detection files, vehicle observation files).

// `s` without leading and trailing spaces, tabs and carriage returns (files written by other
// tools sometimes pad their fields).
std::string trimmed(const std::string& s);

// The fields of `line` between commas, untrimmed; one field for a line without a comma.
std::vector<std::string> comma_fields(const std::string& line);

// The whole (trimmed) field as a number. InvalidArgument "<where><name> is not a number: '...'"
// otherwise. strtod's "nan" and "inf" are accepted: callers check finiteness with the field's
// own rule and name.
double number_field(const std::string& field, const std::string& name, const std::string& where);

}  // namespace vtrack::core
