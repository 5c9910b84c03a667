#pragma once
// Sequential Monte Carlo multi-Bernoulli filter for track-before-detect on a background-subtracted
// image (mb-tbd-background-subtraction paper, Section 4, eqs. 21-24; the update is Vo,
// Vo & Hoseinnezhad's multi-Bernoulli update for separable likelihoods, eqs. 3-5).
//
// Each Bernoulli component i has an existence probability r_i, a weighted particle set of box
// states (x, y, w, h) (eq. 21) and a label it keeps for life. One step(y):
//   1. predict: r <- P_S r, x <- x + e, e ~ N(0, diag(sigma^2)), weights kept (eq. 22);
//      widths and heights are clamped to the size prior's range;
//   2. birth: the paper's four image quarters (r_Gamma each, location uniform in the quarter, size
//      from the people size prior) and, optionally, data-driven births on the person-sized windows
//      that best explain foreground not covered by any existing target's estimate;
//   3. update with g_y of eq. (20), each component seeing other existing targets' boxes as
//      background (eq. 13; see cover_existence): rho = sum_j w_j g_y(x_j),
//      r <- r rho / (1 - r + r rho) (eq. 23), w_j <- w_j g_y(x_j) / rho (eq. 24), in logs;
//   4. prune r < prune_threshold; merge components whose estimates overlap (intersection over
//      the smaller box above merge_overlap; the older label survives);
//   5. resample each component to L = clamp(ceil(r L_max), L_min, L_max) particles;
//   6. report every component with r > estimate_threshold as a track: its label, the weighted
//      mean box and r. Beyond the paper (MultiBernoulliParams, "track management"): only once
//      confirmed (confirm_frames reports), a re-born component near where a recently lost track
//      would be takes its label back (lost_memory), the prediction drifts at each component's
//      smoothed velocity (velocity_smoothing), and the reported box is scaled and shifted from
//      the foreground box to the annotation convention (box_scale_*, box_offset_*).
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/core/parameters.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/filters/appearance.hpp"
#include "vtrack/filters/person_prior.hpp"
#include "vtrack/filters/track_management.hpp"
#include "vtrack/filters/tracks.hpp"
#include "vtrack/models/motion.hpp"
#include "vtrack/models/tbd_likelihood.hpp"
#include "vtrack/smc/particle_set.hpp"

namespace vtrack::filters {

using models::BoxStates;

// The likelihood's defaults in the tracker: eq. (20) with the "row" reference (see size_by_row).
inline models::TbdLikelihoodParams row_likelihood() {
  models::TbdLikelihoodParams p;
  p.delta_b_reference = models::TbdLikelihoodParams::DeltaBReference::row;
  return p;
}

struct MultiBernoulliParams {
  models::TbdLikelihoodParams likelihood = row_likelihood();

  // P_S of eq. (22), in (0, 1].
  double survival_probability = 0.99;
  // ---- Scale. Every size below is relative to the people size prior's mean height h (pixels),
  // so that the defaults hold at any resolution, crop and camera distance (issue 12); they were
  // pixel sizes fitted to PETS09-S2L1 at 768 x 576 before, where h = 85 px, and are those
  // values divided by 85 (or by the width 30).
  //
  // The people size prior: its mean height h (given or learnt from the scene's foreground),
  // aspect, spread and clamp range (filters/person_prior.hpp).
  PersonSizeParams size;
  // Pixels, or 0 (default) for size_aspect x h.
  double width_mean = 0.0;
  // Perspective (issue 12): with size_by_row and a learnt h, every size above and below is taken
  // relative to the person height at the foot row, h(y_foot) = a y_foot + b, learnt from the
  // foreground components' heights by foot row (models::PersonHeightLine; the constant h when the
  // data do not support a slope) instead of the one h: the birth windows and their grid, the
  // birth sizes, the size clamp range and the random walk's sigmas (per component, for a person
  // centred on its estimate). The likelihood's closing keeps the one h; the box calibration is
  // relative to each box already. Alone it scores worse on PETS09-S2L1 (the filter's box is a
  // silhouette's core held up by the size clamp's minimum). With the likelihood's
  // delta_b_reference "row" (which needs size_by_row) the reward follows the row too and far and
  // near people are boxed alike: with delta_b_row 3e-3 the pair (the default) beats the former
  // defaults ("image", size_by_row off) on MOTA, IDF1 and HOTA on all frames of PETS09-S2L1 at
  // 768 x 576 and resized 0.4x-1.5x. Where the scene shows no perspective (the line needs five
  // row bands of people that agree on it, models/person_size.hpp) the sizes are the one h's and
  // the reward is per the prior's person area (the likelihood's delta_b_no_line).
  // benchmarks/mb_perspective.py has the figures.
  bool size_by_row = true;
  // Standard deviations of the random walk x(k+1) = x(k) + e(k) (Section 4) per frame, as
  // fractions of h: positions (x, y) and sizes (w, h). PETS09-S2L1 runs at 7 frames/s, so its
  // walkers move 3-6 px/frame at 768 x 576 (h = 85); a random walk follows a drift of about its
  // own sigma, hence 5 px = 0.06 h; sizes 1.5-2 px = 0.02 h.
  double sigma_xy = 0.06;
  double sigma_wh = 0.02;

  // The paper's birth (Section 4): one Bernoulli per image quarter with r_Gamma = 0.02.
  bool quarter_birth = true;
  double birth_probability = 0.02;
  // Particles of each birth component (at most core::kMaxParticles, as max_particles).
  int birth_particles = 200;

  // Components with r >= cover_existence are "existing targets": each component is evaluated
  // with other targets' estimated boxes filled with background (eq. 13, see TbdLikelihood), and
  // data-driven births look only at foreground outside them. Which others: every older one, and
  // younger ones once they are established_age frames old. So a fresh duplicate of a track sees
  // the track's pixels as explained and dies, without suppressing the track in return (with a
  // symmetric rule both would lose their evidence at once), while established neighbours
  // partition the foreground between them and neither grows over the other.
  double cover_existence = 0.1;
  int established_age = 3;

  // Data-driven birth: person-sized windows (the prior's mean size times 0.85, 1 and 1.3, on a
  // grid of adaptive_birth_stride x h pixels, at least 1) are scored by log g_y of eq. (20) with the existing
  // targets' boxes counted as background, i.e. by how well a new target there would explain
  // foreground no target explains. The best windows scoring above adaptive_birth_log_likelihood
  // (0: the box alone would raise an existence probability, eq. 23), at most adaptive_birth_max
  // per frame and not overlapping each other, each give a Bernoulli with existence
  // adaptive_birth_probability whose boxes are spread around the window (centre +-15% of its
  // size, size N(window size, (15%)^2)). It uses the current frame, so an entering person is
  // confirmed within a frame or two. (Smaller windows, e.g. 0.7, let a tall person's untracked
  // half become a second target, which stays: each half explains the other's pixels.)
  bool adaptive_birth = true;
  double adaptive_birth_probability = 0.05;
  // -3 (was 0): with delta_b = 2e-3 a small, far person's window scores below 0 though the
  // person is clearly foreground; the birth then has to prove itself in the update (eq. 23).
  // PETS09-S2L1 second half, calibrated: MOTA 0.32 with -3 vs 0.29 with 0 (IDF1 0.27 vs 0.29).
  double adaptive_birth_log_likelihood = -3.0;
  double adaptive_birth_stride = 0.1;  // fraction of h (formerly 8 px at h = 85)
  int adaptive_birth_max = 3;

  // Particle counts of a component after resampling: clamp(ceil(r L_max), L_min, L_max). The
  // paper gives no values. L_max is the approximation's accuracy: a confirmed target's density
  // (four box coordinates, eq. 20's likelihood sharp at the silhouette's edges) holds L_max
  // particles, and a box costs O(1) on integral images, so a large L_max is cheap. L_min keeps
  // new and fading components (r small) cheap. The values measured, on every resolution and
  // crop, are in benchmarks/pets09_identity.py.
  int min_particles = 50;    // L_min
  int max_particles = 1600;  // L_max
  core::ResamplingScheme resampling = core::ResamplingScheme::Systematic;

  double prune_threshold = 0.01;     // Section 4: components with r below are removed
  // "Targets with substantial overlap are merged" (Section 4): two components merge when the
  // intersection of their estimates covers more than this fraction of the smaller one. The
  // separable likelihood (eq. 20) scores a box half on a person nearly as well as one on it, so
  // duplicates of one person are often offset by a third of a box; IoU (0.46 for such a pair)
  // would keep them apart, the overlap of the smaller box (0.7) does not.
  double merge_overlap = 0.6;
  double estimate_threshold = 0.5;   // Section 4: tracks are the components with r above
  // Upper bound on r after the update and merge. With r = 1 exactly, eq. (23) can never lower r
  // again (1 - r = 0), so a departed target would live for ever when P_S = 1; the cap bounds the
  // log odds (6.9 for 0.999), so a target that has left dies within a few frames.
  double max_existence = 0.999;

  // ---- Track management beyond the paper. Section 4 reports every component with r above
  // estimate_threshold under the label it was born with; the paper's output is confirm_frames 1,
  // lost_memory 0, velocity_smoothing 0, box scales 1 and offsets 0. The defaults below were
  // chosen on frames 1-397 of PETS09-S2L1 (benchmarks/pets09.py, whose docstring has the sweep)
  // and scored on 398-795.

  // Confirmation and lost-track memory (filters/track_management.hpp, shared with the box GLMB;
  // names confirm_frames, lost_memory, relabel_overlap). An estimate is a component with
  // r > estimate_threshold; it is reported once it has had one on confirm_frames steps (not
  // necessarily consecutive). Births on ghosts, kerb edges and the unexplained part of a
  // silhouette rarely live that long. (PETS09 frames 1-397, calibrated MOTA / IDF1: 3 frames
  // 0.546 / 0.593, 5 frames 0.544 / 0.597, 8 frames 0.530 / 0.597.) A confirmed component that is
  // pruned (its person occluded, or merged into another's blob, or absorbed by a merge) is
  // remembered for lost_memory frames; an unconfirmed component whose estimate overlaps the lost
  // box, moved on at the lost velocity, by IoU >= relabel_overlap takes that label back. (PETS09:
  // no change on frames 1-397; on 398-795, where people cross in groups, IDF1 0.397 -> 0.447.)
  // Failing the overlap, one whose centre is within relabel_distance 3 of the lost box's moved-on
  // centre, in that box's widths and heights, does: a track re-founded 10-50 frames after its
  // person was lost (faint foreground, a pair's blob) starts near where the lost box was heading
  // but rarely on it, since the fading box had shrunk and a birth starts at the prior's size.
  // (benchmarks/pets09.py's docstring has the sweep: IDF1 on all frames +0.05-0.09 for 2-5.)
  // Colour appearance on, as the re-clustering SIR's (appearance_rate 0.05, appearance_sigma
  // 0.15, appearance_distance 1.5; used when step() is given the frame, as the mb pipeline does):
  // people who cross get their labels back by their colours (benchmarks/pets09_identity.py:
  // IDF1 +0.02 on 1-397, +0.07-0.13 on 398-795 at every scale, MOTA unchanged).
  TrackManagementParams management{5, 30, 0.3, 3.0, 0.05, 0.15, 1.5};
  // Drift in the prediction (eq. 22 is a random walk, which lags a walking person and lets a box
  // slide onto whichever neighbour it meets when two people cross): each component keeps v, an
  // exponential average (weight velocity_smoothing on the newest) of the frame-to-frame change
  // of its estimated box centre, and the prediction becomes x <- x + v + e. 0 is the paper's
  // random walk. The same v moves a lost track's box (above). (PETS09 frames 1-397, calibrated,
  // KDE without selective update: MOTA / IDF1 0.414 / 0.388 with 0, 0.610 / 0.492 with 0.3,
  // 0.578 / 0.473 with 0.6; with it, 0.2 / 0.3 / 0.4 give 0.567 / 0.552, 0.544 / 0.597,
  // 0.549 / 0.614.)
  double velocity_smoothing = 0.3;
  // Reported box: the filter's box fits the foreground as eq. (20) scores it, i.e. the dark core
  // of a silhouette; annotations (MOTChallenge's) box the whole person with a margin, hence the
  // calibration (filters/person_prior.hpp). Defaults: the medians of the calibration fits on
  // PETS09-S2L1 frames 1-397 of tracker seeds 0-2 with the "row" defaults
  // (benchmarks/mb_perspective.py --calibrate: 1.665-1.685 x 1.698-1.720, offsets 0.009-0.027,
  // 0.034-0.053; with the former "image" defaults the fit was 1.75 x 1.47, -0.01, -0.01), and
  // clipped to the image (box_clip).
  BoxCalibrationParams box{1.673, 1.706, 0.023, 0.045, true};

  // The filter's random engine (prediction noise, births, resampling): the same seed gives the
  // same tracks.
  std::uint64_t seed = 0;

  static const core::ParameterTable<MultiBernoulliParams>& table();
};

// Throws InvalidArgument naming the parameter and its value when one is out of range.
void validate(const MultiBernoulliParams& params);

// A component's weighted particle set {x_j, w_j} of eq. (21): L box states (x, y, w, h), one per
// row (the SMC engine's layout, smc/particle_set.hpp), with normalised log-domain weights.
using BoxParticles = smc::ParticleSet<float, 4>;

struct BernoulliComponent {
  std::uint64_t label;
  int birth_frame;    // step index (0-based) at which the component was born
  double existence;   // r
  BoxParticles particles;
  // Track management (MultiBernoulliParams::management); record.velocity is also the drift of
  // the prediction (velocity_smoothing).
  TrackRecord record;
  Eigen::Vector4f last_mean = Eigen::Vector4f::Zero();  // estimate at the previous step
  // Weighted mean box (the engine's estimate, part-based eq. 8).
  Eigen::Vector4f mean() const;
};

// The people size prior in pixels at one step: MultiBernoulliParams' relative sizes times the
// given or learnt mean height.
struct PersonSizePrior {
  double width = 0.0, height = 0.0;          // means
  double width_std = 0.0, height_std = 0.0;  // of births
  double width_min = 0.0, width_max = 0.0;   // clamp range after prediction
  double height_min = 0.0, height_max = 0.0;
  double sigma_xy = 0.0, sigma_wh = 0.0;     // random walk, px per frame
  int birth_stride = 1;                      // adaptive birth grid, px
  bool learnt = false;                       // from the scene's foreground (else given/initial)
};
// The pixel sizes for mean height `height` and mean width `width` (0: size_aspect x height).
PersonSizePrior person_size_prior(const MultiBernoulliParams& params, double width, double height);

class MultiBernoulliFilter {
 public:
  MultiBernoulliFilter(int width, int height, const MultiBernoulliParams& params = {});

  // One predict-update cycle on the background-subtracted image y (H x W float32 in [0, 1]) and,
  // optionally, the frame it came from (8-bit BGR of y's size; empty: none), whose colours keep
  // the labels on the people when management.appearance_rate > 0 (TrackManager's appearance).
  // Returns the reported tracks in label order: id = label, the reported box, score = r, state =
  // the filter's own box (x, y, w, h) before the box calibration.
  const Tracks& step(const cv::Mat& y, const cv::Mat& frame = cv::Mat());

  const Tracks& tracks() const { return tracks_; }
  const std::vector<BernoulliComponent>& components() const { return components_; }
  const MultiBernoulliParams& params() const { return params_; }
  const models::TbdLikelihood& likelihood() const { return likelihood_; }
  // The people size prior in force (pixels): fixed by height_mean / width_mean, else learnt from
  // the foreground seen so far (see MultiBernoulliParams::height_mean).
  const PersonSizePrior& size_prior() const { return size_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int frame() const { return frame_; }  // number of steps taken

 private:
  void predict();
  void add_quarter_births();
  void add_adaptive_births();
  // A birth component whose box centres are uniform on [cx_lo, cx_hi] x [cy_lo, cy_hi] and whose
  // sizes are N(size, diag(size_std^2)) clamped to the size range.
  // prior_size: size and size_std are the prior's (at h), scaled to each box's row with
  // size_by_row; else the box's own. The clamp range follows the row either way.
  void add_birth(double existence, double cx_lo, double cx_hi, double cy_lo, double cy_hi,
                 const Eigen::Vector2d& size, const Eigen::Vector2d& size_std, bool prior_size);
  void update();
  void prune_and_merge();
  void resample();
  // Clamps sizes to the size prior's range times `scale` (the row's, see size_by_row).
  void clamp_sizes(BoxParticles::States& states, float scale) const;
  // h(foot_row) / h with a fitted, supported line, else 1 (line_scale); the same with
  // size_by_row only (row_scale), which the size prior uses.
  double line_scale(double foot_row) const;
  double row_scale(double foot_row) const;
  bool prior_by_row() const { return params_.size_by_row && !line_scale_.empty(); }
  // The same for a person whose box is centred on row cy: at the foot row cy + h(foot) / 2 (one
  // fixed-point step from the mean height). Not at the box's own bottom: the filter's box is the
  // dark core of a silhouette, shorter than the person, and a scale taken at its bottom would
  // shrink the size range, so the box, so the scale, frame after frame.
  double line_centre_scale(double cy) const;
  double centre_row_scale(double cy) const;
  // Observes y's foreground and updates size_ (and the likelihood's person size and the random
  // walk's sigmas) when learning.
  void update_size_prior();
  // Sets size_ and what depends on it: the likelihood's person size and motion_'s sigmas.
  void set_size_prior(const PersonSizePrior& size);
  // Confirmation, relabelling from the lost memory (and by the colours of `frame`, when not
  // empty) and velocities; fills tracks_.
  void manage_tracks(const cv::Mat& y, const cv::Mat& frame);

  MultiBernoulliParams params_;
  int width_;
  int height_;
  core::Rng rng_;
  // Eq. (22)'s random walk x + e, e ~ N(0, diag(sx^2, sx^2, sw^2, sw^2)), sx = sigma_xy h and sw =
  // sigma_wh h for the size prior's mean height h (set_size_prior).
  models::RandomWalk motion_;
  models::TbdLikelihood likelihood_;
  PersonHeight person_height_;
  PersonSizePrior size_;
  // [foot row]: h(row) / h (a line fitted for size_by_row or the "row" likelihood reference and
  // supported by the data; empty otherwise).
  std::vector<double> line_scale_;
  TrackManager management_;
  std::vector<BernoulliComponent> components_;
  Tracks tracks_;
  std::uint64_t next_label_ = 1;
  int frame_ = 0;
  // Scratch buffers reused across frames.
  // Existing targets (r >= cover_existence) after prediction: labels, birth frames and boxes.
  std::vector<std::uint64_t> covered_labels_;
  std::vector<int> covered_births_;
  std::vector<image::Rect> covered_;
  std::vector<image::Rect> explained_;
  std::vector<float> noise_;
  BoxParticles::States eps_;
  BoxParticles::States next_;
  Eigen::VectorXd log_g_;
  ForegroundColour colour_;
  std::vector<ColourHistogram> seen_;
};

// Area of the intersection of two boxes (x, y, w, h) over the area of the smaller one; 0 when
// either is empty.
double box_overlap(const Eigen::Vector4f& a, const Eigen::Vector4f& b);
// Merges every component whose estimate overlaps an older one's (box_overlap > min_overlap) into
// the older, which keeps its label (unless only the younger is confirmed: then its label and
// track state carry on); `components` must be in label order (older first) and stay so. The merged
// existence is 1 - (1 - r_a)(1 - r_b) (capped at max_existence), the density the r-weighted
// mixture of the two particle sets. The absorbed components are appended to `absorbed` if given.
void merge_overlapping(std::vector<BernoulliComponent>& components, double min_overlap,
                       double max_existence,
                       std::vector<BernoulliComponent>* absorbed = nullptr);
// r rho / (1 - r + r rho) of eq. (23) from log rho, computed as a logistic of the log odds so it
// is exact for huge or tiny rho and never NaN.
double updated_existence(double r, double log_rho);

}  // namespace vtrack::filters
