#pragma once
// The delta-GLMB filter (labelled random finite sets) with Gaussian track densities, in the joint
// prediction-update form of Vo, Vo & Hoang (2017), "An efficient implementation of the generalized
// labeled multi-Bernoulli filter", IEEE TSP 65(8), with the ranked assignments of Murty's method
// (rgbd-glmb-switching-observation.txt eqs. 5-8 and the references there).
//
// Why the joint form: predicting every hypothesis first and updating it next enumerates survival
// sets that the data then rule out; solving one ranked assignment per prior hypothesis over the
// rows {its tracks, the birth components} and the columns {detections, missed, dead/not born}
// gives the posterior hypotheses directly, each with its exact weight.
//
// Labels are l = (birth time k, birth component index i) as in the paper. A track's density is
// kept per association history: one Gaussian (GaussianTracks, the Kalman recursion of
// models/linear_gaussian.hpp) or a weighted particle set (ParticleTracks, filters/particle_glmb.hpp,
// with the paper's switching observation model).
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/parameters.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/filters/assign.hpp"
#include "vtrack/models/linear_gaussian.hpp"

namespace vtrack::filters {

struct TrackLabel {
  int birth_time = 0;   // k at which the track was born (scans count from 1)
  int birth_index = 0;  // index of the birth component that produced it
  bool operator==(const TrackLabel& o) const {
    return birth_time == o.birth_time && birth_index == o.birth_index;
  }
};

// One component of a labelled multi-Bernoulli birth model: a target is born from it at each scan
// with probability `existence`, its state distributed as `density`.
struct GaussianBirth {
  double existence = 0.03;
  models::GaussianDensity density;
};

// Measurement-driven birth, as the adaptive birth of the LMB filter (Reuter, Vo, Vo & Dietmayer
// 2014, "The labeled multi-Bernoulli filter", IEEE TSP 62(12), adaptive birth): every detection of
// scan k-1 proposes a Bernoulli birth at scan k with existence
//   r_B(z) = min(max_existence, expected_births (1 - r_U(z)) / sum_z' (1 - r_U(z'))),
// where r_U(z) is the posterior probability that z was assigned to a track at scan k-1, so
// detections that tracks explain propose (almost) nothing. The birth density is Gaussian, centred
// on the state H^+ z (the least-norm state that predicts z exactly: zero velocity for a
// position observation) with covariance `cov`. Fixed births (GaussianBirth) still apply.
//
// A caller may weight the detections (ScanInput::birth_weight, b_j >= 0, e.g. the likelihood ratio
// of a detection's score): r_B(z_j) = min(max_existence, expected_births (1 - r_U(z_j)) b_j /
// sum_z' (1 - r_U(z')) b_z'), so that births go to detections that are both unexplained and
// target-like. At most max_births detections propose a birth per scan (the largest r_B): a scan
// with tens of thousands of boxes then adds a bounded number of rows to the next assignment.
//
// Detections that missed tracks explain (`missed_tracks`, off by default): r_U(z_j) also counts the
// hypotheses in which z_j went to clutter while a track that was missed at the same scan lies on
// it -- in the switching model a track carried by the depth image through a burst of missed
// detections (filters/particle_glmb.hpp). Per hypothesis I (weight w_I) with z_j unassigned,
//   P(z_j explained | I) = 1 - prod_{t in I missed} (1 - q_tj),
//   q_tj = p_D g(z_j | p_t) / (kappa(z_j) + p_D g(z_j | p_t)),
// p_t the track's posterior density after the miss (the depth-updated one in the switching
// model), q_tj the probability that z_j is that track's detection rather than clutter were the
// track detected. Then r_U(z_j) = P(z_j assigned) + sum_I w_I 1(z_j unassigned in I)
// P(z_j explained | I). Without it a person whom a missed (depth-carried) track already explains
// proposes a birth at every scan with full weight, and the newborn competes for the person's next
// detection under a new label.
struct AdaptiveBirthParams {
  bool enabled = false;
  // r_U counts detections that missed tracks explain (above). Off: on the RGB-D benchmark
  // (benchmarks/rgbd_switching.py) it left label switches unchanged and OSPA(2) worse, on the
  // seeds it was developed on and on held-out seeds alike.
  bool missed_tracks = false;
  double expected_births = 0.1;  // lambda_B: expected number of adaptive births per scan
  double max_existence = 0.03;   // r_B,max: cap on one detection's birth existence
  int max_births = 100;          // cap on the number of adaptive births proposed per scan
  Eigen::MatrixXd cov;           // x_dim x x_dim; must be given when enabled

  // adaptive_birth_rate (expected_births), adaptive_birth_max_existence, adaptive_birth_max,
  // adaptive_birth_missed_tracks (missed_tracks);
  // `enabled` and `cov` come with the covariance matrix, a model argument rather than a
  // parameter.
  static const core::ParameterTable<AdaptiveBirthParams>& table();
};

// Runs of missed detections (occlusion), the state-dependent p_D,k(x, l) of eq. (8) with a hidden
// visibility mode per track: a visible track turns undetectable with probability `rate` per scan
// and an undetectable one becomes visible again with probability 1 / `length` (a Markov chain, so
// runs of misses last `length` scans on average); p_D is the usual one while visible and 0 while
// undetectable. Each track carries o = P(undetectable), predicted as
//   o' = o (1 - 1/length) + (1 - o) rate,
// and eq. (8)'s factors become p_D (1 - o') g(z|x) / kappa(z) for a detection (posterior o = 0) and
// o' + (1 - o') (1 - p_D) for a miss (posterior o = o' / that). After a few misses in a row o is
// near 1, a further miss costs -log(1 - 1/length) instead of -log(1 - p_D), and the track coasts
// through the run instead of dying and being re-born under a new label; a track that is missed
// once in a while (o small) is scored as before. rate = 0 (the default) is the constant p_D.
//
// Runs last at most max_length scans: a track missed that many scans in a row (its association
// history says so) is detectable again (o' = 0), so further misses cost -log(1 - p_D) and it dies
// unless re-detected. Without the bound a false track coasts on for as long as the truncated
// hypotheses keep no alternative in which it died: measured on all of PETS09's ACF boxes, a
// track born on a static false box (two frames) was reported for 118 frames with existence 1.
struct OcclusionParams {
  double rate = 0.0;      // per-scan probability that a detectable track starts a run of misses
  double length = 10.0;   // mean length of a run, scans (>= 1)
  int max_length = 1000;  // longest run, scans (>= 1)

  // occlusion_rate, occlusion_length, occlusion_max_length.
  static const core::ParameterTable<OcclusionParams>& table();
};

// Which hypothesis the estimates are read from.
enum class LabelEstimator {
  // The most probable hypothesis among those with the MAP cardinality (the usual delta-GLMB
  // estimator, Vo & Vo 2013), afresh at every scan.
  map,
  // A joint MAP of the reported label set with the previous report: among the posterior
  // hypotheses I, the one maximising
  //   log w(I) + keep_bonus |I ∩ R| - entry_penalty |I \ R|,
  // R the labels reported at the previous scan. It is the MAP estimate under a Markov prior on
  // the reported set that makes keeping a label e^keep_bonus times likelier than dropping it and
  // a new label e^entry_penalty times less likely than not reporting it. For one independent
  // label of existence r: a reported label stays while r > 1 / (1 + e^keep_bonus), a new one
  // enters once r > 1 / (1 + e^-entry_penalty) -- hysteresis on the existence, so the estimate no
  // longer flips between two labels that explain one person with similar weights, and a label
  // born on one false detection (r below the entry level) is not reported.
  consistent,
};

struct EstimatorParams {
  // The consistent estimator by default: measured better on the standard scenario (OSPA 11.46 /
  // 11.66 mean of ten draws vs 11.63 / 11.77, benchmarks/glmb_standard.py) and on the RGB-D scene
  // (benchmarks/rgbd_switching.py); the box tracker keeps "map" (apps/track_detections.hpp).
  LabelEstimator estimator = LabelEstimator::consistent;
  double keep_bonus = 2.0;     // nats (consistent estimator)
  double entry_penalty = 0.0;  // nats (consistent estimator)
  // Duplicate suppression (either estimator): of two tracks of the chosen hypothesis whose
  // predicted detections coincide -- squared Mahalanobis distance
  //   (H m_a - H m_b)^T (H P_a H^T + H P_b H^T)^-1 (H m_a - H m_b) <= duplicate_gate
  // -- only the older label (earlier birth, eq. 5's l = (t, i)) is reported. Why: eq. (4)'s
  // separable depth likelihood lets two tracks explain one person's pixels at once, so through a
  // burst of missed detections a track born on a tracked person lives beside it (both exist
  // with probability ~1) and the report holds both labels on one person, which an evaluation
  // pairs with the person alternately. 0 disables.
  double duplicate_gate = 0.0;

  // label_estimator "map" | "consistent", label_keep_bonus, label_entry_penalty,
  // label_duplicate_gate.
  static const core::ParameterTable<EstimatorParams>& table();
};

// How each prior hypothesis's posterior hypotheses are generated from its cost matrix.
enum class HypothesisRanking {
  // Murty's k best assignments (exact ranking; the paper's choice, the default).
  murty,
  // The Gibbs sampler of Vo, Vo & Hoang (2017) section IV-B (assign::gibbs_assignments): as many
  // sweeps as hypotheses requested, the distinct assignments visited kept with their exact
  // weights. Cheaper per hypothesis for large problems, random (seeded by GlmbParams::seed).
  gibbs,
};

// State-dependent survival and detection probabilities, the paper's p_S,k(x, l) (eq. 6) and
// p_D,k(x, l) (eq. 8), in their simplest useful form: a field of view. Inside the axis-aligned box
// lower <= x <= upper of state space the constant GlmbParams p_S and p_D apply; outside it
// `outside_survival_probability` and `outside_detection_probability` do (use -inf / +inf bounds
// for unconstrained components, e.g. velocities).
//
// Why: with a constant p_S a track that has left the surveillance region keeps "alive and missed"
// (cost -log p_S (1 - p_D)) cheaper per scan than "dead" (-log (1 - p_S)) whenever
// p_S > 1 / (2 - p_D), so it can fly off for ever once the hypotheses where it died earlier are truncated. A small p_S
// outside makes death the best assignment there; a small p_D outside says a target leaving the
// view is not expected to be detected, so missing it is no evidence against its existence.
//
// The integrals of eqs. 6 and 8, eta_S(l) = <p_S(., l), p(., l)> over the prior density and
// <p_D(., l), p(., l)> over the predicted one, are approximated by p_S and p_D at the densities'
// means (exact away from the border, where a track spends one or two scans). Disabled (the
// default), the filter computes exactly what it did with constant probabilities.
struct FieldOfView {
  bool enabled = false;
  Eigen::VectorXd lower, upper;  // x_dim each, lower <= upper
  double outside_survival_probability = 0.1;   // p_S(x) for x outside (eq. 6)
  double outside_detection_probability = 0.1;  // p_D(x) for x outside (eq. 8)
  // True when x lies in the box (bounds included).
  bool contains(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    return (x.array() >= lower.array()).all() && (x.array() <= upper.array()).all();
  }
};

struct GlmbParams {
  double survival_probability = 0.99;   // p_S (eq. 6) inside the field of view (everywhere if off)
  double detection_probability = 0.98;  // p_D (eq. 8's psi) inside the field of view
  // Poisson clutter intensity kappa(z) per unit measurement volume (uniform clutter: mean count
  // divided by the surveillance volume). The standard scenario's 30 / 2000^2 = 7.5e-6.
  double clutter_intensity = 7.5e-6;
  // Posterior hypotheses requested per scan, shared among the prior hypotheses in proportion to
  // the square root of their weights (Vo, Vo & Hoang 2017, section IV). Both at most
  // core::kMaxHypotheses.
  int hypothesis_budget = 1000;
  int max_hypotheses = 1000;           // cap after each update (the largest weights are kept)
  double prune_threshold = 1e-15;      // hypotheses below this normalised weight are dropped
  // Squared Mahalanobis distance beyond which a detection cannot be associated with a track; the
  // chi-square quantile of the gate probability (32.24 = P_G 0.9999999 for 2-D detections).
  // +inf disables gating (exact but slower).
  double gate_threshold = 32.24;
  // At most this many detections, the most likely ones, enter the association of one track (its
  // row of the cost matrix); the others are scored as if outside its gate. It bounds the
  // assignment problem when a scan has very many detections (tens of thousands of boxes in one
  // frame: the cost matrix then has at most rows x gate_max_detections columns); in ordinary
  // scenes a gate holds a few detections and the cap changes nothing.
  int gate_max_detections = 50;
  AdaptiveBirthParams adaptive_birth;
  OcclusionParams occlusion;  // runs of missed detections (off: constant p_D)
  EstimatorParams estimator;
  FieldOfView field_of_view;  // state-dependent p_S and p_D (off: constant)
  HypothesisRanking ranking = HypothesisRanking::murty;
  // The filter's random engine: the Gibbs sampler's, and the particle densities' (prediction,
  // births, resampling) of the particle GLMB. Murty's ranking with Gaussian densities uses none.
  std::uint64_t seed = 0;

  // Names: the fields above, ranking "murty" | "gibbs", and those of adaptive_birth, occlusion
  // and estimator (field_of_view is a box in state space, set by the trackers that use it).
  static const core::ParameterTable<GlmbParams>& table();
};

// InvalidArgument naming the parameter and its value (dimensions are checked by the filter,
// which knows the state's).
void validate(const GlmbParams& params);
void validate(const OcclusionParams& params);
void validate(const EstimatorParams& params);
// InvalidArgument unless the models, births, field of view and adaptive-birth covariance agree on
// the state and measurement dimensions.
void check_glmb_dimensions(const models::LinearGaussianMotion& motion,
                           const models::LinearGaussianObservation& observation,
                           const std::vector<GaussianBirth>& births, const GlmbParams& params);

// What a caller may say about one scan's detections beyond their positions (each vector empty or
// of one entry per detection).
struct ScanInput {
  // log kappa(z_j): the clutter intensity at each detection, replacing the constant
  // GlmbParams::clutter_intensity (a clutter density that is not uniform, a clutter rate learnt
  // online, a detection feature's likelihood ratio folded in: a feature f with densities f1 under
  // a target and f0 under clutter multiplies g(z|x) / kappa(z) by f1 / f0, i.e. divides kappa by
  // it).
  Eigen::VectorXd log_clutter;
  // b_j >= 0: the adaptive birth's weight of each detection (AdaptiveBirthParams).
  Eigen::VectorXd birth_weight;
};

// What the posterior of the last scan says about its detections and tracks (over the kept,
// normalised hypotheses): the sufficient statistics of an online estimate of the clutter and the
// detector (filters/detector_learning.hpp).
struct ScanSummary {
  // P(detection j was assigned to a track that existed before the scan), and to a track born at
  // it; 1 - both = P(j is clutter).
  Eigen::VectorXd to_track, to_birth;
  // Over the surviving tracks whose mean lies where p_D applies (the field of view): the expected
  // number detected, and the expected number missed while detectable (a miss of a track that may
  // be in an undetectable run, OcclusionParams, counts with the probability it was detectable).
  double detected = 0.0;
  double missed = 0.0;
  // r_U(z_j) as the adaptive birth used it (AdaptiveBirthParams): to_track + to_birth, plus, with
  // missed_tracks, P(unassigned but on a missed track). Zero when adaptive birth is off.
  Eigen::VectorXd explained;
};

// Labels of adaptive births: birth_index = (number of fixed births) + (index of the proposing
// detection in the previous scan's detection matrix).
struct GlmbEstimate {
  TrackLabel label;
  Eigen::VectorXd mean;
  Eigen::MatrixXd cov;
  double existence = 1.0;  // the label's posterior probability of existing (over all hypotheses)
  double undetectable = 0.0;  // P(in a run of misses) of this track (OcclusionParams)
};

// The track-density policy of the Gaussian filter: one Gaussian per track, the Kalman recursion.
// A policy (here and ParticleTracks in filters/particle_glmb.hpp) supplies, per candidate row of
// one joint prediction-update, the predicted density and its factors; GlmbFilter<Policy> does
// everything about hypotheses. Calls are per track, never per particle, so a template costs
// nothing at run time.
struct GaussianTracks {
  using Density = models::GaussianDensity;
  // A candidate track of the current scan: its predicted density and the measurement-independent
  // half of its update, shared by every hypothesis that contains it.
  struct Candidate {
    Density predicted;
    models::KalmanInnovation innovation;
  };

  Density predict(const Density& prior, const models::LinearGaussianMotion& motion) {
    return models::kalman_predict(prior, motion);
  }
  Density birth(const models::GaussianDensity& density) { return density; }
  Candidate candidate(Density predicted, const models::LinearGaussianObservation& observation,
                      const TrackLabel& /*label*/, bool /*is_birth*/) {
    models::KalmanInnovation innovation(predicted, observation);
    return {std::move(predicted), std::move(innovation)};
  }
  // log <p, g(z_j|.)> (eq. 2 integrated over the density) for every detection j, -inf outside
  // the gate (squared Mahalanobis distance of the predicted detection above `gate`).
  void log_detection_likelihoods(const Candidate& c, const Eigen::Ref<const Eigen::MatrixXd>& z,
                                 double gate, Eigen::Ref<Eigen::RowVectorXd> out) const;
  // log g(z_j | missed density) for every detection j (-inf outside the gate): the density after
  // a miss is the predicted one, so these are log_detection_likelihoods.
  void log_missed_likelihoods(const Candidate& c, const Eigen::Ref<const Eigen::MatrixXd>& z,
                              double gate, Eigen::Ref<Eigen::RowVectorXd> out) const {
    log_detection_likelihoods(c, z, gate, out);
  }
  // log of the missed-detection factor divided by (1 - p_D): 0, there is no secondary observation.
  double log_missed_likelihood(const Candidate&) const { return 0.0; }
  void set_detection_probability(double) {}  // the Gaussian densities do not depend on p_D
  Density detected(const Candidate& c, const Eigen::Ref<const Eigen::VectorXd>& z) {
    return c.innovation.posterior(z);
  }
  Density missed(const Candidate& c) { return c.predicted; }
  static models::GaussianDensity moments(const Density& d) { return d; }
};

// The delta-GLMB recursion, generic over the track density (a policy as GaussianTracks). The
// hypothesis machinery -- per-row factors, sqrt-budgeted ranked assignments per prior hypothesis,
// merging of equal track sets, log-domain normalisation, pruning and capping, r_U for adaptive
// birth, keeping the tracks in use -- is written once here for every density.
template <class Tracks>
class GlmbFilter {
 public:
  using Density = typename Tracks::Density;

  GlmbFilter(models::LinearGaussianMotion motion, models::LinearGaussianObservation observation,
             std::vector<GaussianBirth> births, GlmbParams params = {}, Tracks tracks = {});

  // One joint prediction-update with the detections of the next scan, one per column of the
  // z_dim x M matrix (M may be 0), and optionally what the caller knows of each (ScanInput).
  void step(const Eigen::Ref<const Eigen::MatrixXd>& detections, const ScanInput& input = {});

  // Estimates at the current scan, each with its label's existence probability: the tracks of
  // the hypothesis the estimator chooses (EstimatorParams).
  const std::vector<GlmbEstimate>& estimates() const { return estimates_; }
  // The posterior's association statistics of the last scan.
  const ScanSummary& summary() const { return summary_; }
  // p_D inside the field of view from the next scan on (an online estimate of it; in (0, 1]).
  void set_detection_probability(double p_d);
  // Whether some hypothesis holds a track with this label (false once the track has surely
  // ended).
  bool holds(const TrackLabel& label) const;
  // P(n targets), n = 0 .. the largest hypothesis size.
  Eigen::VectorXd cardinality_distribution() const;
  int map_cardinality() const;
  std::size_t hypothesis_count() const { return hypotheses_.size(); }
  std::size_t track_count() const { return tracks_.size(); }
  int time() const { return time_; }
  Eigen::Index z_dim() const { return observation_.H.rows(); }
  const GlmbParams& params() const { return params_; }
  const models::LinearGaussianMotion& motion() const { return motion_; }

 protected:
  Tracks tracks_model_;

 private:
  struct Track {
    TrackLabel label;
    Density density;
    double undetectable = 0.0;  // o = P(in a run of misses), OcclusionParams
    int misses = 0;             // scans missed in a row
  };
  struct Hypothesis {
    std::vector<int> tracks;  // indices into tracks_, increasing
    double log_weight = 0.0;  // normalised over hypotheses
  };
  // The factors of one scan, per candidate row (surviving prior tracks, then birth components),
  // shared by every hypothesis (see score_candidates).
  struct ScanFactors {
    std::vector<typename Tracks::Candidate> candidates;
    std::vector<TrackLabel> labels;  // each row's label (births: labelled at this scan)
    Eigen::VectorXd log_exists, log_absent, log_missed;
    Eigen::VectorXd log_pd;          // log p_D(x) of each row (eq. 8, field of view), no visibility
    Eigen::RowVectorXd log_kappa;    // log kappa(z_j) per detection
    Eigen::MatrixXd log_detected;  // rows x detections
    // Per row: P(undetectable) after a miss (OcclusionParams), and the probability that a miss
    // happened while detectable, or -1 where p_D does not apply (births, outside the field of view)
    // -- the ScanSummary's missed count.
    Eigen::VectorXd missed_undetectable, missed_detectable;
  };
  // The posterior hypotheses of one scan before normalisation, and the child tracks they use.
  struct Posterior {
    std::vector<Track> children;
    std::vector<int> child_detection;             // the detection each child took, -1 if missed
    std::vector<int> child_row;                   // the candidate row each child comes from
    std::map<std::pair<int, int>, int> child_of;  // (row, detection or -1) -> child
    std::map<std::vector<int>, double> weights;   // child set -> log weight (unnormalised)
  };
  // The posterior hypotheses of one prior hypothesis that the Gibbs sampler visits.
  struct RankedChoices {
    Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> assignments;
    Eigen::VectorXd costs;
  };

  // The stages of step(), in order.
  ScanFactors score_candidates(const Eigen::Ref<const Eigen::MatrixXd>& detections,
                               const ScanInput& input);
  Posterior rank_hypotheses(const ScanFactors& factors,
                            const Eigen::Ref<const Eigen::MatrixXd>& detections);
  // Normalised, pruned below prune_threshold and capped at max_hypotheses (best first).
  std::vector<Hypothesis> normalise_and_prune(const Posterior& posterior) const;
  // Replaces tracks_ by the children the hypotheses use (renumbered) and hypotheses_ by them.
  void keep_used_tracks(std::vector<Hypothesis> hypotheses, Posterior& posterior);

  // The child of candidate `row` updated by `detection` (-1: missed), made once per scan.
  int child_index(const ScanFactors& factors, Posterior& posterior, int row, int detection,
                  const Eigen::Ref<const Eigen::MatrixXd>& detections);
  // The cost matrix of one prior hypothesis (its tracks and the births as rows) over the
  // detections some row can take (`columns`), missed and absent: the Gibbs sampler's input
  // (Murty's ranking reads the same costs from ranking_pool_).
  Eigen::MatrixXd cost_matrix(const ScanFactors& factors, const std::vector<int>& rows,
                              std::vector<int>& columns) const;
  // The Gibbs sampler's posterior hypotheses of one cost matrix.
  RankedChoices rank(const Eigen::MatrixXd& cost, std::int64_t requested);
  // Loads the scan's candidate rows into ranking_pool_ (Murty's ranking): row r's entries are the
  // costs cost_matrix gives it, its private columns missed and absent.
  void pool_rows(const ScanFactors& factors);

  // The summary of the kept hypotheses (summary_).
  void summarise(const std::vector<Hypothesis>& hypotheses, const ScanFactors& factors,
                 const Posterior& posterior, Eigen::Index n_det);
  // P(z_j unassigned but explained by a missed track) over the kept hypotheses
  // (AdaptiveBirthParams::missed_tracks), added to r_U.
  Eigen::VectorXd missed_explanations(const std::vector<Hypothesis>& hypotheses,
                                      const ScanFactors& factors, const Posterior& posterior,
                                      const Eigen::Ref<const Eigen::MatrixXd>& detections);
  // Replaces adaptive_births_ by the births that `detections` propose for the next scan, given
  // each detection's posterior probability of having been assigned to a track and its weight.
  void propose_adaptive_births(const Eigen::Ref<const Eigen::MatrixXd>& detections,
                               const Eigen::VectorXd& assigned, const Eigen::VectorXd& weight);
  // Keeps, per row, the gate_max_detections most likely detections (the others to -inf).
  void cap_gates(Eigen::MatrixXd& log_detected) const;
  // The estimates of the current hypotheses (estimates_, reported_).
  void estimate();
  // Drops from estimates_ and reported_ every estimate within duplicate_gate of an older label's
  // (EstimatorParams::duplicate_gate).
  void suppress_duplicates();

  models::LinearGaussianMotion motion_;
  models::LinearGaussianObservation observation_;
  std::vector<GaussianBirth> births_;
  GlmbParams params_;
  // The births proposed by the previous scan's detections (adaptive birth), used at this scan.
  std::vector<GaussianBirth> adaptive_births_;
  // Column indices (into the previous scan's detections) of adaptive_births_.
  std::vector<int> adaptive_birth_detections_;
  std::vector<Track> tracks_;
  std::vector<Hypothesis> hypotheses_;
  core::Rng ranking_rng_;
  // Murty's ranking of every prior hypothesis's matrix of one scan, from the candidate rows they
  // share: the same k best as assign::murty of cost_matrix, without forming it.
  assign::PooledMurty ranking_pool_;
  int time_ = 0;
  ScanSummary summary_;
  std::vector<GlmbEstimate> estimates_;
  std::vector<TrackLabel> reported_;  // the labels of estimates_ (the consistent estimator's R)
};

// The member definitions are in filters/glmb_impl.hpp: a translation unit that adds a density
// policy includes it and instantiates GlmbFilter<Policy> (glmb.cpp does GaussianTracks,
// particle_glmb.cpp ParticleTracks).
extern template class GlmbFilter<GaussianTracks>;

// The Gaussian (Kalman) delta-GLMB filter. Deterministic: no random numbers.
using GaussianGlmbFilter = GlmbFilter<GaussianTracks>;

}  // namespace vtrack::filters
