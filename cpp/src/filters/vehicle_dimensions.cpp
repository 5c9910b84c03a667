#include "vtrack/filters/vehicle_dimensions.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/smc/mh.hpp"

namespace vtrack::filters {

namespace {

using core::kInf;
// Passes of the outlier refit (header, "outlying views"): the second drops views that the first
// fit's outliers had kept within the gate. Two as prototyped and measured (benchmarks/vehicles.py);
// other counts were not tried.
constexpr int kOutlierPasses = 2;

using models::VehicleModelPrior;
using models::VehicleObservation;

// log p(x | M) for one hypothesis, allocation-free (the chains call it per proposal; the batched
// VehicleModelPrior::log_density allocates per call). The same mixture: w_m N(x; x_m, S_m), 0
// below min_size.
class Mixture {
 public:
  Mixture(const VehicleModelPrior& prior, const std::array<double, 3>& min_size) {
    const auto& models = prior.params().models;
    const auto m = static_cast<Eigen::Index>(models.size());
    means_.resize(3, m);
    inv_sigma_.resize(3, m);
    log_constant_.resize(m);
    double total = 0.0;
    for (const auto& c : models) total += c.weight;
    for (Eigen::Index i = 0; i < m; ++i) {
      const auto& c = models[static_cast<std::size_t>(i)];
      means_.col(i) = c.mean;
      inv_sigma_.col(i) = c.sigma.cwiseInverse();
      log_constant_(i) = std::log(c.weight / total) - 1.5 * std::log(2.0 * M_PI) - c.sigma.array().log().sum();
    }
    min_size_ = Eigen::Vector3d(min_size[0], min_size[1], min_size[2]);
  }
  // log w_m N(x; x_m, S_m) of class m.
  double component(const Eigen::Vector3d& x, Eigen::Index m) const {
    return log_constant_(m) - 0.5 * ((x - means_.col(m)).cwiseProduct(inv_sigma_.col(m))).squaredNorm();
  }
  double operator()(const Eigen::Vector3d& x) const {
    if ((x.array() < min_size_.array()).any()) return -kInf;
    double top = -kInf, sum = 0.0;
    for (Eigen::Index m = 0; m < means_.cols(); ++m) {
      const double v = component(x, m);
      if (v > top) {
        sum = sum * std::exp(top - v) + 1.0;
        top = v;
      } else {
        sum += std::exp(v - top);
      }
    }
    return top + std::log(sum);
  }
  Eigen::Index size() const { return means_.cols(); }
  Eigen::Vector3d mean(Eigen::Index m) const { return means_.col(m); }

 private:
  Eigen::Matrix3Xd means_, inv_sigma_;
  Eigen::VectorXd log_constant_;
  Eigen::Vector3d min_size_;
};

// §3.1's ray likelihood for one hypothesis: y = the foot of the perpendicular from x to the ray
// (= L pi, models::project_onto_ray), -1/2 (y - x)^T S^-1 (y - x).
struct RayTerm {
  Eigen::Vector3d a, direction, inv_var;
  RayTerm(const VehicleObservation& obs, const models::RayLikelihoodParams& p)
      : a(obs.a), direction((obs.b - obs.a).normalized()),
        inv_var(1.0 / (p.sigma_w * p.sigma_w), 1.0 / (p.sigma_h * p.sigma_h), 1.0 / (p.sigma_l * p.sigma_l)) {}
  double operator()(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d u = x - a;
    const Eigen::Vector3d r = u - direction.dot(u) * direction;
    return -0.5 * r.cwiseAbs2().dot(inv_var);
  }
};

// The rigid dynamic's log density (up to a constant) against x* or, for reference "all", the
// log of sum_i p(x | x_{t-1}^i). Zero at the first frame.
class Dynamic {
 public:
  Dynamic(const VehiclePosterior* previous, const VehicleEstimatorParams& p, core::Rng& rng)
      : inv_var_(1.0 / (p.dynamic_sigma * p.dynamic_sigma)) {
    if (previous == nullptr) return;
    active_ = true;
    switch (p.reference) {
      case smc::McmcReference::All: all_ = previous->samples; break;
      case smc::McmcReference::Map: reference_ = previous->map; break;
      case smc::McmcReference::Mean: reference_ = previous->mean; break;
      case smc::McmcReference::Random: {
        const auto n = static_cast<std::uint64_t>(previous->samples.rows());
        reference_ = previous->samples.row(static_cast<Eigen::Index>(rng() % n)).transpose();
        break;
      }
    }
  }
  double operator()(const Eigen::Vector3d& x) const {
    if (!active_) return 0.0;
    if (all_.size() == 0) return -0.5 * inv_var_ * (x - reference_).squaredNorm();
    double top = -kInf, sum = 0.0;  // log-sum-exp over the previous samples, one pass
    for (Eigen::Index i = 0; i < all_.rows(); ++i) {
      const double v = -0.5 * inv_var_ * (x - all_.row(i).transpose()).squaredNorm();
      if (v > top) {
        sum = sum * std::exp(top - v) + 1.0;
        top = v;
      } else {
        sum += std::exp(v - top);
      }
    }
    return top + std::log(sum);
  }
  bool active() const { return active_; }
  // Where the chain starts: x* or the previous samples' mean.
  Eigen::Vector3d centre() const { return all_.size() ? Eigen::Vector3d(all_.colwise().mean().transpose()) : reference_; }

 private:
  double inv_var_;
  bool active_ = false;
  Eigen::Vector3d reference_ = Eigen::Vector3d::Zero();
  Eigen::MatrixXd all_;
};

Eigen::Vector3d min_size_of(const VehicleEstimatorParams& p) { return {p.min_size[0], p.min_size[1], p.min_size[2]}; }

// §3.3's discrete candidates: the class means projected on the ray, clamped to the feasible
// segment; the score of each is log p(y_m | y*) + log w_m N(y_m; x_m, S_m).
struct Discrete {
  Eigen::Matrix3Xd candidates;
  Eigen::VectorXd scores;
  Eigen::Index best = 0;
};
Discrete discrete_candidates(const VehicleObservation& obs, const Mixture& mixture, const Dynamic& dynamic,
                             std::pair<double, double> heights) {
  Discrete d;
  d.candidates.resize(3, mixture.size());
  d.scores.resize(mixture.size());
  const Eigen::Vector3d direction = (obs.b - obs.a) / obs.b.y();  // d x / d h on the ray
  for (Eigen::Index m = 0; m < mixture.size(); ++m) {
    // The foot of the perpendicular (= L pi) is a + h direction with h below.
    const double h = direction.dot(mixture.mean(m) - obs.a) / direction.squaredNorm();
    d.candidates.col(m) = obs.point_at_height(std::clamp(h, heights.first, heights.second));
    d.scores(m) = dynamic(d.candidates.col(m)) + mixture.component(d.candidates.col(m), m);
  }
  d.scores.maxCoeff(&d.best);
  return d;
}

// Fills mean, map and class probabilities from the samples and their log pi.
void summarise(VehiclePosterior& post, const VehicleModelPrior& prior) {
  post.mean = post.samples.colwise().mean().transpose();
  Eigen::Index best = 0;
  post.log_target.maxCoeff(&best);
  post.map = post.samples.row(best).transpose();
  const Eigen::MatrixXd logp = prior.class_log_posteriors(post.samples.transpose());
  post.class_probability = logp.array().exp().rowwise().mean().matrix();
}

// A 1-D random walk on the height of the point on the ray.
struct HeightProposal {
  double scale;
  double propose(const Eigen::VectorXd& from, Eigen::VectorXd& to, core::Rng& rng) const {
    to[0] = from[0] + scale * rng.normal();
    return 0.0;
  }
};

VehiclePosterior ray_chain(const VehicleObservation& obs, const Mixture& mixture, const Dynamic& dynamic,
                           std::pair<double, double> heights, const Eigen::Vector3d& start,
                           const VehicleEstimatorParams& p, core::Rng& rng) {
  const Eigen::Vector3d direction = (obs.b - obs.a) / obs.b.y();
  auto log_target = [&](const Eigen::VectorXd& h) {
    if (!(h[0] >= heights.first && h[0] <= heights.second)) return -kInf;
    const Eigen::Vector3d x = obs.a + h[0] * direction;
    return dynamic(x) + mixture(x);
  };
  const double h0 = std::clamp(direction.dot(start - obs.a) / direction.squaredNorm(), heights.first, heights.second);
  HeightProposal proposal{p.proposal_scale};
  const smc::ChainResult chain = smc::metropolis_hastings(
      log_target, Eigen::VectorXd::Constant(1, h0), smc::ChainParams{p.n_particles, p.burn_in, p.thinning},
      proposal, rng);
  VehiclePosterior post;
  post.samples = (chain.samples * direction.transpose()).rowwise() + obs.a.transpose();
  post.log_target = chain.log_target;
  post.acceptance_rate = chain.acceptance_rate();
  return post;
}

template <class LogTarget>
VehiclePosterior space_chain(const LogTarget& log_target, const Eigen::Vector3d& start,
                             const VehicleEstimatorParams& p, core::Rng& rng) {
  smc::RandomWalkProposal proposal(p.proposal_scale * Eigen::Matrix3d::Identity());
  Eigen::VectorXd x0(3);
  for (int k = 0; k < 3; ++k) x0[k] = start[k];  // (GCC 12 warns on the vectorised copy of a Vector3d)
  smc::ChainResult chain = smc::metropolis_hastings(
      [&](const Eigen::VectorXd& x) { return log_target(Eigen::Vector3d(x[0], x[1], x[2])); }, std::move(x0),
      smc::ChainParams{p.n_particles, p.burn_in, p.thinning}, proposal, rng);
  VehiclePosterior post;
  post.samples = std::move(chain.samples);
  post.log_target = std::move(chain.log_target);
  post.acceptance_rate = chain.acceptance_rate();
  return post;
}

}  // namespace

const std::vector<std::pair<std::string, VehicleSampler>>& vehicle_sampler_names() {
  static const std::vector<std::pair<std::string, VehicleSampler>> names{
      {"ray", VehicleSampler::Ray}, {"mh", VehicleSampler::Mh}, {"discrete", VehicleSampler::Discrete},
      {"rays", VehicleSampler::Rays}};
  return names;
}
const std::vector<std::pair<std::string, LightHeavyRule>>& light_heavy_rule_names() {
  static const std::vector<std::pair<std::string, LightHeavyRule>> names{{"volume", LightHeavyRule::Volume},
                                                                         {"class", LightHeavyRule::Class}};
  return names;
}
const std::vector<std::pair<std::string, VehicleDecision>>& vehicle_decision_names() {
  static const std::vector<std::pair<std::string, VehicleDecision>> names{
      {"auto", VehicleDecision::Auto}, {"mean", VehicleDecision::Mean}, {"last", VehicleDecision::Last}};
  return names;
}

const core::ParameterTable<VehicleEstimatorParams>& VehicleEstimatorParams::table() {
  using P = VehicleEstimatorParams;
  static const auto t = core::ParameterTable<P>()
                            .add_choice("sampler", &P::sampler, vehicle_sampler_names())
                            .add_choice("reference", &P::reference, smc::mcmc_reference_names())
                            .add("n_particles", &P::n_particles)
                            .add("burn_in", &P::burn_in)
                            .add("thinning", &P::thinning)
                            .add("proposal_scale", &P::proposal_scale)
                            .add("dynamic_sigma", &P::dynamic_sigma)
                            .add("min_size", &P::min_size)
                            .include(&P::likelihood)
                            .add_choice("light_heavy_rule", &P::light_heavy_rule, light_heavy_rule_names())
                            .add("heavy_volume", &P::heavy_volume)
                            .add("heavy_height", &P::heavy_height)
                            .add("max_vehicle_width", &P::max_vehicle_width)
                            .add_choice("decision", &P::decision, vehicle_decision_names())
                            .add("border_margin_px", &P::border_margin_px)
                            .add("max_length_resolution", &P::max_length_resolution)
                            .add("length_resolution_factor", &P::length_resolution_factor)
                            .add("outlier_gate", &P::outlier_gate)
                            .add("far_view_gate", &P::far_view_gate)
                            .add("seed", &P::seed);
  return t;
}

void validate(const VehicleEstimatorParams& p) {
  require(p.n_particles >= 1 && p.n_particles <= core::kMaxParticles, "n_particles", p.n_particles,
          "in [1, 1000000]");
  require(p.burn_in >= 0, "burn_in", p.burn_in, ">= 0");
  require(p.thinning >= 1, "thinning", p.thinning, ">= 1");
  require(p.proposal_scale > 0.0 && std::isfinite(p.proposal_scale), "proposal_scale", p.proposal_scale,
          "a positive finite number (metres)");
  require(p.dynamic_sigma > 0.0 && std::isfinite(p.dynamic_sigma), "dynamic_sigma", p.dynamic_sigma,
          "a positive finite number (metres)");
  for (double v : p.min_size) require(v >= 0.0 && std::isfinite(v), "min_size", v, "three finite numbers >= 0");
  models::validate(p.likelihood);
  require(p.heavy_volume > 0.0 && std::isfinite(p.heavy_volume), "heavy_volume", p.heavy_volume,
          "a positive finite number (m^3)");
  require(p.heavy_height >= 0.0 && std::isfinite(p.heavy_height), "heavy_height", p.heavy_height,
          "a finite number >= 0 (metres; 0: off)");
  require(p.max_vehicle_width >= 0.0 && std::isfinite(p.max_vehicle_width), "max_vehicle_width",
          p.max_vehicle_width, "a finite number >= 0 (metres; 0: off)");
  require(p.border_margin_px >= 0.0 && std::isfinite(p.border_margin_px), "border_margin_px", p.border_margin_px,
          "a finite number >= 0 (pixels)");
  require(p.max_length_resolution >= 0.0 && std::isfinite(p.max_length_resolution), "max_length_resolution",
          p.max_length_resolution, "a finite number >= 0 (metres per pixel; 0: no fixed cut)");
  require(p.length_resolution_factor == 0.0 || (p.length_resolution_factor >= 1.0 &&
                                                std::isfinite(p.length_resolution_factor)),
          "length_resolution_factor", p.length_resolution_factor,
          "0 (off) or a finite number >= 1 (a factor of the vehicle's best view's resolution)");
  require(p.outlier_gate >= 0.0 && std::isfinite(p.outlier_gate), "outlier_gate", p.outlier_gate,
          "a finite number >= 0 (Mahalanobis distance under S; 0: off)");
  require(p.far_view_gate >= 0.0 && std::isfinite(p.far_view_gate), "far_view_gate", p.far_view_gate,
          "a finite number >= 0 (Mahalanobis distance under S; 0: off)");
}

void RaySums::add(const VehicleObservation& obs, const models::RayLikelihoodParams& p) {
  // P S^-1 P with P = I - d d^T the projector orthogonal to the ray: (y - x)^T S^-1 (y - x) =
  // (x - a)^T P S^-1 P (x - a).
  const Eigen::Vector3d d = (obs.b - obs.a).normalized();
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
  const Eigen::Vector3d inv_var(1.0 / (p.sigma_w * p.sigma_w), 1.0 / (p.sigma_h * p.sigma_h),
                                1.0 / (p.sigma_l * p.sigma_l));
  const Eigen::Matrix3d M = P * inv_var.asDiagonal() * P;
  A += M;
  g += M * obs.a;
  c += obs.a.dot(M * obs.a);
  ++frames;
}

void RaySums::add(const RaySums& other, double weight) {
  A += weight * other.A;
  g += weight * other.g;
  c += weight * other.c;
  frames += other.frames;
}

VehiclePosterior sample_vehicle_frame(const VehicleObservation& obs, const VehicleModelPrior& prior,
                                      const VehiclePosterior* previous, const RaySums& rays,
                                      const VehicleEstimatorParams& p, core::Rng& rng) {
  const auto heights = obs.feasible_heights(min_size_of(p));
  if (!(heights.first <= heights.second)) {
    throw InvalidArgument("the observation's ray has no dimensions above min_size");
  }
  const Mixture mixture(prior, p.min_size);
  // "rays" carries its memory in the sums: no dynamic term.
  const Dynamic dynamic(p.sampler == VehicleSampler::Rays ? nullptr : previous, p, rng);
  const Discrete discrete = discrete_candidates(obs, mixture, dynamic, heights);
  const Eigen::Vector3d start = dynamic.active() ? dynamic.centre()
                                : previous != nullptr ? previous->mean
                                                      : Eigen::Vector3d(discrete.candidates.col(discrete.best));
  VehiclePosterior post;
  switch (p.sampler) {
    case VehicleSampler::Discrete: {
      post.samples = discrete.candidates.col(discrete.best).transpose();
      post.log_target = Eigen::VectorXd::Constant(1, discrete.scores(discrete.best));
      summarise(post, prior);
      // §3.3: the class is the candidate's; the probabilities are the normalised scores.
      const Eigen::ArrayXd e = (discrete.scores.array() - discrete.scores.maxCoeff()).exp();
      post.class_probability = (e / e.sum()).matrix();
      return post;
    }
    case VehicleSampler::Ray: post = ray_chain(obs, mixture, dynamic, heights, start, p, rng); break;
    case VehicleSampler::Mh: {
      const RayTerm ray(obs, p.likelihood);
      post = space_chain([&](const Eigen::Vector3d& x) { return ray(x) + dynamic(x) + mixture(x); }, start, p, rng);
      break;
    }
    case VehicleSampler::Rays:
      post = space_chain([&](const Eigen::Vector3d& x) { return rays.log_likelihood(x) + mixture(x); }, start, p, rng);
      break;
  }
  summarise(post, prior);
  return post;
}

// ---- the per-vehicle estimator ------------------------------------------------------------------

namespace {
models::VehiclePriorParams prior_params(std::vector<models::VehicleModel> models, const VehicleEstimatorParams& p) {
  validate(p);
  models::VehiclePriorParams out;
  if (!models.empty()) out.models = std::move(models);
  out.min_size = min_size_of(p);
  return out;
}

// A per-vehicle random stream: splitmix64 of the seed and the id, so a vehicle's samples do not
// depend on the other vehicles or the order of the updates.
std::uint64_t vehicle_seed(std::uint64_t seed, int vehicle_id) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (static_cast<std::uint64_t>(static_cast<std::uint32_t>(vehicle_id)) + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
}  // namespace

VehicleDimensionEstimator::VehicleDimensionEstimator(models::Camera camera, std::vector<models::VehicleModel> models,
                                                     VehicleEstimatorParams params)
    : camera_(std::move(camera)), prior_(prior_params(std::move(models), params)), params_(params) {}

VehicleDimensionEstimator::Track& VehicleDimensionEstimator::track(int vehicle_id, int frame) {
  auto it = tracks_.find(vehicle_id);
  if (it == tracks_.end()) {
    Track t;
    t.rng = core::Rng(vehicle_seed(params_.seed, vehicle_id));
    t.first_frame = t.last_frame = frame;
    it = tracks_.emplace(vehicle_id, std::move(t)).first;
  } else if (frame < it->second.last_frame) {
    throw InvalidArgument("vehicle " + std::to_string(vehicle_id) + ": frame " + std::to_string(frame) +
                          " is before its last frame " + std::to_string(it->second.last_frame));
  }
  it->second.last_frame = frame;
  ++it->second.frames_seen;
  return it->second;
}

bool VehicleDimensionEstimator::touches_border(const Eigen::Ref<const Eigen::Matrix2Xd>& polygon) const {
  const auto& c = camera_.calibration();
  if (c.image_width <= 0 || c.image_height <= 0) return false;
  // Pixel centres at integers: the image spans [-0.5, size - 0.5].
  const double m = params_.border_margin_px - 0.5;
  return polygon.row(0).minCoeff() <= m || polygon.row(1).minCoeff() <= m ||
         polygon.row(0).maxCoeff() >= c.image_width - 1 - m || polygon.row(1).maxCoeff() >= c.image_height - 1 - m;
}

// The resolution cut of "frames used" (header): max(max_length_resolution, factor * best).
double VehicleDimensionEstimator::resolution_bound(double best) const {
  if (params_.max_length_resolution == 0.0 && params_.length_resolution_factor == 0.0) return kInf;
  return std::max(params_.max_length_resolution, params_.length_resolution_factor * best);
}

// Drops the used views that a better best view has put beyond the bound; the "rays" sums are
// rebuilt from the remaining views' own factors (no subtraction: no cancellation).
void VehicleDimensionEstimator::drop_coarse_views(Track& t) const {
  const double bound = resolution_bound(t.best_resolution);
  const bool rays = params_.sampler == VehicleSampler::Rays;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < t.resolution.size(); ++i) {
    if (t.resolution[i] > bound) {
      if (rays && params_.far_view_gate > 0.0) t.far_views.emplace_back(t.resolution[i], t.ray_terms[i]);
      continue;
    }
    t.resolution[kept] = t.resolution[i];
    t.means[kept] = t.means[i];
    t.class_probability[kept] = t.class_probability[i];
    if (rays) t.ray_terms[kept] = t.ray_terms[i];
    ++kept;
  }
  if (kept == t.resolution.size()) return;
  t.resolution.resize(kept);
  t.means.resize(kept);
  t.class_probability.resize(kept);
  if (!rays) return;
  t.ray_terms.resize(kept);
  t.rays = RaySums{};
  for (const auto& term : t.ray_terms) t.rays.add(term);
}

bool VehicleDimensionEstimator::add(Track& t, const VehicleObservation& obs) {
  const auto heights = obs.feasible_heights(min_size_of(params_));
  if (!(heights.first <= heights.second)) return false;  // smaller than min_size from any height
  const double resolution = obs.edge_resolution(1);
  if (resolution < t.best_resolution) {
    t.best_resolution = resolution;
    drop_coarse_views(t);
  }
  const bool rays = params_.sampler == VehicleSampler::Rays;
  const bool too_far = resolution > resolution_bound(t.best_resolution);  // to tell its length
  const bool held_far = rays && params_.far_view_gate > 0.0;
  if (too_far && !held_far) return false;
  RaySums term;
  if (rays) term.add(obs, params_.likelihood);
  if (too_far) {
    t.far_views.emplace_back(resolution, term);
    return false;
  }
  if (rays) {
    t.rays.add(term);
    t.ray_terms.push_back(term);
  }
  // After drops that took every earlier view, the vehicle starts afresh (no x* from dropped views).
  const bool first = t.means.empty();
  t.last = sample_vehicle_frame(obs, prior_, first ? nullptr : &t.last, t.rays, params_, t.rng);
  t.means.push_back(t.last.mean);
  t.class_probability.push_back(t.last.class_probability);
  t.resolution.push_back(resolution);
  return true;
}

bool VehicleDimensionEstimator::update_polygon(int vehicle_id, int frame,
                                               const Eigen::Ref<const Eigen::Matrix2Xd>& polygon) {
  // Observe before touching the track: a refused silhouette leaves the estimator unchanged.
  const VehicleObservation obs = models::observe_silhouette(camera_, polygon, params_.likelihood);
  Track& t = track(vehicle_id, frame);
  return !touches_border(polygon) && add(t, obs);
}

bool VehicleDimensionEstimator::update_box(int vehicle_id, int frame, double x, double y, double w, double h) {
  const VehicleObservation obs = models::observe_box(camera_, x, y, w, h, params_.likelihood);
  Eigen::Matrix2Xd corners(2, 2);
  corners << x, x + w, y, y + h;
  Track& t = track(vehicle_id, frame);
  return !touches_border(corners) && add(t, obs);
}

int VehicleDimensionEstimator::next_frame(int vehicle_id) const {
  const auto it = tracks_.find(vehicle_id);
  return it == tracks_.end() ? 1 : it->second.last_frame + 1;
}

const VehiclePosterior* VehicleDimensionEstimator::posterior(int vehicle_id) const {
  const auto it = tracks_.find(vehicle_id);
  if (it == tracks_.end() || it->second.means.empty()) return nullptr;
  return &it->second.last;
}

// The "rays" answer refitted without outlying views (header, "outlying views"): `post` (the last
// posterior) is replaced by the chain on the kept views' sums, pass after pass, while some but not
// all of the kept views lie beyond the gate; then the far views that agree join it (add_far_views()).
// Returns the number of views used. The chain draws from a copy of the vehicle's stream: the answer
// is the same at every call.
int VehicleDimensionEstimator::refit_without_outliers(const Track& t, VehiclePosterior& post) const {
  std::vector<const RaySums*> kept;
  for (const auto& term : t.ray_terms) kept.push_back(&term);
  core::Rng rng = t.rng;
  if (params_.outlier_gate > 0.0) {
    const double gate2 = params_.outlier_gate * params_.outlier_gate;
    for (int pass = 0; pass < kOutlierPasses; ++pass) {
      std::vector<const RaySums*> inside;
      RaySums sums;
      for (const RaySums* term : kept) {
        if (term->squared_distance(post.mean) > gate2) continue;
        inside.push_back(term);
        sums.add(*term);
      }
      if (inside.empty() || inside.size() == kept.size()) break;
      kept = std::move(inside);
      rechain(sums, post, rng);
    }
  }
  return add_far_views(t, kept, post, rng);
}

// `post` replaced by the chain on the product of the rays in `sums` and the prior, from its mean.
void VehicleDimensionEstimator::rechain(const RaySums& sums, VehiclePosterior& post, core::Rng& rng) const {
  const Mixture mixture(prior_, params_.min_size);
  post = space_chain([&](const Eigen::Vector3d& x) { return sums.log_likelihood(x) + mixture(x); }, post.mean,
                     params_, rng);
  summarise(post, prior_);
}

// The far views that agree with the answer join it (header, "far views"): the chain re-runs on the
// kept views and the far views within far_view_gate of `post` (under S), each with S widened by its
// resolution over the cut's. Returns the number of views used.
int VehicleDimensionEstimator::add_far_views(const Track& t, const std::vector<const RaySums*>& kept,
                                             VehiclePosterior& post, core::Rng& rng) const {
  const double gate2 = params_.far_view_gate * params_.far_view_gate;
  const double bound = resolution_bound(t.best_resolution);
  RaySums sums;
  for (const RaySums* term : kept) sums.add(*term);
  int joined = 0;
  for (const auto& [resolution, term] : t.far_views) {
    if (term.squared_distance(post.mean) > gate2) continue;
    sums.add(term, std::min(1.0, (bound / resolution) * (bound / resolution)));  // S x (r / bound)^2
    ++joined;
  }
  if (joined > 0) rechain(sums, post, rng);
  return static_cast<int>(kept.size()) + joined;
}

VehicleEstimate VehicleDimensionEstimator::estimate(int vehicle_id) const {
  const auto it = tracks_.find(vehicle_id);
  if (it == tracks_.end()) throw InvalidArgument("no vehicle with id " + std::to_string(vehicle_id));
  const Track& t = it->second;
  VehicleEstimate e;
  e.vehicle_id = vehicle_id;
  e.first_frame = t.first_frame;
  e.last_frame = t.last_frame;
  e.frames_seen = t.frames_seen;
  e.frames_used = static_cast<int>(t.means.size());
  if (t.means.empty()) return e;  // never fully in view: not guessed
  e.valid = true;
  const bool last = params_.decision == VehicleDecision::Last ||
                    (params_.decision == VehicleDecision::Auto && params_.sampler == VehicleSampler::Rays);
  if (last && params_.sampler == VehicleSampler::Rays) {
    VehiclePosterior post = t.last;
    e.frames_used = refit_without_outliers(t, post);
    e.dimensions = post.mean;
    e.class_probability = post.class_probability;
  } else if (last) {
    e.dimensions = t.means.back();
    e.class_probability = t.class_probability.back();
  } else {
    e.dimensions.setZero();
    e.class_probability = Eigen::VectorXd::Zero(t.class_probability.front().size());
    for (std::size_t i = 0; i < t.means.size(); ++i) {
      e.dimensions += t.means[i];
      e.class_probability += t.class_probability[i];
    }
    e.dimensions /= static_cast<double>(t.means.size());
    e.class_probability /= static_cast<double>(t.means.size());
  }
  Eigen::Index best = 0;
  e.class_probability.maxCoeff(&best);
  e.class_index = static_cast<int>(best);
  const auto& model = prior_.params().models[static_cast<std::size_t>(best)];
  e.class_name = model.name;
  // "volume": W H L >= heavy_volume, W at most max_vehicle_width, or H >= heavy_height (header:
  // light/heavy).
  const bool tall = params_.heavy_height > 0.0 && e.dimensions.y() >= params_.heavy_height;
  const double width = params_.max_vehicle_width > 0.0 ? std::min(e.dimensions.x(), params_.max_vehicle_width)
                                                       : e.dimensions.x();
  const double volume = width * e.dimensions.y() * e.dimensions.z();
  e.heavy = params_.light_heavy_rule == LightHeavyRule::Class ? model.heavy : volume >= params_.heavy_volume || tall;
  return e;
}

std::vector<VehicleEstimate> VehicleDimensionEstimator::estimates() const {
  std::vector<VehicleEstimate> out;
  out.reserve(tracks_.size());
  for (const auto& [id, t] : tracks_) out.push_back(estimate(id));
  return out;
}

}  // namespace vtrack::filters
