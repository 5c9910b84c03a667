#include "vtrack/apps/background_subtraction.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>

#include <opencv2/imgcodecs.hpp>

#include "vtrack/apps/output_paths.hpp"
#include "vtrack/apps/temporary_files.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"

namespace vtrack::apps {
namespace fs = std::filesystem;
namespace {

// Where the y images go: a video written under a temporary name, or a folder of PNGs.
class YWriter {
 public:
  virtual ~YWriter() = default;
  virtual void write(const cv::Mat& y8, long long index) = 0;
  // Called once every frame is written.
  virtual void finish() = 0;
  // What the caller should know about the output after a failure.
  virtual std::string state_after_failure(long long frames_written) const = 0;
};

class FolderWriter : public YWriter {
 public:
  explicit FolderWriter(const fs::path& folder) : folder_(folder) {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (!fs::is_directory(folder_, ec)) {
      throw IoError("cannot create output folder '" + folder_.string() + "'");
    }
  }
  void write(const cv::Mat& y8, long long index) override {
    char name[32];
    std::snprintf(name, sizeof name, "%06lld", index);
    const fs::path target = folder_ / (std::string(name) + ".png");
    const fs::path partial = partial_path(target, /*keep_extension=*/true);
    TemporaryFile registered(partial.string());
    bool written = false;
    try {
      written = cv::imwrite(partial.string(), y8);
    } catch (const cv::Exception&) {
      written = false;
    }
    if (!written) {
      std::error_code ec;
      fs::remove(partial, ec);  // a half-written image is not left behind
      throw IoError("cannot write frame " + std::to_string(index) + " to '" + partial.string() + "'");
    }
    rename_or_throw(partial, target);
  }
  void finish() override {}
  std::string state_after_failure(long long frames_written) const override {
    return "the " + std::to_string(frames_written) + " images already written to '" +
           folder_.string() + "' (frames 0 to " + std::to_string(frames_written - 1) +
           ") are complete";
  }

 private:
  fs::path folder_;
};

class VideoFileWriter : public YWriter {
 public:
  VideoFileWriter(const std::string& output, double fps, cv::Size size)
      : video_(output, fps, size) {}
  void write(const cv::Mat& y8, long long) override { video_.write(y8); }
  void finish() override { video_.commit(); }
  std::string state_after_failure(long long) const override {
    return "no video written ('" + video_.path() + "' left untouched)";
  }

 private:
  AtomicVideoWriter video_;
};

}  // namespace

BgsResult run_background_subtraction(const std::string& input, const std::string& output,
                                     const image::KdeBackgroundParams& params,
                                     const FrameProgress& progress) {
  image::KdeBackground model(params);  // validates params before any file is touched
  const bool video = is_video_output(output);
  check_outputs({{"input", input}}, {{"output", output, !video}});
  VideoSource source(input);
  BgsResult result;
  result.video = video;
  std::unique_ptr<YWriter> writer;
  if (result.video) {
    const double fps = source.fps() > 0 ? source.fps() : 25.0;
    writer = std::make_unique<VideoFileWriter>(output, fps, cv::Size(source.width(), source.height()));
  } else {
    writer = std::make_unique<FolderWriter>(output);
  }
  cv::Mat frame, y, y8;
  while (true) {
    core::poll_interrupt();
    try {
      if (!source.read(frame)) break;
    } catch (const IoError& e) {
      throw IoError(std::string(e.what()) + "; " + writer->state_after_failure(result.frames));
    }
    model.apply(frame, y);
    y.convertTo(y8, CV_8U, 255.0);  // rounds to nearest, saturates
    writer->write(y8, result.frames);
    ++result.frames;
    if (progress) progress(result.frames, source.expected_frame_count());
  }
  writer->finish();
  return result;
}

}  // namespace vtrack::apps
