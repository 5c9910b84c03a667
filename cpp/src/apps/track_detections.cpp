#include "vtrack/apps/track_detections.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"
#include "vtrack/core/limits.hpp"

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

const core::ParameterTable<BoxTrackerParams>& BoxTrackerParams::table() {
  using P = BoxTrackerParams;
  static const auto table = core::ParameterTable<P>()
                                .add("detection_probability", &P::detection_probability)
                                .add("survival_probability", &P::survival_probability)
                                .add("outside_survival_probability", &P::outside_survival_probability)
                                .add("outside_detection_probability", &P::outside_detection_probability)
                                .add("clutter_rate", &P::clutter_rate)
                                .add("sigma_accel", &P::sigma_accel)
                                .add("sigma_size", &P::sigma_size)
                                .add("detection_sd_centre", &P::detection_sd_centre)
                                .add("detection_sd_size", &P::detection_sd_size)
                                .add("birth_sd_centre", &P::birth_sd_centre)
                                .add("birth_sd_velocity", &P::birth_sd_velocity)
                                .add("birth_sd_size", &P::birth_sd_size)
                                .add("birth_rate", &P::birth_rate)
                                .add("birth_max_existence", &P::birth_max_existence)
                                .add("hypothesis_budget", &P::hypothesis_budget)
                                .add("gate_threshold", &P::gate_threshold)
                                .add("min_confidence", &P::min_confidence)
                                .include(&P::management)
                                .add_choice("ranking", &P::ranking,
                                            {{"murty", filters::HypothesisRanking::murty},
                                             {"gibbs", filters::HypothesisRanking::gibbs}})
                                .add("seed", &P::seed);
  return table;
}

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
  // Squared into covariances: a square that overflows would reach the filter as an inf in Q or R.
  for (const auto& [name, v] : positive) {
    require(v > 0 && std::isfinite(v * v), name, v, "> 0 with a finite square");
  }
  require(p.birth_max_existence > 0 && p.birth_max_existence < 1, "birth_max_existence",
          p.birth_max_existence, "in (0, 1)");
  validate(p.management);
  require(p.hypothesis_budget > 0 && p.hypothesis_budget <= core::kMaxHypotheses,
          "hypothesis_budget", p.hypothesis_budget, "in [1, 100000]");
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

filters::GlmbParams box_glmb_params(const BoxTrackerParams& p, int width, int height) {
  validate(p);
  require(width > 0, "image width", width, "> 0");
  require(height > 0, "image height", height, "> 0");
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
  const double area = static_cast<double>(width) * height;
  g.clutter_intensity = p.clutter_rate / (area * area);
  g.hypothesis_budget = p.hypothesis_budget;
  g.max_hypotheses = p.hypothesis_budget;
  g.gate_threshold = p.gate_threshold;
  g.ranking = p.ranking;
  g.seed = p.seed;
  g.adaptive_birth.enabled = true;
  g.adaptive_birth.expected_births = p.birth_rate;
  g.adaptive_birth.max_existence = p.birth_max_existence;
  Eigen::VectorXd sd(6);
  sd << p.birth_sd_centre, p.birth_sd_velocity, p.birth_sd_centre, p.birth_sd_velocity,
      p.birth_sd_size, p.birth_sd_size;
  g.adaptive_birth.cov = sd.array().square().matrix().asDiagonal();
  return g;
}

namespace {

filters::GlmbTrackerParams box_tracker_params(const BoxTrackerParams& p, int width, int height) {
  filters::GlmbTrackerParams t;
  t.glmb = box_glmb_params(p, width, height);
  t.management = p.management;
  return t;
}

}  // namespace

BoxTracker::BoxTracker(int width, int height, const BoxTrackerParams& params)
    : params_(params),
      width_(width),
      height_(height),
      tracker_(box_motion(params), box_observation(params), {},
               box_tracker_params(params, width, height), std::nullopt, filters::BoxLayout{}) {}

const filters::Tracks& BoxTracker::step(const std::vector<Detection>& detections) {
  std::vector<Detection> kept;
  kept.reserve(detections.size());
  for (const auto& d : detections) {
    if (d.confidence >= params_.min_confidence) kept.push_back(d);
  }
  return tracker_.step(observations(kept));
}

std::pair<int, int> detections_extent(const std::vector<Detection>& detections) {
  double width = 1, height = 1;
  for (const auto& d : detections) {
    width = std::max(width, d.x + d.w);
    height = std::max(height, d.y + d.h);
  }
  // Range-checked before narrowing to int (an image side beyond 2^20 px is no camera's).
  for (const auto& [name, extent] : {std::pair{"x + w", width}, std::pair{"y + h", height}}) {
    if (extent > core::kMaxImageSide) {
      throw InvalidArgument(std::string("the detections reach ") + name + " = " +
                            value_text(extent) + ", beyond the largest image side (" +
                            std::to_string(core::kMaxImageSide) + " px): give the image size");
    }
  }
  return {static_cast<int>(std::ceil(width)), static_cast<int>(std::ceil(height))};
}

std::vector<TrackRow> track_detections(const std::vector<Detection>& detections, int width,
                                       int height, const BoxTrackerParams& params,
                                       long long last_frame, const FrameProgress& progress) {
  if (width == 0 || height == 0) std::tie(width, height) = detections_extent(detections);
  BoxTracker tracker(width, height, params);  // validates the parameters and the image size
  if (last_frame < 0 || last_frame > core::kMaxFrame) {
    throw InvalidArgument("last_frame must be in [0, " + std::to_string(core::kMaxFrame) + "], got " +
                          std::to_string(last_frame));
  }
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
  // Idle: nothing tracked, remembered (lost-track memory) or about to be born (adaptive births
  // come from the previous frame's detections). An empty frame then changes nothing but the
  // filter's step count and reports nothing, so the loop jumps to the next frame with
  // detections: the cost depends on the number of detections, not on the frame numbers (a row
  // at frame 10^14 or last_frame = 10^12 would otherwise step through every empty frame).
  bool idle = true;
  long long reported = 0;  // the last frame given to `progress`
  for (long long frame = 1; frame <= last; ++frame) {
    if (idle) {
      frame = next == sorted.end() ? last + 1 : next->frame;
      if (frame > last) break;
    }
    frame_detections.clear();
    for (; next != sorted.end() && next->frame == frame; ++next) frame_detections.push_back(*next);
    const filters::Tracks& tracks = tracker.step(frame_detections);
    append_rows(rows, frame, tracks);
    const bool any_kept =
        std::any_of(frame_detections.begin(), frame_detections.end(),
                    [&](const Detection& d) { return d.confidence >= params.min_confidence; });
    idle = !any_kept && tracker.tracker().track_count() == 0 &&
           tracker.tracker().management().lost_count() == 0;
    if (progress) progress(reported = frame, last);
    core::poll_interrupt();
  }
  if (progress && reported < last) progress(last, last);  // the skipped frames are done too
  return rows;
}

}  // namespace vtrack::apps
