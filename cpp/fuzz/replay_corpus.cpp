// Replays the fuzz corpus (fuzz/corpus/, the seeds and every input a fuzzer found) through the
// C++ readers it targets (ctest: fuzz_corpus_replay), so that a build with sanitizers checks
// them too -- the atheris harnesses drive the Python module. Per corpus folder:
//   detections/  apps::read_detections, then apps::track_detections on what it accepts
//   config/      apps::read_config, then apps::apply_config to both methods' parameters
//   video/       the first byte picks .avi/.mp4/.mkv or an image folder (fuzz/fuzz_video.py);
//                apps::probe_video on the rest
// A file may be rejected with vtrack::InvalidArgument or vtrack::IoError; any other exception
// fails the replay (exit 1), and a sanitizer report aborts it.
//
//   vtrack_replay_corpus fuzz/corpus
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "vtrack/apps/config.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/pipeline.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/core/errors.hpp"

namespace fs = std::filesystem;
namespace apps = vtrack::apps;

namespace {

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void replay_detections(const fs::path& file) {
  const auto detections = apps::read_detections(file.string());
  if (!detections.empty() && detections.size() <= 64) {
    apps::BoxTrackerParams params;
    params.hypothesis_budget = 20;
    apps::track_detections(detections, 0, 0, params);
  }
}

void replay_config(const fs::path& file) {
  const apps::Config config = apps::read_config(file.string());
  for (const char* method : {"mb", "glmb"}) {
    apps::PipelineParams params;
    params.method = method;
    try {
      apps::apply_config(params, config);
    } catch (const vtrack::InvalidArgument&) {
      // a section or name the other method reads
    }
  }
}

// fuzz/fuzz_video.py's layout: byte 0 % 6 picks the container or image type; for images, bit 3
// adds a truncated copy and bit 4 a whole copy to the folder.
void replay_video(const fs::path& file, const fs::path& scratch) {
  const std::string data = read_bytes(file);
  if (data.empty()) return;
  static const char* const kinds[] = {".avi", ".mp4", ".mkv", "png", "jpg", "bmp"};
  const auto first = static_cast<unsigned char>(data[0]);
  const std::string kind = kinds[first % 6];
  const std::string body = data.substr(1);
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  fs::path input = scratch / ("video" + kind);
  if (kind[0] == '.') {
    write_bytes(input, body);
  } else {
    input = scratch / "frames";
    fs::create_directories(input);
    write_bytes(input / ("000." + kind), body);
    if (first & 8) write_bytes(input / ("001." + kind), body.substr(0, body.size() / 2));
    if (first & 16) write_bytes(input / ("002." + kind), body);
  }
  apps::probe_video(input.string());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: vtrack_replay_corpus CORPUS_FOLDER (fuzz/corpus)\n";
    return 2;
  }
  apps::quiet_video_backend_logs();
  const fs::path root = argv[1];
  const fs::path scratch = fs::temp_directory_path() / ("vtrack-replay-" + std::to_string(::getpid()));
  const std::vector<std::pair<std::string, std::function<void(const fs::path&)>>> readers = {
      {"detections", replay_detections},
      {"config", replay_config},
      {"video", [&](const fs::path& f) { replay_video(f, scratch); }},
  };
  int files = 0, rejected = 0, failures = 0;
  for (const auto& [folder, replay] : readers) {
    std::vector<fs::path> inputs;
    for (const auto& entry : fs::directory_iterator(root / folder)) inputs.push_back(entry.path());
    std::sort(inputs.begin(), inputs.end());
    for (const auto& file : inputs) {
      ++files;
      try {
        replay(file);
      } catch (const vtrack::InvalidArgument&) {
        ++rejected;
      } catch (const vtrack::IoError&) {
        ++rejected;
      } catch (const std::exception& e) {
        ++failures;
        std::cerr << file.string() << ": unexpected exception: " << e.what() << "\n";
      }
    }
  }
  std::error_code ec;
  fs::remove_all(scratch, ec);
  std::cout << "replayed " << files << " corpus files: " << files - rejected - failures
            << " accepted, " << rejected << " rejected with a vtrack error, " << failures
            << " failures\n";
  return failures == 0 && files > 0 ? 0 : 1;
}
