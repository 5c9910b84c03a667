#include "batch_handoff.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "vtrack/version.hpp"

extern char** environ;

namespace vtrack::cli {
namespace {

std::vector<char*> c_argv(std::vector<std::string>& args) {
  std::vector<char*> out;
  for (auto& a : args) out.push_back(a.data());
  out.push_back(nullptr);
  return out;
}

// Interpreters to try, best first (see the header).
std::vector<std::string> candidates() {
  if (const char* chosen = std::getenv("VTRACK_PYTHON"); chosen != nullptr && *chosen != '\0') {
    return {chosen};
  }
  std::vector<std::string> out;
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const char* name : {"python3", "python"}) {
      const auto path = self.parent_path() / name;
      if (std::filesystem::exists(path, ec)) out.push_back(path.string());
    }
  }
#ifdef VTRACK_BUILD_PYTHON_EXECUTABLE
  out.push_back(VTRACK_BUILD_PYTHON_EXECUTABLE);
#endif
  out.push_back("python3");  // searched on PATH
  return out;
}

// Runs `python -c` to check that it imports vtrack.batch of our version; "" when it does, else
// why not.
std::string probe(const std::string& python) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return std::string("cannot create a pipe: ") + std::strerror(errno);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<std::string> args = {
      python, "-c", "import sys, vtrack, vtrack.batch; sys.stdout.write(vtrack.__version__)"};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, python.c_str(), &actions, nullptr, c_argv(args).data(),
                                   environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fds[1]);
  if (spawned != 0) {
    close(pipe_fds[0]);
    return std::string("cannot run it (") + std::strerror(spawned) + ")";
  }
  std::string version;
  char buffer[256];
  ssize_t n = 0;
  while ((n = read(pipe_fds[0], buffer, sizeof buffer)) > 0) version.append(buffer, n);
  close(pipe_fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) == 127) return "cannot run it";
  if (WEXITSTATUS(status) != 0) return "cannot import vtrack.batch";
  if (version != kVersion) return "has vtrack " + version + ", this is vtrack " + kVersion;
  return "";
}

}  // namespace

std::string exec_python_batch(const std::vector<std::string>& args) {
  std::string tried;
  for (const auto& python : candidates()) {
    const std::string refused = probe(python);
    if (!refused.empty()) {
      tried += "\n  " + python + ": " + refused;
      continue;
    }
    std::vector<std::string> command = {python, "-m", "vtrack.batch"};
    command.insert(command.end(), args.begin(), args.end());
    setenv("VTRACK_PROG", "vtrack batch", 1);
    execvp(python.c_str(), c_argv(command).data());
    return "cannot run " + python + ": " + std::strerror(errno);
  }
  return "vtrack batch runs in Python (vtrack.batch, on Dask) and found no Python with vtrack " +
         std::string(kVersion) + " (pip install 'vtrack[batch]', or set VTRACK_PYTHON to its "
         "interpreter); tried:" + tried;
}

}  // namespace vtrack::cli
