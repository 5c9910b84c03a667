#include "vtrack/apps/output_paths.hpp"

#include <filesystem>
#include <system_error>

#include <unistd.h>

#include "vtrack/core/errors.hpp"

namespace vtrack::apps {
namespace fs = std::filesystem;
namespace {

// The path with links, "." and ".." resolved as far as it exists (the rest appended as given).
fs::path resolved(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) return fs::path(path).lexically_normal();
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

bool same_path(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  return resolved(a) == resolved(b);
}

std::string quoted(const NamedPath& p) { return p.name + " '" + p.path + "'"; }

// The folder a file output is written into (or, for a folder output, its nearest existing
// ancestor), which must be a writable folder.
void check_writable(const NamedPath& out) {
  std::error_code ec;
  fs::path folder = resolved(out.path);
  if (!out.folder) folder = folder.parent_path();
  if (out.folder) {
    while (!folder.empty() && !fs::exists(folder, ec) && folder != folder.root_path()) {
      folder = folder.parent_path();
    }
  }
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, ec)) {
    throw IoError(quoted(out) + ": folder '" + folder.string() + "' does not exist");
  }
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    throw IoError(quoted(out) + ": folder '" + folder.string() + "' is not writable");
  }
}

}  // namespace

void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& out = outputs[i];
    if (out.path.empty()) throw InvalidArgument(out.name + " must not be empty");
    std::error_code ec;
    if (!out.folder && fs::is_directory(out.path, ec)) {
      throw InvalidArgument(quoted(out) + " is a folder, not a file");
    }
    if (out.folder && fs::exists(out.path, ec) && !fs::is_directory(out.path, ec)) {
      throw InvalidArgument(quoted(out) + " exists and is not a folder");
    }
    for (const NamedPath& in : inputs) {
      if (in.path.empty() || !fs::exists(in.path, ec)) continue;
      if (same_path(out.path, in.path)) {
        throw InvalidArgument(quoted(out) + " is the input " + in.name +
                              ": it would be overwritten (choose another output)");
      }
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (same_path(out.path, outputs[j].path)) {
        throw InvalidArgument(quoted(out) + " is also " + quoted(outputs[j]) +
                              ": each output needs its own path");
      }
    }
    check_writable(out);
  }
}

}  // namespace vtrack::apps
