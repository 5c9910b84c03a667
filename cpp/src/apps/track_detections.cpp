#include "vtrack/apps/track_detections.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "vtrack/apps/parameters.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"

namespace vtrack::apps {
namespace {

// Rows: the detections' z = (cx, cy, w, h), one per column (the filter's layout).
Eigen::MatrixXd observations(const std::vector<Detection>& detections) {
  Eigen::MatrixXd z(4, static_cast<Eigen::Index>(detections.size()));
  for (std::size_t j = 0; j < detections.size(); ++j) {
    const Detection& d = detections[j];
    z.col(static_cast<Eigen::Index>(j)) << d.x + d.w / 2, d.y + d.h / 2, d.w, d.h;
  }
  return z;
}

}  // namespace

void validate(const BoxTrackerParams& p) {
  require(p.detection_probability > 0 && p.detection_probability < 1, "detection_probability",
          p.detection_probability, "in (0, 1)");
  require(p.survival_probability > 0 && p.survival_probability < 1, "survival_probability",
          p.survival_probability, "in (0, 1)");
  require(p.outside_survival_probability > 0 && p.outside_survival_probability < 1,
          "outside_survival_probability", p.outside_survival_probability, "in (0, 1)");
  require(p.outside_detection_probability > 0 && p.outside_detection_probability < 1,
          "outside_detection_probability", p.outside_detection_probability, "in (0, 1)");
  const std::pair<const char*, double> positive[] = {
      {"clutter_rate", p.clutter_rate},           {"sigma_accel", p.sigma_accel},
      {"sigma_size", p.sigma_size},               {"detection_sd_centre", p.detection_sd_centre},
      {"detection_sd_size", p.detection_sd_size}, {"birth_sd_centre", p.birth_sd_centre},
      {"birth_sd_velocity", p.birth_sd_velocity}, {"birth_sd_size", p.birth_sd_size},
      {"birth_rate", p.birth_rate}};
  for (const auto& [name, v] : positive) require(v > 0 && std::isfinite(v), name, v, "> 0 and finite");
  require(p.birth_max_existence > 0 && p.birth_max_existence < 1, "birth_max_existence",
          p.birth_max_existence, "in (0, 1)");
  require(p.min_age >= 1, "min_age", p.min_age, ">= 1");
  require(p.seed >= 0, "seed", p.seed, ">= 0");
  require(p.hypothesis_budget > 0, "hypothesis_budget", p.hypothesis_budget, "> 0");
  require(p.gate_threshold > 0, "gate_threshold", p.gate_threshold, "> 0 (or inf for no gating)");
  require(!std::isnan(p.min_confidence), "min_confidence", p.min_confidence, "a number");
}

models::LinearGaussianMotion box_motion(const BoxTrackerParams& p) {
  const auto cv = models::LinearGaussianMotion::constant_velocity(2, 1.0, p.sigma_accel);
  models::LinearGaussianMotion m{Eigen::MatrixXd::Identity(6, 6), Eigen::MatrixXd::Zero(6, 6)};
  m.F.topLeftCorner(4, 4) = cv.F;
  m.Q.topLeftCorner(4, 4) = cv.Q;
  m.Q(4, 4) = m.Q(5, 5) = p.sigma_size * p.sigma_size;
  return m;
}

models::LinearGaussianObservation box_observation(const BoxTrackerParams& p) {
  models::LinearGaussianObservation o{Eigen::MatrixXd::Zero(4, 6), Eigen::MatrixXd::Zero(4, 4)};
  o.H(0, 0) = o.H(1, 2) = o.H(2, 4) = o.H(3, 5) = 1.0;  // (cx, cy, w, h) of [cx,vcx,cy,vcy,w,h]
  const double c = p.detection_sd_centre * p.detection_sd_centre;
  const double s = p.detection_sd_size * p.detection_sd_size;
  o.R.diagonal() << c, c, s, s;
  return o;
}

filters::GlmbParams box_glmb_params(const BoxTrackerParams& p, double width, double height) {
  validate(p);
  require(width > 0 && std::isfinite(width), "image width", width, "> 0");
  require(height > 0 && std::isfinite(height), "image height", height, "> 0");
  filters::GlmbParams g;
  g.survival_probability = p.survival_probability;
  g.detection_probability = p.detection_probability;
  // The field of view: box centres (cx, cy) in the image, velocities and sizes unconstrained.
  constexpr double inf = std::numeric_limits<double>::infinity();
  g.field_of_view.enabled = true;
  g.field_of_view.lower = Eigen::VectorXd::Constant(6, -inf);
  g.field_of_view.upper = Eigen::VectorXd::Constant(6, inf);
  g.field_of_view.lower(0) = g.field_of_view.lower(2) = 0.0;
  g.field_of_view.upper(0) = width;
  g.field_of_view.upper(2) = height;
  g.field_of_view.outside_survival_probability = p.outside_survival_probability;
  g.field_of_view.outside_detection_probability = p.outside_detection_probability;
  // Uniform clutter over centre (W x H) and size ([0, W] x [0, H]): volume (W H)^2.
  g.clutter_intensity = p.clutter_rate / ((width * height) * (width * height));
  g.hypothesis_budget = p.hypothesis_budget;
  g.max_hypotheses = p.hypothesis_budget;
  g.gate_threshold = p.gate_threshold;
  g.ranking = p.gibbs_ranking ? filters::HypothesisRanking::gibbs
                              : filters::HypothesisRanking::murty;
  g.seed = static_cast<std::uint64_t>(p.seed);
  g.adaptive_birth.enabled = true;
  g.adaptive_birth.expected_births = p.birth_rate;
  g.adaptive_birth.max_existence = p.birth_max_existence;
  Eigen::VectorXd sd(6);
  sd << p.birth_sd_centre, p.birth_sd_velocity, p.birth_sd_centre, p.birth_sd_velocity,
      p.birth_sd_size, p.birth_sd_size;
  g.adaptive_birth.cov = sd.array().square().matrix().asDiagonal();
  return g;
}

BoxTracker::BoxTracker(double width, double height, const BoxTrackerParams& params)
    : params_(params),
      filter_(box_motion(params), box_observation(params), {},
              box_glmb_params(params, width, height)) {}

std::vector<BoxTrack> BoxTracker::step(const std::vector<Detection>& detections) {
  std::vector<Detection> kept;
  kept.reserve(detections.size());
  for (const auto& d : detections) {
    if (d.confidence >= params_.min_confidence) kept.push_back(d);
  }
  filter_.step(observations(kept));
  std::vector<BoxTrack> out;
  for (const auto& e : filter_.estimates()) {
    if (filter_.time() - e.label.birth_time + 1 < params_.min_age) continue;  // not confirmed yet
    const auto key = std::make_pair(e.label.birth_time, e.label.birth_index);
    const auto it = ids_.emplace(key, ids_.size() + 1).first;
    const double w = e.mean(4), h = e.mean(5);
    out.push_back({it->second, e.mean(0) - w / 2, e.mean(2) - h / 2, w, h});
  }
  return out;
}

std::pair<double, double> detections_extent(const std::vector<Detection>& detections) {
  double width = 1, height = 1;
  for (const auto& d : detections) {
    width = std::max(width, d.x + d.w);
    height = std::max(height, d.y + d.h);
  }
  return {width, height};
}

std::vector<TrackRow> track_detections(const std::vector<Detection>& detections, double width,
                                       double height, const BoxTrackerParams& params,
                                       long long last_frame, const FrameProgress& progress) {
  BoxTracker tracker(width, height, params);  // validates the parameters and the image size
  if (last_frame < 0) throw InvalidArgument("last_frame must be >= 0, got " + std::to_string(last_frame));
  long long last = last_frame;
  for (std::size_t i = 0; i < detections.size(); ++i) {
    validate_detection(detections[i], "detection " + std::to_string(i) + ": ");
    last = std::max(last, detections[i].frame);
  }
  // Stable by frame, so each frame's detections keep their input order (adaptive birth labels
  // index them).
  std::vector<Detection> sorted = detections;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Detection& a, const Detection& b) { return a.frame < b.frame; });
  std::vector<TrackRow> rows;
  std::vector<Detection> frame_detections;
  auto next = sorted.begin();
  for (long long frame = 1; frame <= last; ++frame) {
    frame_detections.clear();
    for (; next != sorted.end() && next->frame == frame; ++next) frame_detections.push_back(*next);
    for (const auto& t : tracker.step(frame_detections)) {
      rows.push_back({frame, t.id, static_cast<float>(t.x), static_cast<float>(t.y),
                      static_cast<float>(t.w), static_cast<float>(t.h), 1.0});
    }
    if (progress) progress(frame, last);
  }
  return rows;
}

void load_pipeline_config(const std::string& path, GlmbPipelineParams& params) {
  const ConfigFile config = read_config_file(path, {"detector", "tracker"}, false);
  apply_config_section(config, "detector", params.detector);
  apply_config_section(config, "tracker", params.tracker);
  validate(params.detector);
  validate(params.tracker);
}

GlmbVideoResult track_video_glmb(const std::string& input, const HogParams& detector_params,
                                 const BoxTrackerParams& tracker_params, const std::string& render,
                                 const FrameProgress& progress) {
  HogPeopleDetector detector(detector_params);  // validates before any file is touched
  validate(tracker_params);
  if (!render.empty() && !is_video_output(render)) {
    throw InvalidArgument("render must be a .avi, .mp4 or .mkv file, got '" + render + "'");
  }
  VideoSource source(input);
  BoxTracker tracker(source.width(), source.height(), tracker_params);
  std::unique_ptr<AtomicVideoWriter> video;
  if (!render.empty()) {
    video = std::make_unique<AtomicVideoWriter>(render, source.fps() > 0 ? source.fps() : 25.0,
                                                cv::Size(source.width(), source.height()));
  }
  GlmbVideoResult result;
  std::vector<Detection> frame_detections;
  cv::Mat frame;
  while (source.read(frame)) {
    const long long frame_number = source.frames_read();  // 1-based, as MOTChallenge counts
    frame_detections.clear();
    for (const auto& b : detector.detect(frame)) {
      frame_detections.push_back({frame_number, b.x, b.y, b.w, b.h, b.score});
    }
    result.detections.insert(result.detections.end(), frame_detections.begin(),
                             frame_detections.end());
    const auto tracks = tracker.step(frame_detections);
    for (const auto& t : tracks) {
      result.tracks.push_back({frame_number, t.id, static_cast<float>(t.x),
                               static_cast<float>(t.y), static_cast<float>(t.w),
                               static_cast<float>(t.h), 1.0});
      if (video) draw_labelled_box(frame, t.id, t.x, t.y, t.w, t.h);
    }
    if (video) video->write(frame);
    if (progress) progress(source.frames_read(), source.expected_frame_count());
  }
  if (video) video->commit();
  return result;
}

}  // namespace vtrack::apps
