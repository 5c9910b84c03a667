#include "vtrack/filters/glmb.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/filters/glmb_impl.hpp"

namespace vtrack::filters {
namespace {

void require_probability(double p, const char* name, bool allow_one = true) {
  require(p > 0.0 && (p < 1.0 || (allow_one && p == 1.0)), name, p,
          allow_one ? "in (0, 1]" : "in (0, 1)");
}

}  // namespace

const core::ParameterTable<AdaptiveBirthParams>& AdaptiveBirthParams::table() {
  using P = AdaptiveBirthParams;
  static const auto table = core::ParameterTable<P>()
                                .add("adaptive_birth_rate", &P::expected_births)
                                .add("adaptive_birth_max_existence", &P::max_existence)
                                .add("adaptive_birth_max", &P::max_births)
                                .add("adaptive_birth_missed_tracks", &P::missed_tracks);
  return table;
}

const core::ParameterTable<OcclusionParams>& OcclusionParams::table() {
  using P = OcclusionParams;
  static const auto table = core::ParameterTable<P>()
                                .add("occlusion_rate", &P::rate)
                                .add("occlusion_length", &P::length)
                                .add("occlusion_max_length", &P::max_length);
  return table;
}

const core::ParameterTable<EstimatorParams>& EstimatorParams::table() {
  using P = EstimatorParams;
  static const auto table =
      core::ParameterTable<P>()
          .add_choice("label_estimator", &P::estimator,
                      {{"map", LabelEstimator::map}, {"consistent", LabelEstimator::consistent}})
          .add("label_keep_bonus", &P::keep_bonus)
          .add("label_entry_penalty", &P::entry_penalty)
          .add("label_duplicate_gate", &P::duplicate_gate);
  return table;
}

const core::ParameterTable<GlmbParams>& GlmbParams::table() {
  using P = GlmbParams;
  static const auto table =
      core::ParameterTable<P>()
          .add("survival_probability", &P::survival_probability)
          .add("detection_probability", &P::detection_probability)
          .add("clutter_intensity", &P::clutter_intensity)
          .add("hypothesis_budget", &P::hypothesis_budget)
          .add("max_hypotheses", &P::max_hypotheses)
          .add("prune_threshold", &P::prune_threshold)
          .add("gate_threshold", &P::gate_threshold)
          .add("gate_max_detections", &P::gate_max_detections)
          .include(&P::adaptive_birth)
          .include(&P::occlusion)
          .include(&P::estimator)
          .add_choice("ranking", &P::ranking,
                      {{"murty", HypothesisRanking::murty}, {"gibbs", HypothesisRanking::gibbs}})
          .add("seed", &P::seed);
  return table;
}

void validate(const GlmbParams& p) {
  require_probability(p.survival_probability, "survival_probability");
  require_probability(p.detection_probability, "detection_probability");
  require(p.clutter_intensity > 0.0 && std::isfinite(p.clutter_intensity), "clutter_intensity",
          p.clutter_intensity, "positive and finite");
  require(p.hypothesis_budget > 0 && p.hypothesis_budget <= core::kMaxHypotheses,
          "hypothesis_budget", p.hypothesis_budget, "in [1, 100000]");
  require(p.max_hypotheses > 0 && p.max_hypotheses <= core::kMaxHypotheses, "max_hypotheses",
          p.max_hypotheses, "in [1, 100000]");
  require(p.prune_threshold >= 0.0 && p.prune_threshold < 1.0, "prune_threshold",
          p.prune_threshold, "in [0, 1)");
  require(p.gate_threshold > 0.0, "gate_threshold", p.gate_threshold,
          "> 0 (or inf for no gating)");
  const auto& fov = p.field_of_view;
  if (fov.enabled) {
    require_probability(fov.outside_survival_probability,
                        "field_of_view outside_survival_probability");
    require_probability(fov.outside_detection_probability,
                        "field_of_view outside_detection_probability");
  }
  const auto& adaptive = p.adaptive_birth;
  require(adaptive.expected_births > 0.0 && std::isfinite(adaptive.expected_births),
          "adaptive_birth_rate", adaptive.expected_births, "positive and finite");
  require_probability(adaptive.max_existence, "adaptive_birth_max_existence", false);
  require(adaptive.max_births >= 0, "adaptive_birth_max", adaptive.max_births, ">= 0");
  require(p.gate_max_detections >= 1, "gate_max_detections", p.gate_max_detections, ">= 1");
  validate(p.occlusion);
  validate(p.estimator);
}

void validate(const OcclusionParams& p) {
  require(p.rate >= 0.0 && p.rate < 1.0, "occlusion_rate", p.rate, "in [0, 1)");
  require(p.length >= 1.0 && std::isfinite(p.length), "occlusion_length", p.length,
          ">= 1 and finite");
  require(p.max_length >= 1, "occlusion_max_length", p.max_length, ">= 1");
}

void validate(const EstimatorParams& p) {
  require(p.keep_bonus >= 0.0 && std::isfinite(p.keep_bonus), "label_keep_bonus", p.keep_bonus,
          ">= 0 and finite");
  require(p.entry_penalty >= 0.0 && std::isfinite(p.entry_penalty), "label_entry_penalty",
          p.entry_penalty, ">= 0 and finite");
  require(p.duplicate_gate >= 0.0 && std::isfinite(p.duplicate_gate), "label_duplicate_gate",
          p.duplicate_gate, ">= 0 and finite (0: off)");
}

void check_glmb_dimensions(const models::LinearGaussianMotion& motion,
                           const models::LinearGaussianObservation& observation,
                           const std::vector<GaussianBirth>& births, const GlmbParams& params) {
  const Eigen::Index x_dim = motion.F.rows();
  if (motion.F.cols() != x_dim || motion.Q.rows() != x_dim || motion.Q.cols() != x_dim) {
    throw InvalidArgument("motion model: F and Q must both be square of the state dimension");
  }
  if (observation.H.cols() != x_dim || observation.R.rows() != observation.H.rows() ||
      observation.R.cols() != observation.H.rows()) {
    throw InvalidArgument("observation model: H must be z_dim x x_dim and R z_dim x z_dim");
  }
  if (observation.noise_scale.size() != 0 &&
      (observation.noise_scale.rows() != observation.H.rows() ||
       observation.noise_scale.cols() != x_dim)) {
    throw InvalidArgument("observation model: noise_scale must be z_dim x x_dim (or empty)");
  }
  // Finite models and true covariances: a negative-definite Q, R or birth covariance would be
  // accepted by the Kalman algebra and come back as negative variances.
  models::validate(motion);
  models::validate(observation);
  for (std::size_t b = 0; b < births.size(); ++b) {
    require_probability(births[b].existence, "birth existence");
    const auto& d = births[b].density;
    if (d.mean.size() != x_dim || d.cov.rows() != x_dim || d.cov.cols() != x_dim) {
      throw InvalidArgument("birth component " + std::to_string(b) +
                            " has the wrong state dimension");
    }
    const std::string name = "birth component " + std::to_string(b);
    if (!d.mean.allFinite()) throw InvalidArgument(name + " mean contains NaN or inf");
    core::require_covariance(d.cov, name + " cov", true, x_dim);
  }
  const auto& fov = params.field_of_view;
  if (fov.enabled) {
    if (fov.lower.size() != x_dim || fov.upper.size() != x_dim) {
      throw InvalidArgument("field_of_view lower and upper must have " + std::to_string(x_dim) +
                            " components, got " + std::to_string(fov.lower.size()) + " and " +
                            std::to_string(fov.upper.size()));
    }
    if (fov.lower.array().isNaN().any() || fov.upper.array().isNaN().any() ||
        !(fov.lower.array() <= fov.upper.array()).all()) {
      throw InvalidArgument("field_of_view needs lower <= upper in every component (no NaN)");
    }
  }
  const auto& adaptive = params.adaptive_birth;
  if (adaptive.enabled && (adaptive.cov.rows() != x_dim || adaptive.cov.cols() != x_dim)) {
    throw InvalidArgument("adaptive_birth cov must be " + std::to_string(x_dim) + "x" +
                          std::to_string(x_dim) + ", got " + std::to_string(adaptive.cov.rows()) +
                          "x" + std::to_string(adaptive.cov.cols()));
  }
  if (adaptive.enabled) core::require_covariance(adaptive.cov, "adaptive_birth_cov", true, x_dim);
}

void GaussianTracks::log_detection_likelihoods(const Candidate& c,
                                               const Eigen::Ref<const Eigen::MatrixXd>& z,
                                               double gate,
                                               Eigen::Ref<Eigen::RowVectorXd> out) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (Eigen::Index j = 0; j < z.cols(); ++j) {
    const double d2 = c.innovation.mahalanobis_squared(z.col(j));
    out[j] = d2 <= gate ? c.innovation.log_likelihood_at(d2) : -kInf;
  }
}

template class GlmbFilter<GaussianTracks>;

}  // namespace vtrack::filters
