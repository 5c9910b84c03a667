#pragma once
// `vtrack batch` (many videos at once on Dask) is Python: python/vtrack/batch.py. The executable
// stays a small C++ program and hands the subcommand to the Python interpreter vtrack is
// installed in.
#include <string>
#include <vector>

namespace vtrack::cli {

// Replaces this process with `PYTHON -m vtrack.batch ARGS...` (environment VTRACK_PROG set to
// "vtrack batch" for its messages), PYTHON being the first of these that imports vtrack.batch of
// this very version: $VTRACK_PYTHON (if set, the only one tried); python3 or python next to this
// executable (a virtual environment's or prefix's bin/); the interpreter the Python module was
// built with; python3 on PATH. Returns only when none qualifies or exec fails: the message says
// what was tried and why each was refused.
std::string exec_python_batch(const std::vector<std::string>& args);

}  // namespace vtrack::cli
