#include "vtrack/filters/particle_glmb.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/filters/glmb_impl.hpp"

namespace vtrack::filters {
namespace {

using core::kInf;

// Lower Cholesky factor of a covariance that must be positive definite; `what` names it.
Eigen::MatrixXd cholesky_of(const Eigen::MatrixXd& cov, const std::string& what) {
  Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (cov + cov.transpose()));
  if (llt.info() != Eigen::Success || !cov.allFinite()) {
    throw InvalidArgument(what + " is not positive definite");
  }
  return llt.matrixL();
}

// The symmetric square root S (S S^T = S^2 = A) of a positive semi-definite A, from its
// eigen-decomposition with negative round-off clamped to zero (A may be singular).
Eigen::MatrixXd symmetric_sqrt(const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eig) {
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() *
         eig.eigenvectors().transpose();
}

}  // namespace

const core::ParameterTable<ParticleParams>& ParticleParams::table() {
  using P = ParticleParams;
  static const auto table =
      core::ParameterTable<P>()
          .add("n_particles", &P::n_particles)
          .add("resample_threshold", &P::resample_threshold)
          .add("regularise", &P::regularise)
          .add("depth_for_births", &P::depth_for_births)
          .add("mask_detections", &P::mask_detections)
          .add("occlusion_margin", &P::occlusion_margin)
          .add("mask_depth_margin", &P::mask_depth_margin)
          .add("track_occluders", &P::track_occluders)
          .add("occluded_detection_probability", &P::occluded_detection_probability);
  return table;
}

void validate(const ParticleParams& p) {
  require(p.n_particles >= 2 && p.n_particles <= core::kMaxParticles, "n_particles", p.n_particles,
          "in [2, 1000000]");
  require(p.occlusion_margin >= 0.0, "occlusion_margin", p.occlusion_margin, ">= 0 (or inf: off)");
  require(p.mask_depth_margin >= 0.0, "mask_depth_margin", p.mask_depth_margin,
          ">= 0 (or inf: the whole footprint)");
  require(p.resample_threshold >= 0.0 && p.resample_threshold <= 1.0, "resample_threshold",
          p.resample_threshold, "in [0, 1]");
}

ParticleTracks::ParticleTracks(ParticleParams params, std::uint64_t seed,
                               const models::LinearGaussianMotion& motion,
                               const models::LinearGaussianObservation& observation,
                               std::optional<models::DepthLikelihood> depth_model)
    : params_(params), depth_model_(std::move(depth_model)), rng_(seed) {
  validate(params_);
  // Q of eq. (7) is singular (rank 3: noise enters through Gamma), so no Cholesky factor: the
  // symmetric square root from the eigen-decomposition, negative round-off clamped to zero.
  const Eigen::MatrixXd Q = 0.5 * (motion.Q + motion.Q.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Q);
  if (eig.info() != Eigen::Success || eig.eigenvalues().minCoeff() < -1e-9 * (1.0 + Q.norm())) {
    throw InvalidArgument("motion Q is not positive semi-definite");
  }
  motion_noise_sqrt_ = symmetric_sqrt(eig);
  noise_llt_.compute(0.5 * (observation.R + observation.R.transpose()));
  if (noise_llt_.info() != Eigen::Success) {
    throw InvalidArgument("observation R is not positive definite");
  }
  const Eigen::MatrixXd L = noise_llt_.matrixL();
  log_g1_normaliser_ = -0.5 * static_cast<double>(L.rows()) * core::kLog2Pi -
                       L.diagonal().array().log().sum();
  if (depth_model_ && observation.H.rows() != 3) {
    throw InvalidArgument("a depth model needs 3-D detections (X, Y, D), got z_dim " +
                          std::to_string(observation.H.rows()));
  }
}

void ParticleTracks::set_depth(const cv::Mat* depth,
                               const Eigen::Ref<const Eigen::MatrixXd>& detections,
                               const std::vector<ReportedTrack>& reported) {
  depth_frame_.reset();
  reported_.clear();
  if (!depth) return;
  if (!depth_model_) throw InvalidArgument("depth given but the tracker has no depth model");
  const bool ordered = std::isfinite(params_.occlusion_margin);
  std::vector<models::Occluder> occluders;
  cv::Mat masked = *depth;
  if (params_.mask_detections && detections.cols() > 0 && detections.rows() == 3) {
    masked = depth->clone();
    for (Eigen::Index j = 0; j < detections.cols(); ++j) {
      const double D = detections(2, j);
      const image::Rect r = depth_model_->footprint(detections(0, j), detections(1, j), D);
      if (r.width == 0 || r.height == 0 || r.x + r.width > masked.cols ||
          r.y + r.height > masked.rows) {
        continue;  // (an image of the wrong size: frame() reports it)
      }
      // Only the pixels the detection can explain: at its depth or behind it. A nearer surface
      // in T(z_j) is in front of the detection (a missed person passing before it) and keeps
      // its depth (mask_depth_margin; +inf blanks the whole footprint).
      cv::Mat footprint = masked(cv::Rect(r.x, r.y, r.width, r.height));
      footprint.setTo(0.0, footprint >= D - params_.mask_depth_margin);
      if (ordered) occluders.push_back({r, D + params_.occlusion_margin});
    }
  }
  if (ordered && params_.track_occluders) {
    for (const ReportedTrack& t : reported) {
      reported_.push_back(t.label);
      const image::Rect r = depth_model_->footprint(t.position.x(), t.position.y(), t.position.z());
      if (r.width > 0 && r.height > 0) {
        occluders.push_back({r, t.position.z() + params_.occlusion_margin, true});
      }
    }
  }
  depth_frame_ = depth_model_->frame(masked);
  depth_frame_->occluders = std::move(occluders);
}

const Eigen::MatrixXd& ParticleTracks::normal_draws(Eigen::Index n, Eigen::Index d) {
  noise_.resize(d, n);
  rng_.fill_normal(noise_.data(), static_cast<std::size_t>(noise_.size()));
  noise_rows_ = noise_.transpose();
  return noise_rows_;
}

ParticleDensity ParticleTracks::predict(const Density& prior,
                                        const models::LinearGaussianMotion& motion) {
  // x_p' = F x_p + S v_p for every row x_p^T: X' = X F^T + V S^T (S is symmetric).
  const Eigen::MatrixXd& noise = normal_draws(prior.size(), prior.dim());
  Density out = prior;
  out.states().noalias() = prior.states() * motion.F.transpose();
  out.states().noalias() += noise * motion_noise_sqrt_;
  return out;
}

ParticleDensity ParticleTracks::birth(const models::GaussianDensity& density) {
  const Eigen::MatrixXd L = cholesky_of(density.cov, "birth covariance");
  Eigen::MatrixXd states = normal_draws(params_.n_particles, density.mean.size()) * L.transpose();
  states.rowwise() += density.mean.transpose();
  return Density(std::move(states));
}

ParticleTracks::Candidate ParticleTracks::candidate(
    Density predicted, const models::LinearGaussianObservation& observation,
    const TrackLabel& label, bool is_birth) {
  Eigen::MatrixXd z = observation.H * predicted.states().transpose();
  // The Gaussian moment match only gates (it is never used for weights); its covariance is
  // positive definite because Sigma is.
  models::KalmanInnovation gate(moments(predicted), observation);
  Candidate c{std::move(predicted), std::move(gate), std::move(z), {}, 0.0, {}};
  if (depth_frame_ && (!is_birth || params_.depth_for_births)) {
    c.depth_log_ratio.resize(c.predicted.size());
    Eigen::VectorXd visible;
    const bool reported = !is_birth && std::find(reported_.begin(), reported_.end(), label) !=
                                           reported_.end();
    depth_model_->log_ratio(*depth_frame_, c.predicted_z, c.depth_log_ratio, &visible, reported);
    if (params_.occluded_detection_probability && visible.minCoeff() < 1.0) {
      // Eq. (8) with p_D(x) = p_D v(x): the detected branch gains log v(x) per particle, the
      // missed branch log((1 - p_D v(x)) / (1 - p_D)) (the engine adds log(1 - p_D)).
      const double pd = detection_probability_;
      c.log_visible = visible.array().log();
      c.depth_log_ratio.array() +=
          ((1.0 - pd * visible.array()) / (1.0 - pd)).log();
    }
    // log eta_depth = log sum_p w_p g2(d|x_p) / prod_all varphi (the common product cancels).
    c.log_eta_depth = core::log_sum_exp(c.predicted.log_weights() + c.depth_log_ratio);
  }
  return c;
}

void ParticleTracks::log_g1(const Candidate& c, const Eigen::Ref<const Eigen::VectorXd>& z,
                            Eigen::VectorXd& out) const {
  // Whitened residuals L^{-1} (z - H x_p) for all particles at once: one triangular solve on a
  // z_dim x N block, then column norms (contiguous, vectorised by Eigen).
  Eigen::MatrixXd white = (-c.predicted_z).colwise() + z;
  noise_llt_.matrixL().solveInPlace(white);
  out = log_g1_normaliser_ - 0.5 * white.colwise().squaredNorm().transpose().array();
}

void ParticleTracks::log_detection_likelihoods(const Candidate& c,
                                               const Eigen::Ref<const Eigen::MatrixXd>& z,
                                               double gate,
                                               Eigen::Ref<Eigen::RowVectorXd> out) const {
  // eta = sum_p w_p g1(z|x_p) (eq. 2 under the particle density), p_D(x) / p_D included.
  gated_log_likelihoods(c, c.predicted.log_weights(), c.log_visible, z, gate, out);
}

void ParticleTracks::log_missed_likelihoods(const Candidate& c,
                                            const Eigen::Ref<const Eigen::MatrixXd>& z,
                                            double gate, Eigen::Ref<Eigen::RowVectorXd> out) const {
  // The missed branch's posterior weights, w_p g2(d|x_p) / eta_depth (missed() without
  // resampling); where the track would be, not whether it is visible.
  if (c.depth_log_ratio.size() == 0) {
    gated_log_likelihoods(c, c.predicted.log_weights(), {}, z, gate, out);
    return;
  }
  const Eigen::VectorXd log_w =
      (c.predicted.log_weights() + c.depth_log_ratio).array() - c.log_eta_depth;
  gated_log_likelihoods(c, log_w, {}, z, gate, out);
}

void ParticleTracks::gated_log_likelihoods(const Candidate& c, const Eigen::VectorXd& log_w,
                                           const Eigen::VectorXd& log_extra,
                                           const Eigen::Ref<const Eigen::MatrixXd>& z,
                                           double gate, Eigen::Ref<Eigen::RowVectorXd> out) const {
  Eigen::VectorXd lg;
  for (Eigen::Index j = 0; j < z.cols(); ++j) {
    if (c.gate.mahalanobis_squared(z.col(j)) > gate) {
      out[j] = -kInf;
      continue;
    }
    log_g1(c, z.col(j), lg);
    if (log_extra.size() > 0) lg += log_extra;
    out[j] = core::log_sum_exp(log_w + lg);
  }
}

ParticleDensity ParticleTracks::reweight(const Density& prior, const Eigen::VectorXd& log_lik) {
  Density out = prior;
  if (!out.reweight(log_lik).updated()) {
    // No particle explains the data (all weights underflowed in the log domain): keep the prior
    // rather than produce NaN. The hypothesis weight already carries the evidence.
    return prior;
  }
  const Eigen::Index n = out.size();
  if (out.ess() < params_.resample_threshold * static_cast<double>(n)) {
    if (!params_.regularise) {
      out.resample(core::ResamplingScheme::Systematic, n, rng_);
      return out;
    }
    const Eigen::VectorXd mean = out.mean();
    const Eigen::MatrixXd cov = out.covariance();
    out.resample(core::ResamplingScheme::Systematic, n, rng_);
    regularise(out, mean, cov);
  }
  return out;
}

void ParticleTracks::regularise(Density& d, const Eigen::VectorXd& mean,
                                const Eigen::MatrixXd& cov) {
  // Silverman's bandwidth for a Gaussian kernel in d dimensions (Musso, Oudjane & Le Gland 2001,
  // the regularised particle filter), and Liu & West's (2001) shrinkage a = sqrt(1 - h^2): the
  // kernel density a x_i + (1 - a) m + h L e has the mean m and the covariance
  // a^2 P + h^2 P = P of the weighted particles, not P (1 + h^2).
  const auto n = static_cast<double>(d.size());
  const auto dim = static_cast<double>(d.dim());
  const double h = std::pow(4.0 / (n * (dim + 2.0)), 1.0 / (dim + 4.0));
  const double a = std::sqrt(1.0 - h * h);
  // P may be singular (a collapsed cloud, or a state component no particle varies in).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (cov + cov.transpose()));
  const Eigen::MatrixXd root = symmetric_sqrt(eig);
  const Eigen::MatrixXd& noise = normal_draws(d.size(), d.dim());
  Eigen::MatrixXd& x = d.states();
  x *= a;
  x.rowwise() += ((1.0 - a) * mean).transpose();
  x.noalias() += h * noise * root;  // root is symmetric: rows e_i^T root = (root e_i)^T
}

ParticleDensity ParticleTracks::detected(const Candidate& c,
                                         const Eigen::Ref<const Eigen::VectorXd>& z) {
  log_g1(c, z, scratch_);
  if (c.log_visible.size() > 0) scratch_ += c.log_visible;
  return reweight(c.predicted, scratch_);
}

ParticleDensity ParticleTracks::missed(const Candidate& c) {
  if (c.depth_log_ratio.size() == 0) return c.predicted;  // detection-only: psi = 1 - p_D
  return reweight(c.predicted, c.depth_log_ratio);
}

models::GaussianDensity ParticleTracks::moments(const Density& d) {
  return {d.mean(), d.covariance()};
}

ParticleGlmbFilter::ParticleGlmbFilter(models::LinearGaussianMotion motion,
                                       models::LinearGaussianObservation observation,
                                       std::vector<GaussianBirth> births, GlmbParams params,
                                       ParticleParams particle_params,
                                       std::optional<models::DepthLikelihood> depth_model)
    : GlmbFilter<ParticleTracks>(
          motion, observation, births, params,
          ParticleTracks(particle_params, params.seed, motion, observation,
                         std::move(depth_model))) {
  // Birth covariances are sampled through their Cholesky factor: check them now, not mid-step.
  for (std::size_t b = 0; b < births.size(); ++b) {
    cholesky_of(births[b].density.cov, "birth covariance " + std::to_string(b));
  }
  if (params.adaptive_birth.enabled) cholesky_of(params.adaptive_birth.cov, "adaptive_birth cov");
  tracks_model_.set_detection_probability(params.detection_probability);
}

void ParticleGlmbFilter::step(const Eigen::Ref<const Eigen::MatrixXd>& detections,
                              const cv::Mat* depth, const ScanInput& input) {
  // The previous report, predicted to this scan: the tracks that may occlude newer ones.
  std::vector<ParticleTracks::ReportedTrack> reported;
  if (depth && particle_params().track_occluders) {
    for (const GlmbEstimate& e : estimates()) {
      const Eigen::VectorXd predicted = motion().F * e.mean;
      reported.push_back({e.label, {predicted[0], predicted[2], predicted[4]}});
    }
  }
  tracks_model_.set_depth(depth, detections, reported);
  GlmbFilter<ParticleTracks>::step(detections, input);
  tracks_model_.set_depth(nullptr, detections);
}

template class GlmbFilter<ParticleTracks>;

}  // namespace vtrack::filters
