#pragma once
// Frames from a video file (anything OpenCV's videoio can open) or from a folder of images
// (sorted by file name), behind one interface.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

namespace vtrack::apps {

// Called by every frame-by-frame job (pipelines, background subtraction, detections) after each
// frame with (frames done, frames announced by the input or -1 if unknown). The one progress
// callback type of the CLI and Python.
using FrameProgress = std::function<void(long long done, long long total)>;

class VideoSource {
 public:
  // IoError when the path does not exist, cannot be opened, or holds no image files.
  explicit VideoSource(const std::string& path);

  // Reads the next frame (8-bit BGR) into `frame`; false once the input is exhausted.
  // IoError naming the 0-based frame index when a frame cannot be decoded: an unreadable image
  // file, an image of a different size, or a video that ends before the frame count in its header
  // (a corrupt or truncated file).
  bool read(cv::Mat& frame);

  const std::string& path() const { return path_; }
  bool is_image_folder() const { return !image_files_.empty(); }
  int width() const { return width_; }
  int height() const { return height_; }
  // Frames per second from the container; 0 when unknown (image folders).
  double fps() const { return fps_; }
  // Frame count announced by the container, or the number of image files; -1 when unknown.
  long long expected_frame_count() const { return expected_frames_; }
  // Frames read so far (the index of the next frame).
  long long frames_read() const { return frames_read_; }

 private:
  std::string path_;
  std::vector<std::string> image_files_;
  cv::VideoCapture capture_;
  cv::Mat first_frame_;  // decoded while opening to learn the size; handed out by the first read()
  int width_ = 0;
  int height_ = 0;
  double fps_ = 0.0;
  long long expected_frames_ = -1;
  long long frames_read_ = 0;
};

struct VideoInfo {
  long long frame_count = 0;  // exact: every frame is decoded
  int width = 0;
  int height = 0;
  double fps = 0.0;  // 0 when unknown
  bool is_image_folder = false;
};

// Silences what FFmpeg and OpenCV print to stderr on a damaged or unsupported file, because our
// exceptions already say it; called by the CLI and the Python module at start-up. Respects an
// OPENCV_FFMPEG_LOGLEVEL the user has set.
void quiet_video_backend_logs();

// Opens `path` and decodes it to the end; IoError on any of VideoSource's errors.
VideoInfo probe_video(const std::string& path);

}  // namespace vtrack::apps
