#pragma once
// The delta-GLMB filter with particle track densities and the switching observation model of
// rgbd-glmb-switching-observation.txt ("we implement the generalized labeled multi-Bernoulli
// recursion equations based on particle approximation"). The hypothesis machinery is
// GlmbFilter's (filters/glmb.hpp); this file supplies the density policy.
//
// Track density: a weighted particle set {w_p, x_p} of the SMC engine (smc::ParticleSet: one
// particle per row, normalised log weights; its reweight gives log eta, its resample the scheme).
// Prediction: x_p' = F x_p + v_p, v_p ~ N(0, Q) (eq. 7's linear-Gaussian motion, sampled with the
// filter's own seeded engine: the same seed gives the same tracks).
// Update, the switching psi of eq. (8) (the display after eq. 8):
//   detected by z (theta(l) > 0):  psi = p_D g1(z|x) / kappa(z), g1 = N(z; H x, Sigma) (eq. 2);
//     eta = sum_p w_p g1(z|x_p), posterior weights w_p g1(z|x_p) / eta.
//   missed (theta(l) = 0):         psi = (1 - p_D) g2(d|x) / g2(d|no target),
//     g2 the depth likelihood of eq. (4) (models/depth_likelihood.hpp); eta_depth =
//     sum_p w_p g2(d|x_p)/prod_all varphi, posterior weights w_p g2(d|x_p) / eta_depth.
//   Without a depth image (or without a depth model) the missed factor is (1 - p_D), the usual
//   detection-only GLMB: the particles are only predicted.
// Our reading of the paper's missed branch. As printed it is
// (1 - p_D) p_D g2(d) / kappa(z_theta(l)) with theta(l) = 0, which divides by the clutter intensity
// of a detection that does not exist (z_0) and multiplies by p_D in the branch where the target
// was not detected: a typo. In the detected branch g1/kappa is the ratio of "z came from the
// target" to "z came from clutter"; the consistent missed-branch analogue is the ratio of the
// depth image's likelihood with the target at x to its likelihood without it, g2(d|x) /
// prod_i varphi_i(d_i) = prod_{i in T(x)} phi_i / varphi_i, times the probability (1 - p_D) of the
// miss. That is what this filter computes (tempered, see depth_likelihood.hpp).
//
// Detected pixels: our one deviation from the paper. Eq. (4) is a separable likelihood: it
// assumes the footprints of different targets do not overlap, so nothing in it stops a second
// track (a duplicate, or a birth) from explaining the depth pixels of a person who is already
// tracked -- once born it lives on the depth image alone. Measured on vtrack.rgbd
// (benchmarks/rgbd_switching.py --ablations, 5 seeds): with eq. (4) on the raw depth image the
// median cardinality error is 9.8 (5.5 if births are scored without depth; detection-only 0.7),
// with 7x the label switches. The remedy
// the switching idea itself suggests ("the depth image is used when the detector misses"): before
// scoring the missed branches, the footprints T(z_j) of this scan's detections are set to 0 in
// the depth image (ParticleParams::mask_detections, on by default). A detected person is
// explained by whichever track takes the detection; a second track on them then finds an empty
// footprint and dies, while a track whose person the detector missed keeps its depth evidence
// (cardinality error 0.39). The cost: a clutter detection that falls on a missed person hides
// them for one scan, and a person the detector misses is not masked, so duplicates born during a
// burst survive until the next detection.
//
// Occlusion ordering (ParticleParams::occlusion_margin): the blanked footprint of a detection
// hides what is behind it, so its pixels are left out of the depth score of farther states
// (models::Occluder) rather than counted as empty background. Diagnosis behind it
// (benchmarks/rgbd_switching.py, seeds 0-4, per event): without it, 46 of the 86 fragmentations
// were one-frame drop-outs of a track with the same label, and 28 of the 76 label switches a
// re-birth after a burst, nearly all while the person's footprint overlapped another's in the
// image -- a missed person passing behind a detected one lost the blanked pixels as evidence
// against them. Measured (totals over seeds 0-4 | 5-9; OSPA, IDF1, coverage: medians):
//   occlusion_margin  OSPA           frag.     switches  IDF1           burst cov.
//   off (inf)         0.171 | 0.184  86 | 74   76 | 82   0.600 | 0.607  0.64 | 0.56
//   0.3 (default)     0.152 | 0.155  40 | 42   99 | 90   0.659 | 0.688  0.72 | 0.70
//   0.15, 0.6, 1.2    seeds 0-4: switches 85, 67, 131; frag. 33, 40, 62
// The switch count moves more between margins than between on and off (a few crossings where
// the estimate alternates between two labels dominate it), so the margin is not tuned on it:
// 0.3 m = 3 sigma of the detections' depth noise.
//
// Births take the depth factor too, as eq. (8)'s psi applies to every label
// (ParticleParams::depth_for_births). Scoring them by (1 - p_D) alone was measured as an option
// (benchmarks/rgbd_switching.py's docstring): fewer label switches on the seeds it was chosen on,
// more on the ten seeds after them, so the default stays the paper's.

// Regularised resampling (ParticleParams::regularise). Diagnosis (benchmarks/rgbd_switching.py,
// seeds 0-9, per event): most label switches the switching filter has and the Gaussian (Kalman)
// filter has not are a new label born on a person whose track is still reported, the new one
// taking over within a frame. The old track had not lost the person to the depth image: its
// particle cloud had collapsed. Eq. (7)'s process noise enters only through the acceleration
// (position noise dt^2/2 sigma_v = 0.8 mm per scan at 30 Hz), so after a few resamplings the
// particles share one ancestor's velocity; a wrong one (seen: vD +0.7 m/s on a person walking at
// -0.3 m/s) carries the whole cloud off the person at a few cm per scan, every particle alike, so
// the detections cannot pull it back, and a birth on the detection soon explains them better
// than the track (p_S g1 falls below r_B g1 of the newborn). With 3000 particles the same track
// follows the person. The regularised particle filter replaces the resampled empirical measure
// by a kernel density: each resampled particle is moved by a Gaussian kernel whose covariance is
// h^2 times the posterior's, with Liu & West's (2001) shrinkage of the locations towards the mean
// so that mean and covariance are unchanged; the cloud keeps the spread the posterior has
// instead of the spread of its few surviving ancestors.
//
// Gating uses the moment-matched Gaussian of the predicted particles: a detection enters a row
// only if its squared Mahalanobis distance under N(H m, H P H^T + Sigma) is within the gate.
// Resampling: systematic (core/resampling.hpp, through smc::ParticleSet::resample), after an
// update whose effective sample size falls below resample_threshold x particles.
#include <optional>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/core/random.hpp"
#include "vtrack/filters/glmb.hpp"
#include "vtrack/models/depth_likelihood.hpp"
#include "vtrack/smc/particle_set.hpp"

namespace vtrack::filters {

using ParticleDensity = smc::ParticleSet<double>;

struct ParticleParams {
  int n_particles = 500;  // particles per track, <= core::kMaxParticles (births sampled with as many)
  double resample_threshold = 0.5;  // resample when N_eff < resample_threshold * n_particles
  // Regularised resampling (see "Regularised resampling" in the header comment): after each
  // resampling the particles are moved by the Gaussian kernel of Liu & West (2001) with
  // location shrinkage, x_i <- a x_i + (1 - a) m + h L e_i, a = sqrt(1 - h^2), L L^T the
  // weighted covariance before resampling and h Silverman's optimal bandwidth
  // (4 / (N (d + 2)))^(1 / (d + 4)) (Musso, Oudjane & Le Gland 2001). false: plain resampling.
  bool regularise = true;
  // Whether birth rows take the depth factor in their missed branch too (eq. 8's psi applies to
  // every label); false scores a birth's missed branch by (1 - p_D) alone (a birth its detection
  // did not follow then cannot survive on the depth pixels of a person another track carries).
  bool depth_for_births = true;
  // Whether the footprints T(z_j) of this scan's detections are blanked (set to 0) in the depth
  // image before the missed branches are scored. See the header comment; false = eq. (4) on the
  // raw depth image, as the paper.
  bool mask_detections = true;
  // Occlusion ordering (with mask_detections): a detection's footprint T(z_j) hides everything
  // farther than its depth D_j + occlusion_margin (m), so those pixels are left out of a farther
  // state's eq. (4) product instead of counting as empty background (models::Occluder). Without
  // it, a missed person walking behind a detected one loses the blanked pixels as evidence
  // against them and their track dies (or drops out for a frame). The margin is 3 sigma of the
  // detections' depth noise (eq. 2's Sigma, 0.1 m in vtrack.rgbd): a duplicate track on the
  // detected person is not "behind" them and still finds an empty footprint. +inf disables.
  double occlusion_margin = 0.3;
  // Which pixels of a detection's footprint T(z_j) mask_detections blanks: those with depth
  // d >= D_j - mask_depth_margin (m), i.e. the detection's own depth and what it hides. A pixel
  // nearer than that belongs to a surface in front of the detection, which the detection does not
  // explain: a missed person walking in front of a detected one (or in front of a clutter
  // detection's large near-depth footprint) keeps those pixels as evidence. +inf blanks the whole
  // footprint (the behaviour before this option). Why: followed event by event
  // (benchmarks/rgbd_switching.py, seeds 15-16), re-births after a burst were tracks that died
  // in the burst a few cm from their person; four of seven followed scored +4.5 to +7.4 nats at
  // the person on the unmasked image: a detection of someone just behind them had blanked their
  // pixels, which then voted "background". The margin is occlusion_margin's (3 sigma of the detections'
  // depth noise), not tuned. Measured on seeds 0-24 (totals, switching filter): bursts kept 146 ->
  // 179, fragmentations 175 -> 128, label switches 187 -> 183; OSPA(2) better on three of the
  // five seed sets (0.739 -> 0.674 on 0-4), worse on 15-19 (0.774 -> 0.779) and 20-24 (0.734 ->
  // 0.771); margins 0.15 / 0.6 on seeds 0-4 and 15-19 gave 23 / 22 and 84 / 60 switches (0.3:
  // 25, 62).
  double mask_depth_margin = 0.3;
  // Tracks as occluders (with occlusion_margin finite): the footprint of every track reported at
  // the previous scan, at its predicted mean, hides what lies more than occlusion_margin behind
  // it from the tracks that report does not hold (births, tracks not or no longer reported), as
  // a detection's footprint hides what lies behind the detection. Why: eq. (4) is separable, so
  // a track behind a person the detector missed scores that person's pixels as its own (short
  // false labels of clutter-born tracks behind a missed person). Reported tracks are not hidden
  // by one another (a person behind a tracked one would lose the nearer person's pixels as
  // support). Off by default: it removes those false labels but raised the label switches over
  // the benchmark's seed sets (benchmarks/rgbd_switching.py's docstring has the figures).
  bool track_occluders = false;
  // State-dependent p_D (eq. 8's psi has p_D,k(x, l)): with occluders, p_D(x) = p_D v(x), v(x)
  // the visible fraction of T(x). A person fully hidden behind a detected one cannot be detected,
  // so their missed branch costs (1 - p_D v) ~ 1 instead of (1 - p_D), and their track is not
  // killed in a few scans by the detector's silence while its pixels say nothing either.
  // Off by default: measured (benchmarks/rgbd_switching.py, seeds 0-9), it keeps more bursts
  // (65 kept / 46 relabelled vs 61 / 50) but a track hidden behind a detected person then costs
  // nothing, so duplicates live there: cardinality error 2.6 (vs 0.33), OSPA 0.39 (vs 0.155),
  // label switches 210 (vs 189).
  bool occluded_detection_probability = false;

  static const core::ParameterTable<ParticleParams>& table();
};

// InvalidArgument naming the parameter and its value.
void validate(const ParticleParams& params);

class ParticleTracks {
 public:
  using Density = ParticleDensity;
  struct Candidate {
    Density predicted;
    models::KalmanInnovation gate;  // of the moment-matched Gaussian, for gating only
    Eigen::MatrixXd predicted_z;    // H x_p, z_dim x N (one particle per column, as detections)
    // Per-particle tempered depth log ratio (empty without a depth image) and log eta_depth.
    Eigen::VectorXd depth_log_ratio;
    double log_eta_depth = 0.0;
    // Per-particle log v(x) (log p_D(x) / p_D, see occluded_detection_probability); empty when
    // every particle is fully visible.
    Eigen::VectorXd log_visible;
  };

  // `seed` seeds the densities' random engine (the filter's GlmbParams::seed).
  ParticleTracks(ParticleParams params, std::uint64_t seed,
                 const models::LinearGaussianMotion& motion,
                 const models::LinearGaussianObservation& observation,
                 std::optional<models::DepthLikelihood> depth_model);

  // A track reported at the previous scan: its label and predicted position (X, Y, D).
  struct ReportedTrack {
    TrackLabel label;
    Eigen::Vector3d position;
  };
  // The depth image of the next step (nullptr: none), that step's detections (z_dim x M) and the
  // tracks reported at the step before (occluders with ParticleParams::track_occluders). The
  // image is checked against the depth model.
  void set_depth(const cv::Mat* depth, const Eigen::Ref<const Eigen::MatrixXd>& detections,
                 const std::vector<ReportedTrack>& reported = {});
  bool has_depth_model() const { return depth_model_.has_value(); }
  const ParticleParams& params() const { return params_; }
  // The filter's p_D, for the state-dependent p_D(x) = p_D v(x) of occluded states.
  void set_detection_probability(double p_d) { detection_probability_ = p_d; }

  Density predict(const Density& prior, const models::LinearGaussianMotion& motion);
  Density birth(const models::GaussianDensity& density);
  Candidate candidate(Density predicted, const models::LinearGaussianObservation& observation,
                      const TrackLabel& label, bool is_birth);
  void log_detection_likelihoods(const Candidate& c, const Eigen::Ref<const Eigen::MatrixXd>& z,
                                 double gate, Eigen::Ref<Eigen::RowVectorXd> out) const;
  // log g1(z_j | missed density) for every detection j (-inf outside the gate): eq. (2) under the
  // particles reweighted by the depth likelihood (the density a missed track carries on with),
  // for the adaptive birth's r_U (AdaptiveBirthParams::missed_tracks).
  void log_missed_likelihoods(const Candidate& c, const Eigen::Ref<const Eigen::MatrixXd>& z,
                              double gate, Eigen::Ref<Eigen::RowVectorXd> out) const;
  double log_missed_likelihood(const Candidate& c) const { return c.log_eta_depth; }
  Density detected(const Candidate& c, const Eigen::Ref<const Eigen::VectorXd>& z);
  Density missed(const Candidate& c);
  // Weighted mean and covariance.
  static models::GaussianDensity moments(const Density& d);

 private:
  // log g1(z | x_p) for every particle (eq. 2), from the candidate's H x_p.
  void log_g1(const Candidate& c, const Eigen::Ref<const Eigen::VectorXd>& z,
              Eigen::VectorXd& out) const;
  // log sum_p exp(log_w_p + log_extra_p) g1(z_j|x_p) per detection (-inf outside the gate of the
  // moment-matched Gaussian); log_extra may be empty.
  void gated_log_likelihoods(const Candidate& c, const Eigen::VectorXd& log_w,
                             const Eigen::VectorXd& log_extra,
                             const Eigen::Ref<const Eigen::MatrixXd>& z, double gate,
                             Eigen::Ref<Eigen::RowVectorXd> out) const;
  // Adds log_lik to the weights, renormalises, and resamples when N_eff is low (regularised
  // with ParticleParams::regularise).
  Density reweight(const Density& prior, const Eigen::VectorXd& log_lik);
  // Moves the resampled particles of `d` by the shrunk Gaussian kernel of the weighted mean
  // `mean` and covariance `cov` they were resampled from (ParticleParams::regularise).
  void regularise(Density& d, const Eigen::VectorXd& mean, const Eigen::MatrixXd& cov);
  // n x d standard normal draws, filled particle by particle (as the d x n layout this filter had
  // before the engine: the same seed gives the same particles).
  const Eigen::MatrixXd& normal_draws(Eigen::Index n, Eigen::Index d);

  ParticleParams params_;
  Eigen::MatrixXd motion_noise_sqrt_;      // S with S S^T = Q (Q may be singular, as eq. 7's)
  Eigen::LLT<Eigen::MatrixXd> noise_llt_;  // of Sigma (eq. 2's R)
  double log_g1_normaliser_ = 0.0;         // -z_dim/2 log 2pi - 1/2 log|Sigma|
  std::optional<models::DepthLikelihood> depth_model_;
  std::optional<models::DepthFrame> depth_frame_;
  std::vector<TrackLabel> reported_;  // the labels of set_depth's reported tracks
  double detection_probability_ = 0.0;
  core::Rng rng_;
  Eigen::MatrixXd noise_;  // scratch for the normal draws (d x n) and their transpose (n x d)
  Eigen::MatrixXd noise_rows_;
  Eigen::VectorXd scratch_;
};

extern template class GlmbFilter<ParticleTracks>;

// The particle delta-GLMB with the switching observation model; with no depth model (or no depth
// image at a step) it is the detection-only particle GLMB.
class ParticleGlmbFilter : public GlmbFilter<ParticleTracks> {
 public:
  ParticleGlmbFilter(models::LinearGaussianMotion motion,
                     models::LinearGaussianObservation observation,
                     std::vector<GaussianBirth> births, GlmbParams params = {},
                     ParticleParams particle_params = {},
                     std::optional<models::DepthLikelihood> depth_model = std::nullopt);

  // One joint prediction-update with the detections (z_dim x M) and, optionally, the
  // background-subtracted metric depth image of the same scan (needs a depth model; its size).
  void step(const Eigen::Ref<const Eigen::MatrixXd>& detections, const cv::Mat* depth = nullptr,
            const ScanInput& input = {});
  const ParticleParams& particle_params() const { return tracks_model_.params(); }
  bool has_depth_model() const { return tracks_model_.has_depth_model(); }
};

}  // namespace vtrack::filters
