#include "vtrack/apps/track_video.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include <opencv2/imgproc.hpp>

#include "vtrack/apps/parameters.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"

namespace vtrack::apps {
namespace {

ParameterValue node_value(const std::string& name, const cv::FileNode& node) {
  if (node.isInt()) return static_cast<long long>(static_cast<int>(node));
  if (node.isReal()) return static_cast<double>(node);
  if (node.isString()) {
    const std::string s = static_cast<std::string>(node);
    if (s == "true") return true;
    if (s == "false") return false;
    return s;
  }
  throw InvalidArgument("parameter " + name + " must be a number, true/false or a name");
}

template <typename Params>
void load_section(const cv::FileNode& section, const std::string& section_name, Params& params) {
  if (section.empty()) return;
  if (!section.isMap()) throw InvalidArgument("config section '" + section_name + "' must be a map");
  for (const auto& node : section) {
    const std::string name = node.name();
    if (!set_parameter(params, name, node_value(name, node))) {
      throw InvalidArgument("unknown parameter '" + name + "' in config section '" +
                            section_name + "'");
    }
  }
}

}  // namespace

void load_pipeline_config(const std::string& path, MbPipelineParams& params) {
  if (!std::filesystem::is_regular_file(path)) throw IoError("no such config file: '" + path + "'");
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw IoError("cannot parse config file '" + path + "': " + e.err);
  }
  if (!fs.isOpened()) throw IoError("cannot parse config file '" + path + "' (YAML or JSON)");
  const cv::FileNode root = fs.root();
  for (const auto& node : root) {
    const std::string key = node.name();
    if (key != "seed" && key != "background" && key != "tracker") {
      throw InvalidArgument("unknown config section '" + key +
                            "' (expected seed, background, tracker)");
    }
  }
  if (!root["seed"].empty()) {
    if (!root["seed"].isInt() || static_cast<int>(root["seed"]) < 0) {
      throw InvalidArgument("config seed must be a non-negative integer");
    }
    params.seed = static_cast<std::uint64_t>(static_cast<int>(root["seed"]));
  }
  load_section(root["background"], "background", params.background);
  load_section(root["tracker"], "tracker", params.tracker);
  image::validate(params.background);
  filters::validate(params.tracker);
}

void draw_tracks(cv::Mat& frame, const std::vector<filters::Track>& tracks) {
  for (const auto& t : tracks) {
    // A colour per label: hue from a golden-ratio walk, so consecutive labels differ clearly.
    const double hue = std::fmod(static_cast<double>(t.label) * 0.618033988749895, 1.0) * 180.0;
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, 220, 255)), bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
    const cv::Scalar colour(c[0], c[1], c[2]);
    const cv::Rect box(cvRound(t.x), cvRound(t.y), cvRound(t.w), cvRound(t.h));
    cv::rectangle(frame, box, colour, 2);
    cv::putText(frame, std::to_string(t.label), box.tl() + cv::Point(2, 14),
                cv::FONT_HERSHEY_SIMPLEX, 0.5, colour, 2);
  }
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
  const std::filesystem::path target(path);
  const std::filesystem::path partial = target.string() + ".partial";
  {
    std::ofstream out(partial);
    if (!out) throw IoError("cannot write tracks to '" + partial.string() + "'");
    char line[160];
    for (const auto& r : rows) {
      std::snprintf(line, sizeof line, "%lld,%llu,%.2f,%.2f,%.2f,%.2f,%.4f,-1,-1,-1\n", r.frame,
                    static_cast<unsigned long long>(r.id), r.x, r.y, r.w, r.h, r.confidence);
      out << line;
    }
    out.close();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(partial, ec);
      throw IoError("cannot write tracks to '" + partial.string() + "'");
    }
  }
  rename_or_throw(partial, target);
}

}  // namespace vtrack::apps
