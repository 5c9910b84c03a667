#pragma once
// Parameters by name. Every tunable component has a plain params struct with the papers'
// defaults, a `validate(params)` and, beside them in the same layer, a ParameterTable that maps
// names to fields. Config files, `--set name=value`, Python keyword arguments and Python's
// `default_params()` all go through the table, so a parameter has one name and one check
// everywhere; ranges are checked by the struct's validate().
//
//   const core::ParameterTable<KdeBackgroundParams>& KdeBackgroundParams::table() {
//     static const auto t = core::ParameterTable<KdeBackgroundParams>()
//         .add("n_samples", &KdeBackgroundParams::n_samples)
//         .add("bandwidth", &KdeBackgroundParams::bandwidth);
//     return t;
//   }
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace vtrack::core {

// A parameter's value as a config file, the command line or Python gives it: a flag, an integer
// (signed when it fits in 64 bits, unsigned above INT64_MAX so that every 64-bit seed can be
// written), a real, a name, or a list of reals (e.g. the KDE's bandwidth).
using ParameterValue =
    std::variant<bool, std::int64_t, std::uint64_t, double, std::string, std::vector<double>>;

// What a parameter takes: a flag, an int (within C int range), a 64-bit unsigned seed, a real,
// one of a fixed set of names, or a fixed number of reals.
enum class ParameterKind { flag, integer, seed, real, choice, reals };

// Human-readable kind ("a number", "true or false", ...), for error messages.
std::string describe(ParameterKind kind, std::size_t size = 0,
                     const std::vector<std::string>& choices = {});

// The value as text: 0.03, 7, true, systematic, 0.03,0.03,0.06 (the form --set accepts).
std::string to_text(const ParameterValue& value);

// Text as `--set name=value` gives it: true/false, an integer, a real, a comma-separated list
// of reals, otherwise a name.
ParameterValue parse_parameter_text(const std::string& text);

// `name=value` as `--set` gives it: the name and parse_parameter_text(value). InvalidArgument
// "--set expects name=value, got '<setting>'" without an '=' or a name.
std::pair<std::string, ParameterValue> parse_setting(const std::string& setting);

// Conversions of a value to a field's type. InvalidArgument "parameter <name> must be <kind>,
// got <value>" when the value is of another kind (an integer is accepted as a real; a real is
// never silently truncated to an integer; integers are range-checked before narrowing).
double real_value(const std::string& name, const ParameterValue& v);
int int_value(const std::string& name, const ParameterValue& v);
std::uint64_t seed_value(const std::string& name, const ParameterValue& v);
bool flag_value(const std::string& name, const ParameterValue& v);
std::string name_value(const std::string& name, const ParameterValue& v);
std::vector<double> reals_value(const std::string& name, const ParameterValue& v, std::size_t size);

// The name among `names` closest to `name` by edit distance, or "" when none is close enough to
// be a likely typo.
std::string closest_name(const std::string& name, const std::vector<std::string>& names);

// "unknown <what> parameter 'nme' (did you mean 'name'?)", or without the suggestion.
std::string unknown_parameter_message(const std::string& name, const std::string& what,
                                      const std::vector<std::string>& names);
// InvalidArgument with unknown_parameter_message.
[[noreturn]] void throw_unknown_parameter(const std::string& name, const std::string& what,
                                          const std::vector<std::string>& names);
// InvalidArgument "parameter <name> must be one of a, b, c, got 'text'".
[[noreturn]] void throw_bad_choice(const std::string& name, const std::string& text,
                                   const std::vector<std::string>& choices);

namespace detail {
template <class T>
struct FieldCodec;
template <>
struct FieldCodec<double> {
  static constexpr ParameterKind kind = ParameterKind::real;
  static ParameterValue encode(double v) { return v; }
  static double decode(const std::string& n, const ParameterValue& v) { return real_value(n, v); }
};
template <>
struct FieldCodec<int> {
  static constexpr ParameterKind kind = ParameterKind::integer;
  static ParameterValue encode(int v) { return std::int64_t{v}; }
  static int decode(const std::string& n, const ParameterValue& v) { return int_value(n, v); }
};
template <>
struct FieldCodec<bool> {
  static constexpr ParameterKind kind = ParameterKind::flag;
  static ParameterValue encode(bool v) { return v; }
  static bool decode(const std::string& n, const ParameterValue& v) { return flag_value(n, v); }
};
template <>
struct FieldCodec<std::uint64_t> {
  static constexpr ParameterKind kind = ParameterKind::seed;
  static ParameterValue encode(std::uint64_t v) { return v; }
  static std::uint64_t decode(const std::string& n, const ParameterValue& v) {
    return seed_value(n, v);
  }
};
template <std::size_t N>
struct FieldCodec<std::array<double, N>> {
  static constexpr ParameterKind kind = ParameterKind::reals;
  static ParameterValue encode(const std::array<double, N>& v) {
    return std::vector<double>(v.begin(), v.end());
  }
  static std::array<double, N> decode(const std::string& n, const ParameterValue& v) {
    const std::vector<double> r = reals_value(n, v, N);
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = r[i];
    return out;
  }
};
template <class T>
struct ArraySize {
  static constexpr std::size_t value = 0;
};
template <std::size_t N>
struct ArraySize<std::array<double, N>> {
  static constexpr std::size_t value = N;
};
}  // namespace detail

template <class Params>
class ParameterTable {
 public:
  struct Entry {
    std::string name;
    ParameterKind kind = ParameterKind::real;
    std::size_t size = 0;              // reals: how many
    std::vector<std::string> choices;  // choice: the accepted names
    std::function<ParameterValue(const Params&)> get;
    std::function<void(Params&, const ParameterValue&)> set;
  };

  // A field of the struct (double, int, bool, std::uint64_t seed, std::array<double, N>).
  template <class T>
  ParameterTable add(std::string name, T Params::*member) && {
    push<T>(std::move(name), [member](auto& p) -> auto& { return p.*member; });
    return std::move(*this);
  }
  // Every parameter of a nested params struct (one with its own table()), under its own names.
  template <class Inner>
  ParameterTable include(Inner Params::*outer) && {
    for (const auto& inner : Inner::table().entries()) {
      Entry e;
      e.name = inner.name;
      e.kind = inner.kind;
      e.size = inner.size;
      e.choices = inner.choices;
      e.get = [outer, get = inner.get](const Params& p) { return get(p.*outer); };
      e.set = [outer, set = inner.set](Params& p, const ParameterValue& v) { set(p.*outer, v); };
      entries_.push_back(std::move(e));
    }
    return std::move(*this);
  }
  // An enum field given by name: `names` lists each accepted name with its value.
  template <class Enum>
  ParameterTable add_choice(std::string name, Enum Params::*member,
                              std::vector<std::pair<std::string, Enum>> names) && {
    Entry e;
    e.name = std::move(name);
    e.kind = ParameterKind::choice;
    for (const auto& [text, value] : names) e.choices.push_back(text);
    e.get = [member, names](const Params& p) -> ParameterValue {
      for (const auto& [text, value] : names) {
        if (p.*member == value) return text;
      }
      return std::string("?");
    };
    e.set = [member, names, key = e.name, choices = e.choices](Params& p, const ParameterValue& v) {
      const std::string text = name_value(key, v);
      for (const auto& [candidate, value] : names) {
        if (candidate == text) {
          p.*member = value;
          return;
        }
      }
      throw_bad_choice(key, text, choices);
    };
    entries_.push_back(std::move(e));
    return std::move(*this);
  }

  const std::vector<Entry>& entries() const { return entries_; }
  const Entry* find(const std::string& name) const {
    for (const auto& e : entries_) {
      if (e.name == name) return &e;
    }
    return nullptr;
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.name);
    return out;
  }
  // Sets `name` to `value`: false when the table has no such name; InvalidArgument naming the
  // parameter for a value of the wrong kind (ranges are validate()'s job).
  bool set(Params& params, const std::string& name, const ParameterValue& value) const {
    const Entry* e = find(name);
    if (!e) return false;
    e->set(params, value);
    return true;
  }
  // Every parameter with its value in `params`, in table order.
  std::vector<std::pair<std::string, ParameterValue>> values(const Params& params) const {
    std::vector<std::pair<std::string, ParameterValue>> out;
    for (const auto& e : entries_) out.emplace_back(e.name, e.get(params));
    return out;
  }

 private:
  template <class T, class Access>
  void push(std::string name, Access access) {
    using Codec = detail::FieldCodec<T>;
    Entry e;
    e.name = std::move(name);
    e.kind = Codec::kind;
    e.size = detail::ArraySize<T>::value;
    e.get = [access](const Params& p) { return Codec::encode(access(p)); };
    e.set = [access, key = e.name](Params& p, const ParameterValue& v) {
      access(p) = Codec::decode(key, v);
    };
    entries_.push_back(std::move(e));
  }
  std::vector<Entry> entries_;
};

// Sets every (name, value) of `values` on `params` through its table; InvalidArgument naming an
// unknown parameter (with the closest name) and `what` (e.g. "tracker").
template <class Params>
void set_parameters(Params& params,
                    const std::vector<std::pair<std::string, ParameterValue>>& values,
                    const std::string& what) {
  const auto& table = Params::table();
  for (const auto& [name, value] : values) {
    if (!table.set(params, name, value)) {
      throw_unknown_parameter(name, what, table.names());
    }
  }
}

}  // namespace vtrack::core
