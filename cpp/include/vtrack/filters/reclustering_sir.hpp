#pragma once
// Multi-person SIR with measurement-guided re-clustering (particle-filters-human-vehicle paper,
// §2, after Nieto, Cuevas & Salgado, ICIP 2009), on the SMC engine (smc/particle_set.hpp).
//
// ONE particle set for all the people in the scene: particle i carries an ellipse state
// x = (x, y, vx, vy, a, b) (§2.1: centre, velocity, horizontal and vertical semi-axes, no
// rotation) and a cluster index c_i in {0, 1, .., M} (§2: c_t^i; 0 = "free", a particle of the
// §2.2 initialisation that no object owns yet). The measurement is the set of foreground pixels
// z = {(x_j, y_j)} of the background-subtracted image y (y < foreground_threshold, vtrack's
// image::KdeBackground output), taken on a grid (see grid_step). One step(y):
//
//   1. (§2.2) no measurement at all: every object ends and the particles are drawn again from
//      the initialisation prior (centres uniform over the image, velocities N(0, sigma_velocity^2),
//      axes uniform in the expected size range), free. Otherwise:
//   2. predict: constant velocity for (x, y, vx, vy), a random walk for (a, b) clamped to the
//      size range (models::LinearTransition);
//   3. associate each measurement with the object whose predicted estimate (its cluster's mean
//      ellipse) is nearest in that ellipse's normalised distance d^2 = (dx/a)^2 + (dy/b)^2 (axes
//      at least the person size's, so that a shrunken ellipse still sees the whole person), if
//      d <= gate; the rest are the free particles' measurements Z^0. (Nearest-ellipse association
//      lets two people in one foreground blob share it: each gets the pixels on its side.)
//   4. weight (§2.1): log L(Z^m | x) = log(N_in / (pi a b)) + log(N_in / N)
//      + sum_{j in Z^m} log(rho + h(z_j | x)) (the first two terms weighted, see shape_weight),  h(z | x) = exp(-(z - p)^T C^{-1} (z - p) / 2),
//      C = diag((novelty_sigma w / 2)^2, (novelty_sigma h / 2)^2) for the learnt person size
//      w x h ("the covariance matrix that normalises dimensions": fixed, so that the product term
//      places the centre and the two factors the axes; with C from the particle's own axes the
//      product rewards ever larger ellipses). N_in counts grid measurements inside the ellipse,
//      so N_in / (pi a b) is measured in grid cells (the grid's area per point is a constant
//      factor). Each cluster's likelihoods are normalised within the cluster before the engine's
//      reweight, so a cluster keeps its mass: clusters see different measurement sets, whose
//      likelihoods are not comparable across clusters (and would underflow each other);
//   5. novelty n(z_j) = prod_m (1 - h(z_j | xhat_m)) over the objects' estimates: measurements
//      with n > novelty_threshold are novel (unexplained);
//   6. injection (Fig. 1): when there are at least min_object_fraction x (a person's expected
//      grid count) novel measurements, up to ceil(inject_fraction N) new particles, each centred
//      on a novel measurement drawn from n(z) (velocity ~0, axes from the size prior), replace
//      the lowest-weighted particles (free ones first) and take the replaced one's weight class
//      (log weight -log N);
//   7. re-clustering: an injected particle within the gate of an object's estimate joins that
//      object (the object gains particles while its measurements stay novel); one outside every
//      gate that holds at least min_object_fraction of a person's novel measurements inside its
//      ellipse starts a new object with that single particle (later injected ones near it join
//      it); the others are dropped. Then every particle joins the object whose estimate is
//      nearest (normalised distance) among the objects whose gate holds it, objects whose
//      centres are closer than merge_distance person half-sizes, or whose measurements together fit
//      in merge_size person sizes, merge into the older,
//      and an object without measurements for max_misses steps releases its particles. An
//      object whose cluster empties ends;
//   8. resampling (engine: core::resample per cluster, smc::gather_rows): the budget is
//      N = n_particles x ceil(M / budget_objects) (the paper: 100 particles for 1-4 people), at
//      least one per object; a new object's count doubles each step up to the equal share N / M,
//      the others share the rest. Free particles survive only while there is no object;
//   9. estimates: each object's weighted mean ellipse, reported as its bounding box (2a x 2b)
//      under the object's label for life, through filters::TrackManager (confirmation, lost-track
//      memory) and the box calibration to the annotation convention (box_scale_*, box_offset_*,
//      as MultiBernoulliParams). With the frame (step(y, frame)), the labels follow the people's
//      colours (TrackManager's appearance, beyond the paper): the objects that come apart after
//      their boxes overlapped share their labels out by colour and motion, and a re-founded object
//      takes the lost label whose colours it has. Without it, labels follow the objects.
//
// No pixel-size default: every size is relative to the people's height h, learnt from the
// scene's foreground (models::ForegroundSizeEstimator, as the multi-Bernoulli tracker does), and
// with size_by_row (default) taken at each ellipse's row from the learnt height-by-foot-row line.
#include <algorithm>
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
#include "vtrack/models/linear_transition.hpp"
#include "vtrack/smc/particle_set.hpp"

namespace vtrack::filters {

struct ReclusteringSirParams {
  // ---- The particle set (§2.2: "100 particles for tracking between 1 and 4 objects").
  // n_particles >= 1 for up to budget_objects objects; N = n_particles x ceil(M / budget_objects)
  // for M objects (and at least M). 600, not the paper's 100: on PETS09-S2L1 frames 1-397
  // (calibrated MOTA / IDF1, mean of tracker seeds 0-2; benchmarks/pets09.py's docstring) 300
  // particles gave 0.304 / 0.353, 600 0.348 / 0.364, 1000 0.349 / 0.369; 100 gave 0.234 / 0.332.
  // The paper's 360 x 288 scenes hold 1-4 people; PETS09 holds up to 8 in groups.
  int n_particles = 600;
  int budget_objects = 4;
  core::ResamplingScheme resampling = core::ResamplingScheme::Systematic;

  // ---- Likelihood (§2.1). rho > 0: the regularisation of prod_j (rho + h(z_j|x)), the base
  // level that keeps outlier measurements from dominating. novelty_sigma > 0: C's standard
  // deviations as fractions of the person's half width and half height (PETS09 frames 1-397,
  // calibrated MOTA / IDF1, mean of seeds 0-2: 2.0 0.166 / 0.348, 1.0 0.350 / 0.365, 0.5
  // 0.449 / 0.445, 0.35 0.455 / 0.468, 0.25 0.452 / 0.473; rho 0.01 / 0.1 / 1 at 1.0: 0.297 /
  // 0.373, 0.350 / 0.365, 0.344 / 0.399; measured before injections founding objects took
  // slots before joins, after which 0.35 gives 0.395 / 0.435 and 1.0 0.345 / 0.388). A narrow
  // h pulls each ellipse onto its silhouette's core, so that neighbours' pixels at its gate's
  // edge do not drag it.
  double rho = 0.1;
  double novelty_sigma = 0.35;
  // Beyond the paper: the two external factors (N_in / (pi a b)) (N_in / N), the only terms that
  // depend on the axes, are raised to the power 1 + shape_weight N for N measurements (0: the
  // paper's L). As printed they span ~0.6 nats between a 12 x 30 px blob's inscribed ellipse and
  // one twice its area, against the product's tens of nats over N ~ 100 terms for a shift of a
  // few pixels: resampling then selects positions only and the axes wander (a synthetic 12 x 30
  // walker kept 22 x 48 px axes for 30 frames). Proportional to N, the factors keep the same
  // weight relative to the product at any resolution and grid.
  double shape_weight = 0.1;
  // y < foreground_threshold is a measurement (the KDE's y: 1 = background).
  double foreground_threshold = 0.5;
  // The measurement grid's step as a fraction of the person height h (at least 1 px): 0.05 is
  // 4 px for 85 px people, ~150 points per person; the product of §2.1 then runs over ~150
  // terms, not ~2500.
  double grid_step = 0.05;

  // ---- Association, novelty, injection, re-clustering (§2, Fig. 1).
  // A measurement belongs to the nearest object whose estimate ellipse, scaled by gate, holds it.
  double gate = 1.5;
  // n(z) > novelty_threshold: novel (n = 1 far from every object; 1 - e^{-1/2} = 0.39 on an
  // estimate's boundary when C matches its axes).
  double novelty_threshold = 0.5;
  // At most ceil(inject_fraction N) particles injected per step.
  double inject_fraction = 0.1;
  // A new object needs this fraction of a person's expected grid count of novel measurements
  // inside its first particle's ellipse; so does a step's injection in total.
  double min_object_fraction = 0.3;
  // Two objects whose centres are within merge_distance in units of the person's half width and
  // half height ((dx / (w/2))^2 + (dy / (h/2))^2 <= merge_distance^2) merge into the older: the
  // two halves of a split silhouette are about one half height apart, two people side by side
  // two half widths.
  double merge_distance = 1.2;
  // ... and two objects whose associated measurements together fit in merge_size times the person
  // size (w x h) merge: one silhouette that re-clustering split into two subsets (each subset's
  // centroid is a stable fixed point of the likelihood's product term, as in 2-means).
  double merge_size = 1.3;
  // ... unless their estimated velocities differ by more than merge_velocity person heights per
  // step (0 = off: every such pair merges). The halves of one silhouette move together; two
  // people who cross come as close but move apart, and merging them hands the survivor's label
  // to either one and the other a re-founded object's. 0.08 h is about a walker's own speed at
  // PETS09's 7 frames/s (benchmarks/pets09.py's docstring has the sweep).
  double merge_velocity = 0.08;
  // An object with fewer than keep_fraction x a person's grid count of measurements on
  // max_misses consecutive steps ends (>= 1). (PETS09 frames 1-397, 100 particles, seeds 0-2:
  // 0.1 kept objects on noise and ghosts alive, MOTA 0.037 against 0.234 with 0.3.)
  double keep_fraction = 0.3;
  int max_misses = 3;

  // ---- Motion and size, relative to the person height h (names as MultiBernoulliParams).
  // The people size prior (filters/person_prior.hpp), as the multi-Bernoulli tracker's: h given
  // or learnt from the foreground; widths size_aspect x h. Axes are clamped to [size_min,
  // size_max] x the prior's half width / half height; the §2.2 initialisation draws them
  // uniformly in that range, injections N(prior, (size_std prior)^2).
  PersonSizeParams size;
  // Perspective (issue 12, beyond the paper, whose §2.2 draws the axes from one "expected range of
  // sizes", noting that perspective makes people appear with different sizes): with size_by_row,
  // every person size above is taken at the ellipse's own row, h(y_foot) of the line learnt from
  // the foreground components' heights by foot row (PersonHeight::height_at_foot, as the
  // multi-Bernoulli tracker's size_by_row; the constant h while the data do not support a slope,
  // and never below the smallest people the line was fitted on): the axes' range and §2.2 /
  // injection draws, C of h(z|x) (per particle), the gate's minimum axes, the novelty, a
  // person's expected grid count (founding, keeping; never below the mean person's, see
  // count_scale) and the merge distances. PETS09-S2L1, tracker seeds 0-2, calibration fitted on
  // 1-397 (benchmarks/sir_tuning.py), MOTA / IDF1 without -> with: 1-397 0.479 / 0.408 -> 0.504 /
  // 0.485, 398-795 0.397 / 0.465 -> 0.686 / 0.494, all frames 0.438 / 0.412 -> 0.596 / 0.476:
  // with one person size the people near the camera (up to twice the median height) were cut
  // into two or more objects and their pixels fed false positives.
  bool size_by_row = true;
  // Per-frame noise standard deviations as fractions of h: position, velocity, axes.
  double sigma_xy = 0.03;
  double sigma_velocity = 0.02;
  double sigma_wh = 0.04;

  // ---- Reporting (beyond the paper; as MultiBernoulliParams).
  // Confirmation and lost-track memory (filters/track_management.hpp), as the multi-Bernoulli
  // tracker's defaults but relabel_overlap 0.1: an object that re-clustering ends in a pair
  // (merged or starved of pixels for max_misses steps) is re-founded a few frames later beside
  // its remembered box, moved on at its velocity, rarely on it. PETS09-S2L1, seeds 0-2 (as
  // size_by_row), MOTA / IDF1 with 0.3 -> 0.1: 1-397 0.504 / 0.485 -> 0.502 / 0.527, 398-795
  // 0.686 / 0.494 -> 0.699 / 0.522, all 0.596 / 0.476 -> 0.602 / 0.499 (65 -> 51 track ids for
  // 19 people; 0.05 the same within 0.002; lost_memory 60 or 100 with 0.1: within 0.005).
  // Colour appearance on (appearance_rate 0.05, appearance_sigma 0.15, appearance_distance 1.5;
  // used when step() is given the frame, as the sir pipeline does): when two people's blobs cover
  // each other the objects merge or bounce, and the labels went to whichever object was nearer;
  // the colours give them back (benchmarks/pets09_identity.py has the sweep on frames 1-397).
  TrackManagementParams management{5, 30, 0.1, 0.0, 0.05, 0.15, 1.5};
  // The reported box: the ellipse's bounding box (2a x 2b) calibrated to the annotation
  // convention, as MultiBernoulliParams' box. Defaults: the medians of the fits of
  // benchmarks/_foreground.py's fit_calibration on PETS09-S2L1 frames 1-397, tracker seeds 0-2
  // (benchmarks/sir_tuning.py prints them), clipped to the image (box_clip; as MB's: PETS09,
  // seeds 0-2, all frames, MOTA +0.008-0.009 on the crop2 / zoom1.25 development variants,
  // +0.001-0.003 at 768 x 576, 0.5x and 1.5x, IDF1 +0.000-0.003; benchmarks/pets09_identity.py).
  BoxCalibrationParams box{1.06, 0.93, 0.01, -0.06, true};

  std::uint64_t seed = 0;

  static const core::ParameterTable<ReclusteringSirParams>& table();
};

// InvalidArgument naming the parameter and its value.
void validate(const ReclusteringSirParams& params);

// The foreground measurements of y on a grid: the points (x, y) (pixel centres, px) of every
// step-th column and row (starting at step / 2) with y < threshold. InvalidArgument when y is not
// a non-empty CV_32FC1 image with values in [0, 1].
Eigen::Matrix2Xf grid_measurements(const cv::Mat& y, float threshold, int step);

// log L(Z | x) of §2.1 for an ellipse x = (cx, cy, a, b) over the measurements z (2 x N):
// shape_power (log(N_in / (pi a b)) + log(N_in / N)) + sum_j log(rho + exp(-d_j^2 / 2))
// (shape_power 1 is the paper's),
// d_j^2 = ((z_j - p)_x / sx)^2 + ((z_j - p)_y / sy)^2 (C = diag(sx^2, sy^2)). -inf when no
// measurement is inside the ellipse (N_in = 0) or there is none (N = 0).
double ellipse_log_likelihood(float cx, float cy, float a, float b,
                              const Eigen::Ref<const Eigen::Matrix2Xf>& z, double rho, float sx,
                              float sy, double shape_power = 1.0);

class ReclusteringSir {
 public:
  using Particles = smc::ParticleSet<float, 6>;  // (x, y, vx, vy, a, b), one per row
  using State = Eigen::Matrix<float, 6, 1>;

  struct Object {
    std::uint64_t label;
    int birth_frame;
    int misses = 0;            // consecutive steps without enough measurements
    Eigen::Matrix<float, 6, 1> estimate = Eigen::Matrix<float, 6, 1>::Zero();
    int count = 0;             // particles in its cluster
    double score = 0.0;        // N_in / N of the estimate over its measurements
    TrackRecord record;
  };

  ReclusteringSir(int width, int height, const ReclusteringSirParams& params = {});

  // One step on the background-subtracted image y (H x W float32 in [0, 1], 1 = background) and,
  // optionally, the frame it came from (8-bit BGR of y's size; empty: none), whose colours keep
  // the labels on the people when management.appearance_rate > 0 (step 9). Returns the reported
  // tracks in id order: the calibrated ellipse bounding box, score N_in / N, state = the estimate
  // (x, y, vx, vy, a, b).
  const Tracks& step(const cv::Mat& y, const cv::Mat& frame = cv::Mat());

  const Tracks& tracks() const { return tracks_; }
  const Particles& particles() const { return particles_; }
  // Cluster index of each particle: 0 free, k >= 1 the object objects()[k - 1].
  const std::vector<int>& clusters() const { return clusters_; }
  const std::vector<Object>& objects() const { return objects_; }
  const ReclusteringSirParams& params() const { return params_; }
  double person_height() const { return person_h_; }
  int grid_pixels() const { return grid_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int frame() const { return frame_; }

 private:
  void set_person_height(double h);
  void initialise();  // §2.2
  void predict();
  void associate();
  void weigh();
  void update_estimates();
  // Step 6 (Fig. 1): injection of particles near novel measurements; new objects.
  void inject();
  // The most likely free particle joins the object whose gate holds it or founds one.
  void place_best_free(const Particles::States& x, const Eigen::VectorXd& lw,
                       const std::vector<int>& novel);
  // A new object at s when its ellipse holds min_object_fraction of a person's expected grid
  // count (at its row) of novel measurements: its index + 1, or -1.
  int found_object(const State& s, const std::vector<int>& novel);
  // A particle drawn around `centre`: position N(centre, sigma_xy^2), velocity N(0, ...), axes
  // N(prior, (size_std prior)^2) clamped to the prior's range.
  State injection_state(const Eigen::Vector2f& centre);
  void recluster();
  void resample();
  // Step 9; the objects' colour histograms from `frame` when it is not empty.
  void report(const cv::Mat& y, const cv::Mat& frame);
  // The engine's reweight with each cluster's log-likelihoods shifted to keep its mass.
  void reweight_per_cluster(Eigen::VectorXd& log_lik);
  void end_object(std::size_t k);
  void remove_ended(std::vector<bool>& ended);
  // A person's expected number of grid measurements at the row scale s (the area of its
  // ellipse, (s w / 2) (s h / 2) pi, in grid cells).
  double expected_points(float s = 1.0f) const;
  // The person size at an ellipse centred on row cy, relative to person_height(): 1 unless
  // size_by_row and the line is learnt (row_scale_).
  float row_scale(float cy) const {
    if (row_scale_.empty()) return 1.0f;
    const float r = std::clamp(cy, 0.0f, float(height_ - 1));
    return row_scale_[std::size_t(r)];
  }
  // The scale of the measurement counts an object needs to start and to stay (min_object_fraction,
  // keep_fraction) at row cy: the row's, but never below the mean person's (1). Above the rows
  // where people walk, the line's small scales made the KDE's flicker in PETS09's windows
  // (specks of a few grid points) enough for an object (FP x9 on frames 1-397).
  float count_scale(float cy) const { return std::max(1.0f, row_scale(cy)); }
  // The person's half width and half height at row cy (px).
  Eigen::Vector2f half_size(float cy) const {
    const float s = row_scale(cy) * float(0.5 * person_h_);
    return {s * float(params_.size.size_aspect), s};
  }
  // Normalised squared distance of (x, y) to an object's estimate for association and
  // re-clustering: its axes, at least the person size's half width and height.
  float gate_d2(const Object& o, float x, float y) const;
  // The object (index + 1) whose gate holds (x, y) at the smallest gate_d2, or 0.
  int nearest_gate(float x, float y) const;
  // The measurements with novelty n(z) > novelty_threshold and their novelty (step 5).
  void novel_measurements(std::vector<int>& novel, std::vector<double>& novelty) const;
  // Two mean-shift steps from `centre` over the novel measurements in a person's ellipse.
  Eigen::Vector2f novel_centroid(const std::vector<int>& novel, Eigen::Vector2f centre) const;

  ReclusteringSirParams params_;
  int width_, height_;
  core::Rng rng_;
  PersonHeight person_height_;
  double person_h_ = 0.0;
  // size_by_row: [centre row] the person size of an ellipse centred there / person_h_.
  std::vector<float> row_scale_;
  int grid_ = 1;
  models::LinearTransition motion_;
  TrackManager management_;
  Particles particles_;
  std::vector<int> clusters_;
  std::vector<Object> objects_;
  std::uint64_t next_label_ = 1;
  int frame_ = 0;
  Tracks tracks_;
  // Per step.
  Eigen::Matrix2Xf z_;            // measurements
  std::vector<int> assoc_;        // per measurement: object index + 1, 0 = none
  std::vector<std::vector<int>> members_;  // per object + 1 (0: free): measurement indices
  std::vector<Eigen::Matrix2Xf> zsets_;
  Particles::States eps_, next_;
  std::vector<float> noise_;
  ForegroundColour colour_;
  std::vector<ColourHistogram> seen_;  // per object: its histogram at this step
};

}  // namespace vtrack::filters
