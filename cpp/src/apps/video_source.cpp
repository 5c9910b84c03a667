#include "vtrack/apps/video_source.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <cstdlib>

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"

namespace vtrack::apps {
namespace fs = std::filesystem;

namespace {

bool has_image_extension(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const char* const kExtensions[] = {".png", ".jpg",  ".jpeg", ".bmp", ".tif",
                                            ".tiff", ".ppm", ".pgm",  ".webp"};
  return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

cv::Mat read_image_file(const std::string& file, long long index) {
  cv::Mat image = cv::imread(file, cv::IMREAD_COLOR);
  if (image.empty()) {
    throw IoError("cannot decode frame " + std::to_string(index) + ": image file '" + file +
                  "' is unreadable or corrupt");
  }
  return image;
}

}  // namespace

VideoSource::VideoSource(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError("no such file or folder: '" + path + "'");
  if (fs::is_directory(path, ec)) {
    for (const auto& entry : fs::directory_iterator(path, ec)) {
      if (entry.is_regular_file() && has_image_extension(entry.path())) {
        image_files_.push_back(entry.path().string());
      }
    }
    if (image_files_.empty()) throw IoError("folder '" + path + "' holds no image files");
    std::sort(image_files_.begin(), image_files_.end());
    first_frame_ = read_image_file(image_files_.front(), 0);
    expected_frames_ = static_cast<long long>(image_files_.size());
  } else {
    // CAP_FFMPEG explicitly: the default backend list would also try the image-sequence reader,
    // which interprets a lone image or a text file in surprising ways.
    if (!capture_.open(path, cv::CAP_FFMPEG) || !capture_.isOpened()) {
      throw IoError("cannot open video '" + path + "' (missing codec, corrupt or not a video)");
    }
    if (!capture_.read(first_frame_) || first_frame_.empty()) {
      throw IoError("video '" + path + "' has no decodable frame (frame 0 is corrupt or missing)");
    }
    fps_ = capture_.get(cv::CAP_PROP_FPS);
    if (!(fps_ > 0.0)) fps_ = 0.0;
    const double announced = capture_.get(cv::CAP_PROP_FRAME_COUNT);
    expected_frames_ = announced > 0 ? static_cast<long long>(announced) : -1;
  }
  width_ = first_frame_.cols;
  height_ = first_frame_.rows;
}

bool VideoSource::read(cv::Mat& frame) {
  if (frames_read_ == 0 && !first_frame_.empty()) {
    frame = first_frame_;
    first_frame_.release();
    ++frames_read_;
    return true;
  }
  if (is_image_folder()) {
    if (frames_read_ >= static_cast<long long>(image_files_.size())) return false;
    const std::string& file = image_files_[static_cast<std::size_t>(frames_read_)];
    frame = read_image_file(file, frames_read_);
    if (frame.cols != width_ || frame.rows != height_) {
      throw IoError("cannot use frame " + std::to_string(frames_read_) + ": image '" + file +
                    "' is " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                    ", the folder's first image is " + std::to_string(width_) + "x" +
                    std::to_string(height_));
    }
  } else if (!capture_.read(frame) || frame.empty()) {
    if (expected_frames_ > 0 && frames_read_ < expected_frames_) {
      throw IoError("cannot decode frame " + std::to_string(frames_read_) + " of '" + path_ +
                    "': the video announces " + std::to_string(expected_frames_) +
                    " frames (corrupt or truncated file)");
    }
    return false;
  }
  ++frames_read_;
  return true;
}

void quiet_video_backend_logs() {
  setenv("OPENCV_FFMPEG_LOGLEVEL", "-8", /*overwrite=*/0);  // AV_LOG_QUIET
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
}

VideoInfo probe_video(const std::string& path) {
  VideoSource source(path);
  cv::Mat frame;
  while (source.read(frame)) core::poll_interrupt();
  VideoInfo info;
  info.frame_count = source.frames_read();
  info.width = source.width();
  info.height = source.height();
  info.fps = source.fps();
  info.is_image_folder = source.is_image_folder();
  return info;
}

}  // namespace vtrack::apps
