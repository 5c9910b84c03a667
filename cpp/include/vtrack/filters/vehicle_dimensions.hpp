#pragma once
// Vehicle dimensions from a calibrated road camera: the samplers of particle-filters-human-vehicle
// §3.3 on the §3.1 ray likelihood and the §3.2 priors (models/vehicle_observation.hpp), a
// per-vehicle estimator over a vehicle's passage and its light/heavy decision.
//
// The target at frame t (§3.2-3.3), x = (W, H, L):
//   pi_t(x) ∝ p(z_t | x) [sum_i p(x | x_{t-1}^i) or p(x | x*)] p(x | M),
// with p(z | x) the ray likelihood of §3.1, p(x | M) the class mixture of §3.2 (0 below the minimum
// sizes) and the rigid dynamic p(x_t | x_{t-1}). At a vehicle's first used frame there is no
// previous sample and the dynamic term is 1. Samplers (`sampler`):
//   * "mh": Metropolis-Hastings in WHL space (smc::metropolis_hastings, a Gaussian random walk of
//     proposal_scale metres). reference = "all" is the full acceptance ratio of §3.3 (O(N N_s));
//     "map" (the previous chain's kept sample of largest pi), "mean" (the previous point estimate)
//     and "random" (a uniformly drawn previous sample, Khan et al.) condition on one x* (O(N)).
//   * "ray": §3.3's samples on the ray, a 1-D chain on the height h of the point
//     a + (h / b_H)(b - a) (VehicleObservation::point_at_height), restricted to the segment where
//     every dimension is at least min_size (§3.1's constraints); the likelihood term is constant on
//     the ray and drops out. The proposal is a random walk in h of proposal_scale metres. Same
//     references as "mh".
//   * "discrete": §3.3's discrete state space: the projections y_m = L_t pi(x_m) of the class means
//     on the ray (clamped to the feasible segment), scored by p(y_m | y*) w_m N(y_m; x_m, S_m) with
//     y* the previous point estimate; the estimate is the best y_m, its class the MAP class.
//   * "rays" (beyond the paper; the default): a rigid vehicle's dimensions do not change, so the exact posterior
//     after frames 1..t is p(x | M) prod_k p(z_k | x). Each ray factor is a Gaussian in x,
//     exp(-1/2 (x - a_k)^T P_k S^-1 P_k (x - a_k)) with P_k the projector orthogonal to the ray,
//     so the product is exp(-1/2 (x^T A x - 2 g^T x)) with A = sum P_k S^-1 P_k and
//     g = sum P_k S^-1 P_k a_k: two running sums, O(1) per frame. The chain ("mh" moves) targets
//     that product times p(x | M); no dynamic term (it is the sigma -> 0 limit of the rigid
//     dynamic, without the information loss of conditioning on one x*).
// Point estimate: the sample mean (§3.3); the class: argmax_m of the mean over samples of
// p(m | x_i) (VehicleModelPrior::class_log_posteriors), the MAP class.
//
// Choices where the paper is silent (each a parameter):
//   * the rigid dynamic p(x_t | x_{t-1}) ∝ exp((x_t - x_{t-1})^T (x_t - x_{t-1})) in the paper, with
//     no sign and no scale: here N(x_t; x_{t-1}, dynamic_sigma^2 I). Not zero: the dimensions are
//     constant but each frame's estimate is uncertain, and a too tight dynamic would freeze the
//     first frame's (usually worst: farthest, smallest) estimate.
//   * the chain starts at the previous point estimate (projected on the ray for "ray"), or at the
//     first frame at the best discrete candidate, so a short burn-in suffices.
//   * frames used: a silhouette touching the image border (within border_margin_px) is cut by the
//     border, its far-most corner is not the vehicle's and its ray is wrong: it is not used. A ray
//     whose feasible segment is empty (a silhouette smaller than min_size from any height, e.g. a
//     degenerate polygon) is not used either. A vehicle with no used frame is reported as never
//     fully in view, with no dimensions and no class. Nor is a view whose box length is resolved
//     too coarsely (VehicleObservation::edge_resolution, near and far edge combined, metres of road
//     per pixel): the ray through the far corner then says little about the length, yet with S in
//     metres for every view it weighs as much as a near one; and it is there, in the distance,
//     that perspective runs following vehicles together into one blob. Under a 7.5 m gantry
//     looking along its lane a pixel row is 7 m of road at 200 m, and vehicles emerging from the
//     distance one behind the other came as one outline for tens of frames: their rays (a length
//     tens of metres too long, read by the far, shallow ray as a taller vehicle) outvoted the near
//     views, and the near views then gave the rays' product a length at min_size (cars as L 1.0 m,
//     H 2.4 m; an 8 m truck as 1.0 m, light).
//     The cut is per vehicle, over its whole passage: a view is used when its resolution r is
//     at most max(max_length_resolution, length_resolution_factor * r_best), r_best the best
//     resolution among the vehicle's usable views (border and min_size tests passed). A fixed cut
//     alone can leave a long vehicle seen by a low camera no view at all (it never comes near
//     enough whole); relaxing it to a factor of the vehicle's own best keeps its best-resolved
//     views, and where some view passes the fixed cut it changes nothing. Which frames: every
//     usable frame of the passage, decided against the best of them all. Online, r_best only
//     improves, so the bound only tightens: a view refused when it came is never needed later,
//     and a view used earlier is dropped (its ray leaves the "rays" sums, its point estimate the
//     "mean" decision) when a better view tightens the bound; the chain re-runs on each accepted
//     view, so the last posterior is always the one given exactly the used views. (For the x*
//     samplers a dropped frame's chain has already shaped x* of the next frames.) update() thus
//     says whether a frame is used so far; frames_used is the final count.
//   * outlying views ("rays", outlier_gate): the product of the rays is a least-squares fit, and a
//     minority of outlines that are not the vehicle's alone (another vehicle's pixels joined to
//     it, a part hidden by a nearer one) pulls it far off, down to a length at min_size (the
//     figures: benchmarks/vehicles.py). So the answer is refitted without the views whose ray
//     lies farther than outlier_gate from the fitted dimensions, in the likelihood's own units
//     (the Mahalanobis distance under S across the ray: 3 = 0.75 m with the default S), twice,
//     keeping the fit when no view or every view would go: a trimmed least squares. The frames
//     left out are not counted in frames_used. 0 = off. The per-frame posteriors (update(),
//     posterior()) are not refitted; only the answer (estimate()) is.
//   * far views ("rays", far_view_gate): the views the resolution cut leaves out are held, and
//     those whose ray lies within far_view_gate of the refitted answer (the same units) join it,
//     each with S widened by its resolution over the cut's (S (r / r_cut)^2: a pixel there is that
//     many times more metres, and an outline a pixel off moves its far corner as far): the chain
//     re-runs on the kept views and those far ones, which count in frames_used. Why: the
//     views within the cut are the near ones, whose rays come from much the same direction, so
//     together they fix two of W, H, L well and leave the third to the class prior -- and Table
//     1's truck is 2.0 +- 0.2 m wide, a van's size: from exact silhouettes, heavies came out
//     0.2-0.6 m narrow and 0.4-3 m short. A far view's shallow ray crosses them and fixes that
//     third dimension. The cut is there for the far outlines that are no one vehicle's (two
//     vehicles emerging from the distance as one blob, metres too long): their rays miss the
//     answer of the near views and stay out (the gate is under S itself, not the widened one: a
//     widened gate let them in). Default 3, the outlier gate's: a far view joins when it would be
//     no outlier among the near ones. Unwidened, far views with 1-2 px of outline noise made cars
//     too tall (benchmarks/vehicles.py: the figures). 0 = off.
//   * the per-vehicle decision (decision): "mean" averages the per-frame point estimates and the
//     per-frame class probabilities over the used frames (every full view counts once: with the x*
//     variants a frame's posterior remembers the earlier ones only through x*); "last" takes the
//     last used frame's posterior; "auto" (the default) is "last" for "rays", whose last posterior
//     is the posterior given every used frame, and "mean" for the others, whose last posterior is
//     mostly the last frame's ray (benchmarks/vehicles.py: "last" costs the "ray" sampler 1-15
//     points of light accuracy with 1-2 px of outline noise, and gains "rays" 0-3).
//   * light/heavy (light_heavy_rule): "volume" (the default; §3.4 classifies "according to their
//     volume") calls a vehicle heavy when W H L >= heavy_volume; "class" takes the MAP class's
//     `heavy` flag (Table 1: truck and bus heavy). heavy_volume = 45 m^3 lies between the largest
//     light vehicles (3.5 t vans: ~2.1 x 2.8 x 7 m = 41 m^3) and the smallest rigid trucks
//     (~2.4 x 2.9 x 7 m = 49 m^3; EU Directive 96/53/EC dimensions). "class" with Table 1 calls
//     vans trucks (Table 1's truck is 2.0 x 2.5 x 7 m, a van's size) and, its sigmas being
//     0.1-0.3 m, follows any bias of the dimensions into the wrong class (benchmarks/vehicles.py).
//     Beyond the paper, "volume" also calls a vehicle heavy when H >= heavy_height, 3.0 m: the same
//     sources put the tallest light vehicles (high-roof 3.5 t vans) at ~2.8-2.9 m and rigid trucks
//     at ~2.9 m and up, so a light vehicle must come out 0.1-0.2 m too tall to cross it. Why: the
//     volume multiplies the three dimensions, and W and L are the ones a partial outline loses --
//     a heavy partly hidden by a nearer vehicle, or followed by a track over only part of its
//     passage, comes out short or narrow (a 9.6 m truck as 1.9 x 3.1 x 7.3 m = 44 m^3, 10.7 m
//     trucks as L 2.7-3.4 m), while its height, read from the roof's far corner in a near view,
//     holds. 3.0 m keeps a margin over the vans' estimated heights and over real high-roof vans;
//     the values measured are in benchmarks/vehicles.py. 0 = off. Nor does the volume count a
//     width beyond max_vehicle_width, 2.6 m: no road vehicle is wider (the same Directive: 2.55 m,
//     2.60 m refrigerated), so more is another vehicle's pixels -- two cars abreast, receding from
//     the camera as one blob for their whole passage, came out 3.1-3.7 m wide and 7 m long, heavy
//     by volume, though 2.1-2.2 m tall. The smallest heavies (~2.9 m tall, 7 m long) reach 45 m^3
//     at 2.2 m wide, so capping a width over 2.6 m turns none light. 0 = off.
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/parameters.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/models/camera.hpp"
#include "vtrack/models/vehicle_observation.hpp"
#include "vtrack/smc/mcmc.hpp"

namespace vtrack::filters {

enum class VehicleSampler { Mh, Ray, Discrete, Rays };
enum class LightHeavyRule { Class, Volume };
enum class VehicleDecision { Auto, Mean, Last };
const std::vector<std::pair<std::string, VehicleSampler>>& vehicle_sampler_names();
const std::vector<std::pair<std::string, LightHeavyRule>>& light_heavy_rule_names();
const std::vector<std::pair<std::string, VehicleDecision>>& vehicle_decision_names();

struct VehicleEstimatorParams {
  // "rays" (the extension above) by default: on benchmarks/vehicles.py's generated scenes
  // (5 set-ups x 60 vehicles, outline noise 0-2 px) it classifies 100 % of light and heavy
  // vehicles with W, H, L errors of 0.1-0.2, 0.0-0.8, 0.3-1.1 m, against §3.3's "ray" 93-100 %
  // of light (1.2-1.7 m on L); "ray" stays one setting away.
  VehicleSampler sampler = VehicleSampler::Rays;
  // x* of §3.3: "map" (the paper: "much better performance selecting the most likely sample"),
  // "mean", "random" (Khan et al.), or "all" (the full acceptance ratio).
  smc::McmcReference reference = smc::McmcReference::Map;
  // N_s, kept samples per frame, and B: the chains start at the previous estimate, so a short
  // burn-in suffices; 50/25 to 1000/500 change no accuracy by more than a vehicle in 300
  // (benchmarks/vehicles.py --ablations) and the cost is linear in B + c N_s.
  int n_particles = 100;
  int burn_in = 50;
  int thinning = 1;       // c
  // Random-walk step (metres): of each dimension for "mh" and "rays", of the height on the ray
  // for "ray".
  double proposal_scale = 0.2;
  double dynamic_sigma = 0.3;  // metres, the rigid dynamic's standard deviation (see above)
  // §3.1's "positive and minimum height, width and length" (W, H, L), metres.
  std::array<double, 3> min_size = {0.4, 0.6, 1.0};
  models::RayLikelihoodParams likelihood;  // S of §3.1 and the silhouette densification
  LightHeavyRule light_heavy_rule = LightHeavyRule::Volume;
  double heavy_volume = 45.0;  // m^3, for light_heavy_rule = "volume" (see above)
  double heavy_height = 3.0;   // m, for "volume": also heavy when H >= this (see above); 0 = off
  double max_vehicle_width = 2.6;  // m, for "volume": the volume counts W up to this (see above); 0 = off
  VehicleDecision decision = VehicleDecision::Auto;
  double border_margin_px = 1.0;  // a silhouette this close to the image border is cut by it
  // The resolution cut of "frames used": a view is used when its length's resolution (metres of
  // road per pixel) is at most max(max_length_resolution, length_resolution_factor * the
  // vehicle's best). 0 and 0 = every view; factor 0 = the fixed cut alone. The default is the
  // factor alone, 4: a ratio of one vehicle's own views, so the same views at any image
  // resolution and lens (a fixed 2 m per pixel keeps 3x fewer views at a third of the
  // resolution, and none of a lorry under a low mast), and on the gantry it drops the far merged
  // views a fixed 2 m dropped (benchmarks/vehicles.py, tuning seeds: the tables are there).
  double max_length_resolution = 0.0;
  double length_resolution_factor = 4.0;
  // "rays": views whose ray lies farther than this from the fit (Mahalanobis under S) are left out
  // of the answer (see "outlying views" above); 0 = every used view.
  double outlier_gate = 3.0;
  // "rays": views beyond the resolution cut whose ray lies within this of the answer join it
  // (Mahalanobis under S; see "far views" above); 0 = off.
  double far_view_gate = 3.0;
  std::uint64_t seed = 0;

  static const core::ParameterTable<VehicleEstimatorParams>& table();
};
void validate(const VehicleEstimatorParams& params);

// One frame's posterior of one vehicle.
struct VehiclePosterior {
  Eigen::MatrixXd samples;     // N_s x 3 (W, H, L); one row for "discrete"
  Eigen::VectorXd log_target;  // log pi of each sample
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();  // the point estimate
  Eigen::Vector3d map = Eigen::Vector3d::Zero();   // the sample of largest pi
  Eigen::VectorXd class_probability;               // mean over samples of p(m | x_i)
  double acceptance_rate = 0.0;
};

// The running sums of the "rays" sampler (A, g above).
struct RaySums {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double c = 0.0;  // sum a_k^T P_k S^-1 P_k a_k, so that the sums give the squared distance itself
  int frames = 0;
  void add(const models::VehicleObservation& obs, const models::RayLikelihoodParams& likelihood);
  void add(const RaySums& other, double weight = 1.0);  // weight: S of `other` divided by it
  // -1/2 (x^T A x - 2 g^T x): the log of the product of the added ray likelihoods, up to a constant.
  double log_likelihood(const Eigen::Vector3d& x) const { return -0.5 * x.dot(A * x) + g.dot(x); }
  // x^T A x - 2 g^T x + c: for one view's term, the squared Mahalanobis distance (under S) of x
  // from its ray.
  double squared_distance(const Eigen::Vector3d& x) const { return x.dot(A * x) - 2.0 * g.dot(x) + c; }
};

// One frame of §3.3's samplers: the posterior at this frame given the previous one (nullptr at
// the vehicle's first frame) and, for "rays", the sums including this frame. The observation's
// feasible segment must not be empty (InvalidArgument otherwise).
VehiclePosterior sample_vehicle_frame(const models::VehicleObservation& obs, const models::VehicleModelPrior& prior,
                                      const VehiclePosterior* previous, const RaySums& rays,
                                      const VehicleEstimatorParams& params, core::Rng& rng);

// The per-vehicle answer over its passage.
struct VehicleEstimate {
  int vehicle_id = 0;
  bool valid = false;         // false: never fully in view (no used frame); no dimensions, no class
  int class_index = -1;       // into the models
  std::string class_name;     // "" when not valid
  bool heavy = false;
  Eigen::Vector3d dimensions = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::VectorXd class_probability;
  int first_frame = 0, last_frame = 0;  // the frames the vehicle was seen in (given to update)
  int frames_seen = 0, frames_used = 0;
};

class VehicleDimensionEstimator {
 public:
  // `models` empty = Table 1. Validates the models and the parameters.
  VehicleDimensionEstimator(models::Camera camera, std::vector<models::VehicleModel> models = {},
                            VehicleEstimatorParams params = {});

  // One frame's silhouette of one vehicle: an image polygon (2 x n pixels) or an image box.
  // `frame` is the caller's frame number (non-decreasing per vehicle). Returns whether the frame
  // was used (see "frames used"). InvalidArgument for a silhouette the geometry refuses (NaN, a
  // vertex above the horizon, fewer than 3 vertices).
  bool update_polygon(int vehicle_id, int frame, const Eigen::Ref<const Eigen::Matrix2Xd>& polygon);
  bool update_box(int vehicle_id, int frame, double x, double y, double w, double h);

  // The frame after the vehicle's last (1 for a new vehicle), for callers that number frames per vehicle.
  int next_frame(int vehicle_id) const;
  VehicleEstimate estimate(int vehicle_id) const;  // InvalidArgument for an unknown id
  // Releases a vehicle's state (its per-frame terms and last posterior): a caller done with it
  // (the video pipeline, streaming) keeps the memory bounded. The id is then unknown; updating
  // it again starts a new vehicle. No-op for an unknown id.
  void forget(int vehicle_id) { tracks_.erase(vehicle_id); }
  std::vector<VehicleEstimate> estimates() const;  // every vehicle, by id
  // The last used frame's posterior (nullptr before any used frame).
  const VehiclePosterior* posterior(int vehicle_id) const;
  const models::Camera& camera() const { return camera_; }
  const models::VehicleModelPrior& prior() const { return prior_; }
  const VehicleEstimatorParams& params() const { return params_; }

 private:
  struct Track {
    core::Rng rng;
    int first_frame = 0, last_frame = 0, frames_seen = 0;
    std::vector<Eigen::Vector3d> means;             // per used frame
    std::vector<Eigen::VectorXd> class_probability; // per used frame
    std::vector<double> resolution;                 // per used frame, edge_resolution of the length
    std::vector<RaySums> ray_terms;                 // per used frame ("rays"): its own factor
    std::vector<std::pair<double, RaySums>> far_views;  // "rays", far_view_gate: beyond the cut (resolution, term)
    double best_resolution = std::numeric_limits<double>::infinity();
    VehiclePosterior last;
    RaySums rays;
  };
  double resolution_bound(double best) const;
  int refit_without_outliers(const Track& t, VehiclePosterior& post) const;
  int add_far_views(const Track& t, const std::vector<const RaySums*>& kept, VehiclePosterior& post,
                    core::Rng& rng) const;
  void rechain(const RaySums& sums, VehiclePosterior& post, core::Rng& rng) const;
  void drop_coarse_views(Track& t) const;
  Track& track(int vehicle_id, int frame);
  bool touches_border(const Eigen::Ref<const Eigen::Matrix2Xd>& polygon) const;
  bool add(Track& t, const models::VehicleObservation& obs);

  models::Camera camera_;
  models::VehicleModelPrior prior_;
  VehicleEstimatorParams params_;
  std::map<int, Track> tracks_;
};

}  // namespace vtrack::filters
