#include "vtrack/apps/pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include <opencv2/imgproc.hpp>

#include "vtrack/apps/output_paths.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"

namespace vtrack::apps {
namespace {

// mb: y = KDE(frame), tracks = MB(y).
class MbFrameTracker : public FrameTracker {
 public:
  MbFrameTracker(const PipelineParams& p, int width, int height)
      : background_(p.background), tracker_(width, height, p.mb),
        follow_closing_(p.mb.likelihood.closing_size == 0 && p.mb.likelihood.closing_ratio > 0),
        pixel_closing_(p.background.closing) {}
  const filters::Tracks& step(const cv::Mat& frame) override {
    background_.apply(frame, y_);
    const filters::Tracks& tracks = tracker_.step(y_, frame);  // colours: appearance_rate
    // The closing of y is relative to the people's size, which the tracker learns: the background
    // model's closing (and so its selective update's mask) follows the tracker's, but never falls
    // below the background model's own, which removes the sensor's pixel specks: their size is
    // the camera's, not the people's. (Without the floor, people under ~33 px tall, e.g. a
    // 160 x 120 scene, left y unclosed and the specks fed false tracks: MB MOTA on
    // benchmarks/synthetic_people.py's 0.5x scene seed 11, 0.644 -> 0.949 with the floor and the
    // illumination compensation.)
    if (follow_closing_) {
      background_.set_closing(std::max(pixel_closing_, tracker_.likelihood().closing_pixels()));
    }
    return tracks;
  }

 private:
  image::KdeBackground background_;
  filters::MultiBernoulliFilter tracker_;
  bool follow_closing_;  // the tracker's closing is person-relative
  int pixel_closing_;    // the background model's own closing: the floor of the one followed
  cv::Mat y_;
};

// sir: y = KDE(frame), tracks = ReclusteringSir(y). The KDE's own closing (3 x 3 by default)
// is kept: the SIR subsamples the foreground on a grid of 0.05 person heights, coarser than
// any speck a person-sized closing would remove.
class SirFrameTracker : public FrameTracker {
 public:
  SirFrameTracker(const PipelineParams& p, int width, int height)
      : background_(p.sir_background), tracker_(width, height, p.sir) {}
  const filters::Tracks& step(const cv::Mat& frame) override {
    background_.apply(frame, y_);
    return tracker_.step(y_, frame);  // colours keep the labels on the people: appearance_rate
  }

 private:
  image::KdeBackground background_;
  filters::ReclusteringSir tracker_;
  cv::Mat y_;
};

// glmb: boxes = detector(frame), tracks = BoxTracker(boxes).
class GlmbFrameTracker : public FrameTracker {
 public:
  GlmbFrameTracker(const PipelineParams& p, int width, int height)
      : detector_(p.hog), tracker_(width, height, p.box) {
    detector_.check_frame_size(width, height);  // before any frame is read or output opened
  }
  const filters::Tracks& step(const cv::Mat& frame) override {
    detections_.clear();
    for (const auto& b : detector_.detect(frame)) {
      detections_.push_back({0, b.x, b.y, b.w, b.h, b.score});
    }
    return tracker_.step(detections_);
  }
  const std::vector<Detection>* detections() const override { return &detections_; }

 private:
  HogPeopleDetector detector_;
  BoxTracker tracker_;
  std::vector<Detection> detections_;
};

// A method: its name, the detectors it takes ("" = none), its config sections (name, the
// parameters' setter and values), its validation and its FrameTracker.
struct Method {
  std::string name;
  std::vector<std::string> detectors;
  struct Section {
    std::string name;
    std::function<bool(PipelineParams&, const std::string&, const core::ParameterValue&)> set;
    std::function<ParameterValues(const PipelineParams&)> values;
  };
  std::vector<Section> sections;
  std::function<void(const PipelineParams&)> validate;
  std::function<std::unique_ptr<FrameTracker>(const PipelineParams&, int, int)> make;
};

// A config section over the params struct that `member` selects.
template <class Params>
Method::Section section(std::string name, Params PipelineParams::*member) {
  return {std::move(name),
          [member](PipelineParams& p, const std::string& key, const core::ParameterValue& v) {
            return Params::table().set(p.*member, key, v);
          },
          [member](const PipelineParams& p) { return Params::table().values(p.*member); }};
}

const std::vector<Method>& methods() {
  static const std::vector<Method> table = {
      {"mb",
       {""},
       {section("background", &PipelineParams::background), section("tracker", &PipelineParams::mb)},
       [](const PipelineParams& p) {
         image::validate(p.background);
         filters::validate(p.mb);
       },
       [](const PipelineParams& p, int w, int h) -> std::unique_ptr<FrameTracker> {
         return std::make_unique<MbFrameTracker>(p, w, h);
       }},
      {"sir",
       {""},
       {section("background", &PipelineParams::sir_background),
        section("tracker", &PipelineParams::sir)},
       [](const PipelineParams& p) {
         image::validate(p.sir_background);
         filters::validate(p.sir);
       },
       [](const PipelineParams& p, int w, int h) -> std::unique_ptr<FrameTracker> {
         return std::make_unique<SirFrameTracker>(p, w, h);
       }},
      {"glmb",
       {"hog"},
       {section("detector", &PipelineParams::hog), section("tracker", &PipelineParams::box)},
       [](const PipelineParams& p) {
         validate(p.hog);
         validate(p.box);
       },
       [](const PipelineParams& p, int w, int h) -> std::unique_ptr<FrameTracker> {
         return std::make_unique<GlmbFrameTracker>(p, w, h);
       }},
  };
  return table;
}

const Method& method_of(const PipelineParams& params) {
  for (const auto& m : methods()) {
    if (m.name == params.method) return m;
  }
  std::string known;
  for (const auto& m : methods()) known += (known.empty() ? "" : ", ") + m.name;
  throw InvalidArgument("method must be one of " + known + ", got '" + params.method + "'");
}

}  // namespace

const std::vector<std::string>& pipeline_methods() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& m : methods()) out.push_back(m.name);
    return out;
  }();
  return names;
}

std::vector<PipelineSection> pipeline_sections(const PipelineParams& params) {
  std::vector<PipelineSection> out;
  for (const auto& s : method_of(params).sections) out.push_back({s.name, s.values(params)});
  return out;
}

void set_pipeline_parameter(PipelineParams& params, const std::string& name,
                            const core::ParameterValue& value) {
  const Method& method = method_of(params);
  for (const auto& s : method.sections) {
    if (s.set(params, name, value)) return;
  }
  std::vector<std::string> names;
  for (const auto& s : method.sections) {
    for (const auto& [key, v] : s.values(params)) names.push_back(key);
  }
  core::throw_unknown_parameter(name, method.name, names);
}

void apply_config(PipelineParams& params, const Config& config) {
  const Method& method = method_of(params);
  if (config.seed) set_pipeline_parameter(params, "seed", *config.seed);
  const std::string where = config.path.empty() ? "config" : "config file '" + config.path + "'";
  for (const auto& [section_name, values] : config.sections) {
    const auto s = std::find_if(method.sections.begin(), method.sections.end(),
                                [&](const Method::Section& m) { return m.name == section_name; });
    if (s == method.sections.end()) {
      std::string known = "seed";
      for (const auto& m : method.sections) known += ", " + m.name;
      throw InvalidArgument(where + ": method " + method.name + " has no section '" +
                            section_name + "' (it reads " + known + ")");
    }
    for (const auto& [name, value] : values) {
      if (!s->set(params, name, value)) {
        std::vector<std::string> names;
        for (const auto& [key, v] : s->values(params)) names.push_back(key);
        throw InvalidType(where + ": " +
                          core::unknown_parameter_message(name, section_name, names));
      }
    }
  }
}

void validate(const PipelineParams& params) {
  const Method& method = method_of(params);
  if (std::find(method.detectors.begin(), method.detectors.end(), params.detector) ==
      method.detectors.end()) {
    if (params.detector.empty()) {
      throw InvalidArgument("method " + method.name + " needs a detector (detector must be " +
                            method.detectors.front() + ")");
    }
    throw InvalidArgument("method " + method.name + (method.detectors.front().empty()
                                                         ? " takes no detector"
                                                         : " takes detector " + method.detectors.front()) +
                          ", got '" + params.detector + "'");
  }
  method.validate(params);
}

std::unique_ptr<FrameTracker> make_frame_tracker(const PipelineParams& params, int width,
                                                 int height) {
  validate(params);
  return method_of(params).make(params, width, height);
}

void draw_labelled_box(cv::Mat& frame, std::uint64_t id, double x, double y, double w, double h) {
  // A colour per id: hue from a golden-ratio walk, so consecutive ids differ clearly.
  const double hue = std::fmod(static_cast<double>(id) * 0.618033988749895, 1.0) * 180.0;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, 220, 255)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  const cv::Scalar colour(c[0], c[1], c[2]);
  const cv::Rect box(cvRound(x), cvRound(y), cvRound(w), cvRound(h));
  cv::rectangle(frame, box, colour, 2);
  cv::putText(frame, std::to_string(id), box.tl() + cv::Point(2, 14), cv::FONT_HERSHEY_SIMPLEX,
              0.5, colour, 2);
}

PipelineResult track_video(const std::string& input, const PipelineParams& params,
                           const std::string& render, const FrameProgress& progress) {
  validate(params);  // before any file is touched
  if (!render.empty() && !is_video_output(render)) {
    throw InvalidArgument("render must be a .avi, .mp4 or .mkv file, got '" + render + "'");
  }
  if (!render.empty()) check_outputs({{"video", input}}, {{"render", render}});
  VideoSource source(input);
  const auto tracker = make_frame_tracker(params, source.width(), source.height());
  std::unique_ptr<AtomicVideoWriter> video;
  if (!render.empty()) {
    video = std::make_unique<AtomicVideoWriter>(render, source.fps() > 0 ? source.fps() : 25.0,
                                                cv::Size(source.width(), source.height()));
  }
  PipelineResult result;
  cv::Mat frame;
  while (source.read(frame)) {
    core::poll_interrupt();
    const long long frame_number = source.frames_read();  // 1-based, as MOTChallenge counts
    const filters::Tracks& tracks = tracker->step(frame);
    append_rows(result.tracks, frame_number, tracks);
    if (const auto* detections = tracker->detections()) {
      for (Detection d : *detections) {
        d.frame = frame_number;
        result.detections.push_back(d);
      }
    }
    if (video) {
      for (const auto& t : tracks) draw_labelled_box(frame, t.id, t.x, t.y, t.w, t.h);
      video->write(frame);
    }
    if (progress) progress(frame_number, source.expected_frame_count());
  }
  if (video) video->commit();
  result.frames = source.frames_read();
  return result;
}

}  // namespace vtrack::apps
