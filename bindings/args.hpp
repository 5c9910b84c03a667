#pragma once
// Plain arguments of the public functions (counts, sizes, frame numbers, seeds, file paths)
// converted with the argument's name in every error: TypeError "k must be an int, got float",
// ValueError "k must be in [1, 100000], got 0", never pybind11's anonymous "incompatible function
// arguments" or a RuntimeError from a failed cast. And the scope that makes a long C++ call
// interruptible by Ctrl-C.
#include <chrono>
#include <cstdint>
#include <string>

#include "common.hpp"
#include "vtrack/core/interrupt.hpp"

namespace vtrack::bindings {

// An int in [lo, hi] (Python int or NumPy integer, not bool).
std::int64_t int_arg(const py::handle& value, const char* name, std::int64_t lo, std::int64_t hi);
// A real number (int or float, not bool or str); NaN allowed only when `allow_nan`.
double real_arg(const py::handle& value, const char* name, bool allow_nan = false);
// A str (as given, for names such as a method).
std::string str_arg(const py::handle& value, const char* name);
// A file-system path: str, bytes or os.PathLike; ValueError for an empty path or a NUL byte
// (the C library would silently cut the path there).
std::string path_arg(const py::handle& value, const char* name);

// MemoryError "cannot allocate <what>: more than this machine's memory allows" (naming the
// argument instead of a bare std::bad_alloc).
[[noreturn]] void throw_memory_error(const std::string& what);
// throw_memory_error(what) when `bytes` exceed the machine's physical memory: a request that large
// would otherwise be granted by overcommit and end with the process killed mid-way.
void check_allocation(double bytes, const std::string& what);

// For its lifetime, core::poll_interrupt() in the library's loops takes the GIL (at most every
// 50 ms) and runs Python's signal handlers: Ctrl-C raises KeyboardInterrupt out of the C++ call.
class PythonInterrupts {
 public:
  PythonInterrupts();

 private:
  core::InterruptScope scope_;
};

}  // namespace vtrack::bindings
