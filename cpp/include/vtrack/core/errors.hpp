#pragma once
// The two error types of vtrack. Every public function reports bad input by throwing one of
// these with a message that names the argument and its value; nothing in the library asserts on
// user input, aborts or prints.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace vtrack {

// A value, shape or type the caller passed is not acceptable (Python: ValueError subclass).
class InvalidArgument : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A parameter name the component does not have, or a value of the wrong kind for a parameter
// (a name where a number is due): a mistake in how the call is written rather than in a value
// (Python: TypeError subclass; the CLI: a usage error, exit status 2).
class InvalidType : public InvalidArgument {
 public:
  using InvalidArgument::InvalidArgument;
};

// A file or video could not be read or written (Python: OSError subclass).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A number as error messages show it: the shortest form that keeps its value readable (%g-like:
// 0.001, 2e-07, 1e+06, nan, inf), unlike std::to_string's fixed six decimals.
inline std::string value_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Throws InvalidArgument "<name> must be <what>, got <value>" unless `ok`: the one-line parameter
// check of the params validators.
inline void require(bool ok, const char* name, double value, const char* what) {
  if (!ok) throw InvalidArgument(std::string(name) + " must be " + what + ", got " + value_text(value));
}
// The same for an integer parameter, whose value is shown exactly (2147483647, not 2.14748e+09).
inline void require(bool ok, const char* name, int value, const char* what) {
  if (!ok) throw InvalidArgument(std::string(name) + " must be " + what + ", got " + std::to_string(value));
}

// A parameter that must be a positive finite number.
inline void require_positive(const char* name, double value) {
  require(std::isfinite(value) && value > 0.0, name, value, "a positive finite number");
}

}  // namespace vtrack
