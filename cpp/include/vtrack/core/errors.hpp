#pragma once
// The two error types of vtrack. Every public function reports bad input by throwing one of
// these with a message that names the argument and its value; nothing in the library asserts on
// user input, aborts or prints.
#include <stdexcept>
#include <string>

namespace vtrack {

// A value, shape or type the caller passed is not acceptable (Python: ValueError subclass).
class InvalidArgument : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file or video could not be read or written (Python: OSError subclass).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vtrack
