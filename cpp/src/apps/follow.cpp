#include "vtrack/apps/follow.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/output_paths.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"

namespace vtrack::apps {

namespace {

std::string box_text(const filters::Box& b) {
  char text[160];
  std::snprintf(text, sizeof text, "%g,%g,%g,%g", b.x, b.y, b.w, b.h);
  return text;
}

void check_method(const std::string& method) {
  if (method != "color" && method != "parts") {
    throw InvalidArgument("method must be one of color, parts, got '" + method + "'");
  }
}

// The box must be finite, of positive size and inside the image.
void check_init(const filters::Box& b, int cols, int rows) {
  if (!(std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.w) && std::isfinite(b.h))) {
    throw InvalidArgument("init box " + box_text(b) + " must be finite");
  }
  if (!(b.w > 0 && b.h > 0)) {
    throw InvalidArgument("init box " + box_text(b) + " must have positive width and height");
  }
  if (b.x < 0 || b.y < 0 || b.x + b.w > cols || b.y + b.h > rows) {
    throw InvalidArgument("init box " + box_text(b) + " leaves the " + std::to_string(cols) + "x" +
                          std::to_string(rows) + " image");
  }
}

void draw_box(cv::Mat& frame, const filters::Box& b, const cv::Scalar& color, int thickness) {
  cv::rectangle(frame, cv::Point2d(b.x, b.y), cv::Point2d(b.x + b.w, b.y + b.h), color, thickness);
}

// One tracker of either kind behind init/update and the drawing of its estimate.
struct Follower {
  std::optional<filters::ColorParticleFilter> color;
  std::optional<filters::PartParticleFilter> parts;

  explicit Follower(const FollowParams& p) {
    if (p.method == "color") color.emplace(p.color); else parts.emplace(p.parts);
  }
  void init(const cv::Mat& frame, const filters::Box& b) {
    if (color) color->init(frame, b); else parts->init(frame, b);
  }
  bool update(const cv::Mat& frame) { return color ? color->update(frame) : parts->update(frame); }
  filters::Box box() const { return color ? color->box() : parts->box(); }
  void draw(cv::Mat& frame, bool ok) const {
    if (parts) {
      for (int p = 0; p < parts->part_count(); ++p) {
        draw_box(frame, parts->part_box(p),
                 parts->occluded(p) ? cv::Scalar(0, 0, 255) : cv::Scalar(255, 200, 0), 1);
      }
    }
    draw_box(frame, box(), ok ? cv::Scalar(0, 255, 0) : cv::Scalar(0, 0, 255), 2);
  }
};

}  // namespace

void set_follow_parameter(FollowParams& params, const std::string& name,
                          const core::ParameterValue& value) {
  check_method(params.method);
  if (params.method == "color") {
    core::set_parameters(params.color, {{name, value}}, "color tracker");
  } else {
    core::set_parameters(params.parts, {{name, value}}, "parts tracker");
  }
}

void apply_follow_config(FollowParams& params, const Config& config) {
  check_method(params.method);
  for (const auto& [section, values] : config.sections) {
    if (section != "tracker") {
      throw InvalidArgument("config file '" + config.path + "': follow reads only the section "
                            "tracker, got '" + section + "'");
    }
    for (const auto& [name, value] : values) set_follow_parameter(params, name, value);
  }
  if (config.seed) set_follow_parameter(params, "seed", *config.seed);
}

ParameterValues follow_parameter_values(const FollowParams& params) {
  check_method(params.method);
  return params.method == "color" ? filters::ColorParticleParams::table().values(params.color)
                                  : filters::PartParticleParams::table().values(params.parts);
}

void validate(const FollowParams& params) {
  check_method(params.method);
  if (params.method == "color") filters::validate(params.color); else filters::validate(params.parts);
}

std::vector<FollowRow> follow_video(const std::string& path, const filters::Box& init,
                                    const FollowParams& params, long long first, long long last,
                                    const std::string& render, const FrameProgress& progress) {
  validate(params);
  if (first < 1) throw InvalidArgument("first must be >= 1 (frames count from 1), got " +
                                       std::to_string(first));
  if (last != 0 && last < first) {
    throw InvalidArgument("last (" + std::to_string(last) + ") must be >= first (" +
                          std::to_string(first) + ")");
  }
  if (!render.empty()) check_outputs({{"video", path}}, {{"render", render}});
  VideoSource video(path);
  check_init(init, video.width(), video.height());
  cv::Mat frame;
  for (long long k = 1; k < first; ++k) {  // skip to the init frame
    if (!video.read(frame)) break;
    core::poll_interrupt();
  }
  if (!video.read(frame)) {
    throw InvalidArgument("first frame " + std::to_string(first) + " is past the end of '" + path +
                          "' (" + std::to_string(video.frames_read()) + " frames)");
  }
  Follower tracker(params);
  tracker.init(frame, init);
  std::unique_ptr<AtomicVideoWriter> writer;
  if (!render.empty()) {
    writer = std::make_unique<AtomicVideoWriter>(render, video.fps() > 0 ? video.fps() : 25.0,
                                                 frame.size());
  }
  std::vector<FollowRow> rows{{first, init.x, init.y, init.w, init.h}};
  const long long total = last > 0 ? last - first + 1 : (video.expected_frame_count() > 0
                                                             ? video.expected_frame_count() - first + 1
                                                             : -1);
  auto emit = [&](bool ok) {
    if (writer) {
      cv::Mat canvas = frame.clone();
      tracker.draw(canvas, ok);
      writer->write(canvas);
    }
    if (progress) progress(static_cast<long long>(rows.size()), total);
    core::poll_interrupt();
  };
  emit(true);
  for (long long k = first + 1; last == 0 || k <= last; ++k) {
    if (!video.read(frame)) break;
    const bool ok = tracker.update(frame);
    const filters::Box b = tracker.box();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    rows.push_back(ok ? FollowRow{k, b.x, b.y, b.w, b.h} : FollowRow{k, nan, nan, nan, nan});
    emit(ok);
  }
  if (writer) writer->commit();
  return rows;
}

void write_follow(const std::string& path, const std::vector<FollowRow>& rows) {
  write_text_atomically(path, [&](std::ostream& out) {
    char line[256];
    for (const auto& r : rows) {
      if (std::isnan(r.x)) {
        std::snprintf(line, sizeof line, "%lld,nan,nan,nan,nan\n", r.frame);
      } else {
        std::snprintf(line, sizeof line, "%lld,%.2f,%.2f,%.2f,%.2f\n", r.frame, r.x, r.y, r.w, r.h);
      }
      out << line;
    }
  });
}

}  // namespace vtrack::apps
