#include "vtrack/apps/video_writer.hpp"

#include <algorithm>
#include <cctype>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"

namespace vtrack::apps {
namespace fs = std::filesystem;
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

bool is_video_output(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".avi" || ext == ".mp4" || ext == ".mkv";
}

void rename_or_throw(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(from, ignored);  // the temporary file is not left behind
    throw IoError("cannot rename '" + from.string() + "' to '" + to.string() + "': " + ec.message());
  }
}

AtomicVideoWriter::AtomicVideoWriter(const std::string& path, double fps, cv::Size size)
    : path_(path), partial_(partial_path(path, /*keep_extension=*/true)), registered_(partial_.string()) {
  const int fourcc = lower_extension(path) == ".mp4" ? cv::VideoWriter::fourcc('m', 'p', '4', 'v')
                                                     : cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
  if (!writer_.open(partial_.string(), cv::CAP_FFMPEG, fourcc, fps, size, true)) {
    throw IoError("cannot open video '" + partial_.string() + "' for writing");
  }
}

AtomicVideoWriter::~AtomicVideoWriter() {
  if (!committed_) {
    writer_.release();
    std::error_code ec;
    fs::remove(partial_, ec);
  }
}

void AtomicVideoWriter::write(const cv::Mat& frame) {
  if (frame.channels() == 1) {
    cv::cvtColor(frame, bgr_, cv::COLOR_GRAY2BGR);
    writer_.write(bgr_);
  } else {
    writer_.write(frame);
  }
}

void AtomicVideoWriter::commit() {
  writer_.release();
  rename_or_throw(partial_, path_);
  registered_.release();
  committed_ = true;
}

}  // namespace vtrack::apps
