#pragma once
// Labelled tracks from any detector's image boxes: the delta-GLMB filter (filters/glmb.hpp,
// rgbd-glmb-switching-observation.txt eqs. 5-8) with a 2-D box model.
//
// State x = [cx, vcx, cy, vcy, w, h] (pixels, one frame per step): the box centre moves with
// constant velocity, eq. (7) in 2-D with T = 1 frame (F = I2 ⊗ [[1,1],[0,1]],
// Q = sigma_accel^2 I2 ⊗ g g^T, g = [1/2, 1]^T); the size follows a random walk with standard
// deviation sigma_size per frame. A detection (x, y, w, h) is observed as z = (cx, cy, w, h) =
// H x + w, w ~ N(0, diag(sd_c^2, sd_c^2, sd_s^2, sd_s^2)), the Gaussian detection likelihood of
// eq. (2) on the image plane. False detections are Poisson with mean `clutter_rate` per frame,
// uniform over centres in the image and sizes up to the image size, so kappa(z) =
// clutter_rate / (W H)^2. Tracks are born from the detections no track explains (adaptive
// birth, GlmbParams::adaptive_birth), because people enter anywhere in an image.
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "vtrack/apps/box_clutter.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/core/parameters.hpp"
#include "vtrack/filters/detector_learning.hpp"
#include "vtrack/filters/glmb.hpp"
#include "vtrack/filters/glmb_tracker.hpp"
#include "vtrack/filters/track_management.hpp"
#include "vtrack/filters/tracks.hpp"

namespace vtrack::apps {

// Defaults: one set for every detector and scene (issue 14). The clutter rate, p_D and the score
// model are learnt online (below), so clutter_rate and detection_probability are only priors; the
// noise, motion, birth and occlusion values were chosen on the tuning seeds of
// benchmarks/detections_sim.py together with frames 1-397 of the PETS09 real-detector sets
// (benchmarks/detections.py; frames 398-795 and the reporting seeds held out), the grids and the
// figures in those docstrings.
struct BoxTrackerParams {
  // p_D (eq. 8's psi). 0.8 (tuned; 0.7-0.9 tried): the detectors miss a person now and then,
  // more often in groups.
  double detection_probability = 0.8;
  // p_S per frame (eq. 6). 0.99: after two missed frames the hypotheses that end the track weigh
  // about as much as those that keep it (0.999 keeps ghost tracks alive: MOTA 0.49 -> -0.38 on
  // the tuning frames).
  double survival_probability = 0.99;
  // p_S and p_D of a track whose box centre is outside the image (GlmbParams::field_of_view, the
  // paper's state-dependent p_S,k(x, l) and p_D,k(x, l) of eqs. 6 and 8): a person whose centre
  // has left the image is about to be gone, and is not expected to be detected. With a constant
  // p_S a track born on a false box could fly off and be kept for ever (PETS09 with all of
  // ACF's detections: MOTA -3.81, a ghost at x = -18,000; benchmarks/detections.py). Setting
  // them equal to survival_probability and detection_probability restores constant ones.
  // 0.1 / 0.1 chosen on frames 1-397 from {0.1, 0.5, 0.9} x {0.1, 0.5} (Faster R-CNN HOTA
  // 0.420-0.429 except 0.383 for 0.9 / 0.5; all of ACF's: MOTA -0.13 at 0.1 / 0.1, -0.26 to
  // -0.30 at 0.5 or p_D 0.5, -1.1 to -1.2 at p_S 0.9).
  double outside_survival_probability = 0.1;
  double outside_detection_probability = 0.1;
  // Expected false detections per frame (Poisson): the prior of the learnt rate (learn_clutter;
  // the rate itself when learning is off), centred uniformly in the image with person-like sizes
  // (apps/box_clutter.hpp).
  double clutter_rate = 1.0;
  // White-noise acceleration of the centre, px/frame^2 (eq. 7's sigma_v with T = 1 frame). 1
  // (0.5-2 tried): walkers turn and stop; the jumps of box centres are the detection noise's.
  double sigma_accel = 1.0;
  // Random-walk standard deviation of width and height, px/frame.
  double sigma_size = 1.0;
  // Detection noise (eq. 2's R): centre and size standard deviations, px, the floor under the
  // noise that grows with the box (detection_sd_relative). 4 / 4 (2-8 tried).
  double detection_sd_centre = 4.0;
  double detection_sd_size = 4.0;
  // Adaptive birth covariance (standard deviations) around a detection's box with zero velocity:
  // about one box-width of uncertainty in the walking speed per frame and a few pixels in place.
  double birth_sd_centre = 10.0;
  double birth_sd_velocity = 5.0;
  double birth_sd_size = 10.0;
  // lambda_B: expected births per frame, and the cap on one detection's birth existence r_B.
  // 0.02 / 0.1 (0.5 / 0.3 before the clutter and score models): births go to detections that are
  // unexplained and target-like, and a birth must be confirmed by the next detections.
  double birth_rate = 0.02;
  double birth_max_existence = 0.1;
  // Posterior hypotheses requested per frame and kept after each update (at most
  // core::kMaxHypotheses).
  int hypothesis_budget = 200;
  // Squared Mahalanobis gate for the 4-D detection: the chi-square(4) quantile of
  // P_G = 0.9999999 (38.24).
  double gate_threshold = 38.24;
  // Detections with confidence below this are ignored (-inf keeps all).
  double min_confidence = -std::numeric_limits<double>::infinity();
  // Confirmation and lost-track memory (filters/track_management.hpp, shared with the MB
  // tracker): a track of the MAP hypothesis is reported once it has been in the MAP estimate on
  // confirm_frames frames (as SORT's min_hits); a confirmed label that leaves the estimate is
  // remembered for lost_memory frames, and a new label whose box overlaps it (moved on at the
  // track's velocity) by IoU >= relabel_overlap (or, with relabel_distance > 0, whose centre is
  // within that many of its box sizes) reports under its id. Estimates only: the GLMB
  // itself is unaffected. Measured on frames 1-397 (benchmarks/detections.py, as min_age, the
  // label's age, which equals the count while a track stays in the estimate): 3 trims a few FPs
  // of short-lived tracks (MOTA +0.005 to +0.024 on Faster R-CNN and ACF, HOTA +0.002) but the
  // GLMB's false positives are mostly long-lived (duplicate and coasting tracks), so the default
  // reports every track; the memory is off by default (the GLMB keeps labels through misses by
  // itself).
  filters::TrackManagementParams management{1, 0, 0.3};
  // --- Learnt online (filters/detector_learning.hpp): EM with the GLMB update as the E step ---
  // Clutter: kappa(z) = lambda / (W H) p_size(w, h): Poisson false boxes centred uniformly in the
  // image with a log-normal density over their sizes. learn_clutter: lambda (from clutter_rate as
  // its prior) and p_size (from a prior centred on image-relative person sizes) are learnt from
  // the detections the posterior assigns to clutter; false: both stay at their priors.
  bool learn_clutter = true;
  // p_D learnt from the posterior's detected / missed detectable tracks, from
  // detection_probability as its prior, within [detection_probability_min, _max].
  bool learn_detection_probability = true;
  double detection_probability_min = 0.3;
  double detection_probability_max = 0.98;
  // Forgetting of all online estimates (about the last `learning_memory` scans count) and the
  // weight of their priors (worth `learning_prior_weight` scans of data).
  double learning_memory = 100.0;
  double learning_prior_weight = 10.0;
  // Scores as a likelihood ratio (filters::ScoreModel): true multiplies each detection's
  // target-vs-clutter ratio by f1(s) / f0(s), learnt online from the posterior; false ignores
  // scores. score_window: the scores whose empirical distribution maps a score to the probit
  // scale (any detector's score scale works; all-equal scores give a ratio of 1).
  bool use_scores = true;
  int score_window = 1000;
  // Whether the adaptive birth weights each unexplained detection by its score's likelihood ratio.
  bool birth_score_weight = true;
  // Duplicate boxes per person and frame (apps/box_clutter.hpp), the prior of the learnt rate; 0
  // = no duplicate model.
  double duplicate_rate = 0.1;
  // Detection noise proportional to the box: each box edge's standard deviation is this fraction
  // of the box's width (left, right) or height (top, bottom), on top of detection_sd_centre and
  // detection_sd_size: centre variance += (f w)^2 / 2, size variance += 2 (f w)^2 (models::
  // LinearGaussianObservation::noise_scale). 0.08 (0-0.1 tried): a detector's error grows with
  // the object.
  double detection_sd_relative = 0.08;
  // Runs of misses (GlmbParams::occlusion): rate 0.03 per frame, mean length 10, at most 20
  // frames -- a person behind another keeps the label instead of being re-born (the bursts level
  // of benchmarks/detections_sim.py), while a track born on a static false box dies within 20
  // frames of its last detection.
  filters::OcclusionParams occlusion{0.03, 10.0, 20};
  // The label estimator (GlmbParams::estimator): the MAP one by default ("consistent" measured
  // slightly better on the simulated levels, worse on Faster R-CNN).
  filters::EstimatorParams estimator{filters::LabelEstimator::map};
  // At most this many adaptive births per frame (AdaptiveBirthParams::max_births): bounds the
  // cost of a frame with tens of thousands of boxes.
  int max_births = 100;
  // Whether a detection that a missed track explains counts as explained for the adaptive birth
  // (AdaptiveBirthParams::missed_tracks, filters/glmb.hpp).
  bool birth_missed_tracks = false;
  // Hypothesis ranking (GlmbParams::ranking): "murty" = Murty's k best (exact, deterministic),
  // "gibbs" = the Gibbs sampler, seeded by `seed` (same seed, same tracks). Measured on frames
  // 1-397: Gibbs raises MOTA (ACF all -0.13 -> 0.23, Faster R-CNN 0.47 -> 0.54) and lowers IDF1
  // and HOTA (Faster R-CNN HOTA 0.42 -> 0.34): it explores deaths Murty's truncated ranking
  // misses, and also breaks tracks.
  filters::HypothesisRanking ranking = filters::HypothesisRanking::murty;
  std::uint64_t seed = 0;

  static const core::ParameterTable<BoxTrackerParams>& table();
};

// InvalidArgument naming the parameter and its value.
void validate(const BoxTrackerParams& params);

// The motion and observation models of the header comment.
models::LinearGaussianMotion box_motion(const BoxTrackerParams& params);
models::LinearGaussianObservation box_observation(const BoxTrackerParams& params);
// The GLMB configuration (p_S, p_D, kappa, budget, gate, adaptive birth) for a width x height
// image.
filters::GlmbParams box_glmb_params(const BoxTrackerParams& params, int width, int height);

// Frame-by-frame tracker of image boxes: the GLMB tracker (filters/glmb_tracker.hpp) with the
// box model above.
class BoxTracker {
 public:
  // width x height: the image (positive).
  BoxTracker(int width, int height, const BoxTrackerParams& params = {});
  BoxTracker(const BoxTracker&) = delete;
  BoxTracker& operator=(const BoxTracker&) = delete;
  BoxTracker(BoxTracker&&) = default;
  // One frame's detections (x, y, w, h and confidence used; the frame field is ignored), and the
  // tracks reported at that frame: ids 1, 2, ... in order of first report, the box, score = the
  // label's posterior existence probability, state [cx, vcx, cy, vcy, w, h] with its covariance,
  // the GLMB label. Boxes must pass validate_detection.
  const filters::Tracks& step(const std::vector<Detection>& detections);
  const filters::GlmbTracker& tracker() const { return tracker_; }
  const BoxTrackerParams& params() const { return params_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // The current online estimates.
  const BoxClutter& clutter() const { return clutter_; }
  double detection_probability() const { return detection_probability_.probability(); }
  const filters::ScoreModel& score_model() const { return score_model_; }

 private:
  // The duplicate sources of the clutter model: the last estimate's boxes, one frame on.
  void set_duplicate_sources();
  // Updates the online estimates from the posterior of the scan just run.
  void learn(const Eigen::MatrixXd& z, const Eigen::VectorXd& scores, const Eigen::VectorXd& u);

  BoxTrackerParams params_;
  int width_, height_;
  filters::GlmbTracker tracker_;
  BoxClutter clutter_;
  filters::DetectionProbability detection_probability_;
  filters::ScoreModel score_model_;
};

// The smallest image (width, height), from (0, 0), that contains every box, rounded up to whole
// pixels: the image size when a detection file comes without one. (1, 1) for no detections.
std::pair<int, int> detections_extent(const std::vector<Detection>& detections);

// Tracks the detections of frames 1 .. max(last_frame, the last frame with a detection), in a
// width x height image (so trailing frames without detections still get their estimates); width
// or height 0 = the detections' extent (InvalidArgument beyond core::kMaxImageSide).
// MOTChallenge rows, conf = the track's score, ids 1, 2, ... in order of first appearance. Runs
// of empty frames while nothing is tracked or remembered are skipped (they cannot change the
// rows), so the cost does not grow with the frame numbers; progress is reported per frame
// stepped and once at the end, and core::poll_interrupt() is polled per frame.
std::vector<TrackRow> track_detections(const std::vector<Detection>& detections, int width,
                                       int height, const BoxTrackerParams& params = {},
                                       long long last_frame = 0,
                                       const FrameProgress& progress = {});

}  // namespace vtrack::apps
