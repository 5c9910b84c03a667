#include "vtrack/core/parameters.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/text_file.hpp"

namespace vtrack::core {
namespace {

[[noreturn]] void wrong_kind(const std::string& name, const std::string& expected,
                             const ParameterValue& v) {
  throw InvalidType("parameter " + name + " must be " + expected + ", got " + to_text(v));
}

// Whole-text integer: signed when it fits, unsigned above INT64_MAX; false for anything else
// (including integers beyond 2^64 - 1, which become reals).
bool parse_integer(const std::string& text, ParameterValue& out) {
  if (text.empty()) return false;
  const bool negative = text[0] == '-';
  const std::size_t digits_from = (text[0] == '-' || text[0] == '+') ? 1 : 0;
  if (digits_from == text.size()) return false;
  for (std::size_t i = digits_from; i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '9') return false;
  }
  errno = 0;
  char* end = nullptr;
  if (negative) {
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (errno == ERANGE) return false;
    out = std::int64_t{v};
    return true;
  }
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (errno == ERANGE) return false;
  if (v <= static_cast<unsigned long long>(std::numeric_limits<std::int64_t>::max())) {
    out = static_cast<std::int64_t>(v);
  } else {
    out = static_cast<std::uint64_t>(v);
  }
  return true;
}

// Whole-text real (strtod's forms, including inf and nan).
bool parse_real(const std::string& text, double& out) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string describe(ParameterKind kind, std::size_t size, const std::vector<std::string>& choices) {
  switch (kind) {
    case ParameterKind::flag: return "true or false";
    case ParameterKind::integer: return "an integer";
    case ParameterKind::seed: return "an integer in [0, 2^64 - 1]";
    case ParameterKind::real: return "a number";
    case ParameterKind::reals: return std::to_string(size) + " numbers";
    case ParameterKind::choice: {
      std::string s = "one of";
      for (std::size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : " ") + choices[i];
      return s;
    }
  }
  return "?";
}

std::string to_text(const ParameterValue& value) {
  struct Visitor {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(std::uint64_t u) const { return std::to_string(u); }
    std::string operator()(double d) const { return value_text(d); }
    std::string operator()(const std::string& s) const { return "'" + s + "'"; }
    std::string operator()(const std::vector<double>& v) const {
      std::string s;
      for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + value_text(v[i]);
      return s;
    }
  };
  return std::visit(Visitor{}, value);
}

ParameterValue parse_parameter_text(const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  ParameterValue integer;
  if (parse_integer(text, integer)) return integer;
  double real = 0;
  if (parse_real(text, real)) return real;
  if (text.find(',') != std::string::npos) {
    std::vector<double> reals;
    for (const std::string& field : comma_fields(text)) {
      double v = 0;
      if (!parse_real(field, v)) return text;
      reals.push_back(v);
    }
    return reals;
  }
  return text;
}

std::pair<std::string, ParameterValue> parse_setting(const std::string& setting) {
  const std::size_t eq = setting.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InvalidArgument("--set expects name=value, got '" + setting + "'");
  }
  return {setting.substr(0, eq), parse_parameter_text(setting.substr(eq + 1))};
}

double real_value(const std::string& name, const ParameterValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  if (const auto* u = std::get_if<std::uint64_t>(&v)) return static_cast<double>(*u);
  wrong_kind(name, "a number", v);
}

int int_value(const std::string& name, const ParameterValue& v) {
  constexpr auto lo = std::numeric_limits<int>::min(), hi = std::numeric_limits<int>::max();
  if (const auto* i = std::get_if<std::int64_t>(&v)) {
    if (*i >= lo && *i <= hi) return static_cast<int>(*i);
  } else if (!std::holds_alternative<std::uint64_t>(v)) {
    wrong_kind(name, "an integer", v);
  }
  throw InvalidArgument("parameter " + name + " must be an integer in [" + std::to_string(lo) +
                        ", " + std::to_string(hi) + "], got " + to_text(v));
}

std::uint64_t seed_value(const std::string& name, const ParameterValue& v) {
  if (const auto* u = std::get_if<std::uint64_t>(&v)) return *u;
  if (const auto* i = std::get_if<std::int64_t>(&v); i && *i >= 0) return static_cast<std::uint64_t>(*i);
  wrong_kind(name, describe(ParameterKind::seed), v);
}

bool flag_value(const std::string& name, const ParameterValue& v) {
  if (const auto* b = std::get_if<bool>(&v)) return *b;
  wrong_kind(name, "true or false", v);
}

std::string name_value(const std::string& name, const ParameterValue& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  wrong_kind(name, "a name", v);
}

std::vector<double> reals_value(const std::string& name, const ParameterValue& v, std::size_t size) {
  const auto* r = std::get_if<std::vector<double>>(&v);
  if (!r || r->size() != size) wrong_kind(name, describe(ParameterKind::reals, size), v);
  return *r;
}

std::string closest_name(const std::string& name, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const auto& candidate : names) {
    const std::size_t d = edit_distance(name, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

std::string unknown_parameter_message(const std::string& name, const std::string& what,
                                      const std::vector<std::string>& names) {
  std::string message = "unknown " + (what.empty() ? std::string() : what + " ") + "parameter '" +
                        name + "'";
  const std::string suggestion = closest_name(name, names);
  if (!suggestion.empty()) message += " (did you mean '" + suggestion + "'?)";
  return message;
}

void throw_unknown_parameter(const std::string& name, const std::string& what,
                             const std::vector<std::string>& names) {
  throw InvalidType(unknown_parameter_message(name, what, names));
}

void throw_bad_choice(const std::string& name, const std::string& text,
                      const std::vector<std::string>& choices) {
  throw InvalidArgument("parameter " + name + " must be " +
                        describe(ParameterKind::choice, 0, choices) + ", got '" + text + "'");
}

}  // namespace vtrack::core
