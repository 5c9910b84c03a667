// The `vtrack` command-line program: parses arguments and calls the library, nothing more.
// Errors print `vtrack: error: ...` on stderr and exit with status 2 (usage) or 1 (failure).
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "vtrack/apps/video_source.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/version.hpp"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// A mistake in the command line itself (exit status 2, like argparse).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Command {
  const char* name;
  const char* summary;
  const char* usage;
  std::function<int(const std::vector<std::string>&)> run;
};

bool wants_help(const std::vector<std::string>& args) {
  for (const auto& a : args) {
    if (a == "-h" || a == "--help") return true;
  }
  return false;
}

int run_info(const std::vector<std::string>& args) {
  if (args.size() != 1) throw UsageError("info takes exactly one VIDEO_OR_IMAGE_FOLDER");
  if (!args[0].empty() && args[0][0] == '-') throw UsageError("unknown option '" + args[0] + "'");
  const vtrack::apps::VideoInfo info = vtrack::apps::probe_video(args[0]);
  std::cout << "path: " << args[0] << "\n"
            << "kind: " << (info.is_image_folder ? "image folder" : "video") << "\n"
            << "frames: " << info.frame_count << "\n"
            << "size: " << info.width << "x" << info.height << "\n";
  if (info.fps > 0) {
    std::cout << "fps: " << info.fps << "\n";
  } else {
    std::cout << "fps: unknown\n";
  }
  return 0;
}

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"info", "print frame count, frame size and frame rate of a video or image folder",
       "vtrack info VIDEO_OR_IMAGE_FOLDER", run_info},
  };
  return table;
}

void print_help() {
  std::cout << "usage: vtrack [--help] [--version] COMMAND [ARGS]\n\n"
               "Bayesian visual multi-object tracking.\n\ncommands:\n";
  for (const auto& c : commands()) {
    std::cout << "  " << c.name << std::string(10 - std::string(c.name).size(), ' ') << c.summary
              << "\n";
  }
  std::cout << "\nRun 'vtrack COMMAND --help' for a command's options.\n";
}

}  // namespace

int main(int argc, char** argv) {
  vtrack::apps::quiet_video_backend_logs();  // our error messages say what went wrong
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty()) throw UsageError("no command given (try 'vtrack --help')");
    const std::string first = args.front();
    if (first == "-h" || first == "--help") {
      print_help();
      return 0;
    }
    if (first == "--version") {
      std::cout << "vtrack " << vtrack::kVersion << "\n";
      return 0;
    }
    for (const auto& command : commands()) {
      if (first != command.name) continue;
      std::vector<std::string> rest(args.begin() + 1, args.end());
      if (wants_help(rest)) {
        std::cout << "usage: " << command.usage << "\n\n" << command.summary << "\n";
        return 0;
      }
      return command.run(rest);
    }
    throw UsageError("unknown command '" + first + "' (try 'vtrack --help')");
  } catch (const UsageError& e) {
    std::cerr << "vtrack: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "vtrack: error: " << e.what() << "\n";
    return kExitFailure;
  }
}
