#include "vtrack/apps/track_video.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <opencv2/imgproc.hpp>

#include "vtrack/apps/detection_file.hpp"
#include "vtrack/apps/parameters.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"

namespace vtrack::apps {
void load_pipeline_config(const std::string& path, MbPipelineParams& params) {
  const ConfigFile config = read_config_file(path, {"background", "tracker"}, true);
  if (config.seed) params.seed = *config.seed;
  apply_config_section(config, "background", params.background);
  apply_config_section(config, "tracker", params.tracker);
  image::validate(params.background);
  filters::validate(params.tracker);
}

void draw_labelled_box(cv::Mat& frame, std::uint64_t label, double x, double y, double w,
                       double h) {
  // A colour per label: hue from a golden-ratio walk, so consecutive labels differ clearly.
  const double hue = std::fmod(static_cast<double>(label) * 0.618033988749895, 1.0) * 180.0;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, 220, 255)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  const cv::Scalar colour(c[0], c[1], c[2]);
  const cv::Rect box(cvRound(x), cvRound(y), cvRound(w), cvRound(h));
  cv::rectangle(frame, box, colour, 2);
  cv::putText(frame, std::to_string(label), box.tl() + cv::Point(2, 14), cv::FONT_HERSHEY_SIMPLEX,
              0.5, colour, 2);
}

void draw_tracks(cv::Mat& frame, const std::vector<filters::Track>& tracks) {
  for (const auto& t : tracks) draw_labelled_box(frame, t.label, t.x, t.y, t.w, t.h);
}

std::vector<TrackRow> track_video_mb(const std::string& input, const MbPipelineParams& params,
                                     const std::string& render, const FrameProgress& progress) {
  image::KdeBackground background(params.background);  // validates before any file is touched
  filters::validate(params.tracker);
  if (!render.empty() && !is_video_output(render)) {
    throw InvalidArgument("render must be a .avi, .mp4 or .mkv file, got '" + render + "'");
  }
  VideoSource source(input);
  filters::MultiBernoulliFilter tracker(source.width(), source.height(), params.tracker,
                                        params.seed);
  std::unique_ptr<AtomicVideoWriter> video;
  if (!render.empty()) {
    video = std::make_unique<AtomicVideoWriter>(render, source.fps() > 0 ? source.fps() : 25.0,
                                                cv::Size(source.width(), source.height()));
  }
  std::vector<TrackRow> rows;
  cv::Mat frame, y;
  while (source.read(frame)) {
    background.apply(frame, y);
    const std::vector<filters::Track>& tracks = tracker.step(y);
    const long long frame_number = source.frames_read();  // 1-based, as MOTChallenge counts
    for (const auto& t : tracks) {
      rows.push_back({frame_number, t.label, t.x, t.y, t.w, t.h, t.existence});
    }
    if (video) {
      draw_tracks(frame, tracks);
      video->write(frame);
    }
    if (progress) progress(source.frames_read(), source.expected_frame_count());
  }
  if (video) video->commit();
  return rows;
}

void write_mot(const std::string& path, const std::vector<TrackRow>& rows) {
  write_text_atomically(path, [&](std::ostream& out) {
    char line[160];
    for (const auto& r : rows) {
      std::snprintf(line, sizeof line, "%lld,%llu,%.2f,%.2f,%.2f,%.2f,%.4f,-1,-1,-1\n", r.frame,
                    static_cast<unsigned long long>(r.id), r.x, r.y, r.w, r.h, r.confidence);
      out << line;
    }
  });
}

}  // namespace vtrack::apps
