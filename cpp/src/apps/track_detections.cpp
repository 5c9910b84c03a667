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
                                .add("learn_clutter", &P::learn_clutter)
                                .add("learn_detection_probability", &P::learn_detection_probability)
                                .add("detection_probability_min", &P::detection_probability_min)
                                .add("detection_probability_max", &P::detection_probability_max)
                                .add("learning_memory", &P::learning_memory)
                                .add("learning_prior_weight", &P::learning_prior_weight)
                                .add("use_scores", &P::use_scores)
                                .add("score_window", &P::score_window)
                                .add("birth_score_weight", &P::birth_score_weight)
                                .add("duplicate_rate", &P::duplicate_rate)
                                .add("detection_sd_relative", &P::detection_sd_relative)
                                .include(&P::occlusion)
                                .include(&P::estimator)
                                .add("max_births", &P::max_births)
                                .add("birth_missed_tracks", &P::birth_missed_tracks)
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
  validate(p.occlusion);
  validate(p.estimator);
  // The learning bounds hold the learnt p_D; a fixed p_D (no learning) may lie outside them.
  require(p.detection_probability_min > 0 &&
              p.detection_probability_min <= p.detection_probability_max &&
              p.detection_probability_max < 1,
          "detection_probability_min", p.detection_probability_min,
          "0 < detection_probability_min <= detection_probability_max < 1");
  require(!p.learn_detection_probability ||
              (p.detection_probability >= p.detection_probability_min &&
               p.detection_probability <= p.detection_probability_max),
          "detection_probability", p.detection_probability,
          "within [detection_probability_min, detection_probability_max] when learnt");
  require(p.learning_memory >= 1 && std::isfinite(p.learning_memory), "learning_memory",
          p.learning_memory, ">= 1 and finite");
  require(p.learning_prior_weight > 0 && std::isfinite(p.learning_prior_weight),
          "learning_prior_weight", p.learning_prior_weight, "> 0 and finite");
  require(p.score_window >= 1, "score_window", p.score_window, ">= 1");
  require(p.detection_sd_relative >= 0 && std::isfinite(p.detection_sd_relative),
          "detection_sd_relative", p.detection_sd_relative, ">= 0 and finite");
  require(p.max_births >= 0, "max_births", p.max_births, ">= 0");
  require(p.duplicate_rate >= 0 && std::isfinite(p.duplicate_rate), "duplicate_rate",
          p.duplicate_rate, ">= 0 and finite");
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
  models::LinearGaussianObservation o{Eigen::MatrixXd::Zero(4, 6), Eigen::MatrixXd::Zero(4, 4),
                                      Eigen::MatrixXd()};
  o.H(0, 0) = o.H(1, 2) = o.H(2, 4) = o.H(3, 5) = 1.0;  // (cx, cy, w, h) of [cx,vcx,cy,vcy,w,h]
  const double c = p.detection_sd_centre * p.detection_sd_centre;
  const double s = p.detection_sd_size * p.detection_sd_size;
  o.R.diagonal() << c, c, s, s;
  if (p.detection_sd_relative > 0) {
    // Independent edge errors f w (left, right) and f h (top, bottom): the centre's sd is
    // f w / sqrt 2, the width's f w sqrt 2.
    const double f = p.detection_sd_relative;
    o.noise_scale = Eigen::MatrixXd::Zero(4, 6);
    o.noise_scale(0, 4) = o.noise_scale(1, 5) = f / std::sqrt(2.0);
    o.noise_scale(2, 4) = o.noise_scale(3, 5) = f * std::sqrt(2.0);
  }
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
  g.adaptive_birth.max_births = p.max_births;
  g.adaptive_birth.missed_tracks = p.birth_missed_tracks;
  g.occlusion = p.occlusion;
  g.estimator = p.estimator;
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
               box_tracker_params(params, width, height), std::nullopt, filters::BoxLayout{}),
      clutter_(width, height,
               {params.clutter_rate, params.duplicate_rate,
                {params.learning_memory, params.learning_prior_weight}}),
      detection_probability_(std::clamp(params.detection_probability,
                                        params.detection_probability_min,
                                        params.detection_probability_max),
                             params.detection_probability_min,
                             params.detection_probability_max,
                             {params.learning_memory, params.learning_prior_weight}),
      score_model_(params.score_window, params.learning_prior_weight, params.learning_memory) {}

void BoxTracker::set_duplicate_sources() {
  // The tracks of the last estimate, their boxes moved on by one frame at their velocity, each
  // weighted by its existence and its probability of being detectable at this frame (a detector
  // that cannot see a person gives neither their box nor its duplicates).
  const auto& tracks = tracker_.estimates();
  const double o = params_.occlusion.rate, stay = 1.0 - 1.0 / params_.occlusion.length;
  Eigen::MatrixXd boxes(4, static_cast<Eigen::Index>(tracks.size()));
  Eigen::VectorXd weights(boxes.cols());
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    const auto& x = tracks[t].mean;  // [cx, vcx, cy, vcy, w, h]
    const auto i = static_cast<Eigen::Index>(t);
    boxes.col(i) << x[0] + x[1], x[2] + x[3], std::max(x[4], 1.0), std::max(x[5], 1.0);
    const double hidden = tracks[t].undetectable * stay + (1.0 - tracks[t].undetectable) * o;
    weights[i] = tracks[t].existence * (1.0 - hidden);
  }
  clutter_.set_sources(std::move(boxes), std::move(weights));
}

const filters::Tracks& BoxTracker::step(const std::vector<Detection>& detections) {
  std::vector<Detection> kept;
  kept.reserve(detections.size());
  for (const auto& d : detections) {
    if (d.confidence >= params_.min_confidence) kept.push_back(d);
  }
  const Eigen::MatrixXd z = observations(kept);
  Eigen::VectorXd scores(z.cols());
  for (std::size_t j = 0; j < kept.size(); ++j) scores[Eigen::Index(j)] = kept[j].confidence;
  set_duplicate_sources();
  filters::ScanInput input;
  input.log_clutter = clutter_.log_intensity(z);
  // Births from detections that are unexplained (not a duplicate of a track) and target-like.
  input.birth_weight = clutter_.unexplained(Eigen::VectorXd::Ones(z.cols()));
  const Eigen::VectorXd u = score_model_.transform(scores);
  if (params_.use_scores) {
    const Eigen::VectorXd log_ratio = score_model_.log_ratio(u);
    input.log_clutter -= log_ratio;
    if (params_.birth_score_weight) {
      input.birth_weight.array() *= log_ratio.array().exp();
    }
  }
  if (params_.learn_detection_probability) {
    tracker_.set_detection_probability(detection_probability_.probability());
  }
  const filters::Tracks& tracks = tracker_.step(z, nullptr, input);
  learn(z, scores, u);
  return tracks;
}

void BoxTracker::learn(const Eigen::MatrixXd& z, const Eigen::VectorXd& scores,
                       const Eigen::VectorXd& u) {
  const filters::ScanSummary& s = tracker_.summary();
  const Eigen::VectorXd p_target = (s.to_track + s.to_birth).cwiseMin(1.0);
  if (params_.learn_clutter) clutter_.learn(z, (1.0 - p_target.array()).matrix());
  if (params_.learn_detection_probability) detection_probability_.update(s.detected, s.missed);
  score_model_.update(scores, u, p_target);
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
  // come from the previous frame's detections). An empty frame then reports nothing and changes
  // only the filter's step count and the online learners (clutter rate, p_D, score model), which
  // decay geometrically towards their priors with memory `learning_memory`. So the loop steps
  // through the first idle_steps = 20 memories of an idle run (the learners are then within
  // e^-20 of where any longer run leaves them; every shorter gap gives exactly the rows of
  // stepping every frame) and jumps to the next frame with detections: the cost depends on the
  // number of detections and the memory, not on the frame numbers (a row at frame 10^14 or
  // last_frame = 10^12 would otherwise step through every empty frame).
  const long long idle_steps =
      static_cast<long long>(std::min(20.0 * std::ceil(params.learning_memory), 1e6));
  bool idle = true;
  long long idle_run = 0;  // idle frames stepped since the last busy one
  long long reported = 0;  // the last frame given to `progress`
  for (long long frame = 1; frame <= last; ++frame) {
    if (idle && idle_run >= idle_steps) {
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
    idle_run = idle ? idle_run + 1 : 0;
    if (progress) progress(reported = frame, last);
    core::poll_interrupt();
  }
  if (progress && reported < last) progress(last, last);  // the skipped frames are done too
  return rows;
}

}  // namespace vtrack::apps
