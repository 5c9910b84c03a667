#pragma once
// A video file that appears only when complete: frames go to "<stem>.partial<ext>" beside the
// target, commit() renames it to the target, and destruction without commit() removes it, so an
// error never leaves a half-written video (and never replaces an existing file).
#include <filesystem>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "vtrack/apps/temporary_files.hpp"

namespace vtrack::apps {

// True when `path` names a video we can write (extension .avi, .mp4 or .mkv, any case).
bool is_video_output(const std::string& path);

class AtomicVideoWriter {
 public:
  // .mp4: MPEG-4 part 2; .avi/.mkv: Motion-JPEG. IoError when the file cannot be opened.
  AtomicVideoWriter(const std::string& path, double fps, cv::Size size);
  ~AtomicVideoWriter();
  AtomicVideoWriter(const AtomicVideoWriter&) = delete;
  AtomicVideoWriter& operator=(const AtomicVideoWriter&) = delete;

  // An 8-bit BGR frame (or single-channel, written as grey) of the size given at construction.
  void write(const cv::Mat& frame);
  // Closes the file and moves it to its final name; IoError if that fails.
  void commit();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::filesystem::path partial_;
  TemporaryFile registered_;  // removed by a signal handler if the process is stopped mid-write
  cv::VideoWriter writer_;
  cv::Mat bgr_;
  bool committed_ = false;
};

// Renames `from` (a temporary file) to `to`; on failure removes `from` and throws IoError naming
// both.
void rename_or_throw(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace vtrack::apps
