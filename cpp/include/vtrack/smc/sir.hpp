#pragma once
// Sequential importance resampling (SIR) with selective resampling and optional resample-move.
//
// One step(z) is the part-based paper's Step 2-4 (particle-filters-human-vehicle §1.2):
//   2. x_i ~ q(x | x_i^prev, z) (the motion model: bootstrap), w_i <- w_i p(z|x_i) p(x_i|x_i^prev)
//      / q(x_i | x_i^prev, z) (eq. 5), normalised (eq. 6); the log normaliser is added to the log
//      evidence log p(z_1:k) (its logarithm is an unbiased estimator's, Del Moral 2004);
//   4. the estimate: the weighted mean sum_i w_i x_i (eq. 8) and the particle of largest weight
//      (MAP), both with the weights of step 2, before any resampling (the paper outputs after
//      step 3; before is the same expectation with less Monte Carlo noise);
//   3. selective resampling: when N_eff (eq. 7) <= ess_threshold N (N_th = ess_threshold N:
//      1 resamples every step, 0 never), N equally weighted particles are drawn by the chosen
//      scheme; then, with resample_move_steps = k > 0, each particle takes k Metropolis-Hastings
//      moves that leave p(x_k | x_{k-1}^anc, z_k) invariant (Gilks & Berzuini 2001): the move
//      runs on the particle's Gaussian noise eps (x = propagate(x^anc, eps)), proposing
//      eps' = eps + move_scale eta, eta ~ N(0, I), accepted with probability
//      min(1, p(z|x') N(eps') / (p(z|x) N(eps))). In state space that is a random walk shaped by
//      the process noise, and it works for singular noise (constant velocity's discrete model,
//      the second-order auto-regressive model) where a state-space random walk would not.
//
// Precision: Scalar is the type of the states (double, or float for large particle sets: half
// the memory traffic and twice the vector width in propagation, gather and likelihood; the
// weights' exponentials in float too, but the weights, their sums, the estimates and the log
// evidence stay in double). The random draws are the same for both, so a float filter follows
// its double twin to within float round-off.
//
// Measurement conventions: `prior` is the density of x_0, one step before the first measurement
// (as a Kalman filter's), so every step(z) first propagates. A NaN in z is an InvalidArgument
// (the filter is unchanged; call predict() for a missing measurement). When every particle has
// likelihood zero the update is skipped (reweight.hpp): the particles keep their predicted
// states and previous weights, the estimate is the predicted mean, and the log evidence is -inf.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/parameters.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/core/vmath.hpp"
#include "vtrack/smc/blocks.hpp"
#include "vtrack/smc/model.hpp"
#include "vtrack/smc/particle_set.hpp"
#include "vtrack/smc/reweight.hpp"

namespace vtrack::smc {

struct SirParams {
  int n_particles = 1000;  // N
  core::ResamplingScheme resampling = core::ResamplingScheme::Systematic;
  // Resample when N_eff <= ess_threshold N (part-based Step 3 with N_th = ess_threshold N), in
  // [0, 1]: 1 every step, 0 never.
  double ess_threshold = 1.0;
  // k Metropolis-Hastings moves per particle after each resampling (0: plain SIR).
  int resample_move_steps = 0;
  // Random-walk step of the moves in units of the process noise (eps' = eps + move_scale eta).
  double move_scale = 0.5;
  // Worker threads: 1 the calling thread, 0 OpenCV's pool, T > 1 T stripes. The particles are
  // identical for every value (per-block random streams, blocks.hpp).
  int threads = 1;
  std::uint64_t seed = 0;

  // Names for config files and Python keywords (core/parameters.hpp); defined in sir.cpp.
  static const core::ParameterTable<SirParams>& table();
};
void validate(const SirParams& params);

// Draws n particles from `prior` with the per-block streams (rows of the result).
Eigen::MatrixXd sample_prior(const core::Gaussian& prior, Eigen::Index n, BlockStreams& streams,
                             int threads);

template <class Motion, class Observation, class Proposal = Bootstrap, typename Scalar = double>
class Sir {
  static_assert(std::is_same_v<Scalar, double> || std::is_same_v<Scalar, float>,
                "particle states are double or float");
  using States = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;  // N x d, one per row
  using View = models::StatesView<Scalar>;
  static constexpr bool kBootstrap = std::is_same_v<Proposal, Bootstrap>;
  static constexpr bool kWholeMotion = is_whole_array_v<Motion>;
  static constexpr bool kWholeObservation = is_whole_array_v<Observation>;
  static_assert(kBootstrap || !kWholeMotion, "a proposal replaces the motion model's sampling");
  static_assert(std::is_same_v<Scalar, double> || (!kWholeMotion && !kWholeObservation),
                "whole-array (Python) models take double arrays");
  // Resampled states are gathered lazily, block by block, by the next propagation.
  static constexpr bool kLazyGather = kBootstrap && !kWholeMotion;
  // A block's rows of a particle array, or a block-sized buffer, as a matrix.
  using BlockMatrix = Eigen::Map<States, 0, Eigen::OuterStride<>>;

 public:
  Sir(Motion motion, Observation observation, const core::Gaussian& prior,
      const SirParams& params, Proposal proposal = {})
      : Sir(std::move(motion), std::move(observation), params, std::move(proposal)) {
    if (prior.dim() != motion_.dim()) {
      throw InvalidArgument("prior has dimension " + std::to_string(prior.dim()) +
                            ", the motion model " + std::to_string(motion_.dim()));
    }
    set_ = ParticleSet<Scalar>(
        sample_prior(prior, params_.n_particles, streams_, params_.threads).template cast<Scalar>());
    mean_ = set_.mean();
    map_ = set_.map_estimate().template cast<double>();
  }
  // From given particles (N x d, one per row), equally weighted; N = rows (n_particles ignored).
  Sir(Motion motion, Observation observation, Eigen::MatrixXd particles, const SirParams& params,
      Proposal proposal = {})
      : Sir(std::move(motion), std::move(observation), with_count(params, particles.rows()),
            std::move(proposal)) {
    if (particles.cols() != motion_.dim()) {
      throw InvalidArgument("particles have dimension " + std::to_string(particles.cols()) +
                            ", the motion model " + std::to_string(motion_.dim()));
    }
    if (!particles.allFinite()) throw InvalidArgument("particles contain NaN or inf");
    set_ = ParticleSet<Scalar>(particles.template cast<Scalar>());
    mean_ = set_.mean();
    map_ = set_.map_estimate().template cast<double>();
  }

  // One predict-update-resample cycle with measurement z; returns the weighted mean (eq. 8).
  const Eigen::VectorXd& step(const Eigen::VectorXd& z) {
    observation_.check(z);
    advance(&z);
    resample_and_move(z);
    ++steps_;
    return mean_;
  }
  // Propagation only (a step without a measurement); weights unchanged, no resampling.
  const Eigen::VectorXd& predict() {
    advance(nullptr);
    acceptance_rate_ = 0.0;
    ++steps_;
    return mean_;
  }

  // The particle set after the last step (resampled if it was).
  const ParticleSet<Scalar>& particles() const {
    if (pending_) {
      gather_rows(set_.states(), set_.ancestors().data(), set_.size(), next_, params_.threads);
      set_.states().swap(next_);
      pending_ = false;
    }
    write_uniform_weights();
    return set_;
  }
  const SirParams& params() const { return params_; }
  const Motion& motion() const { return motion_; }
  const Observation& observation() const { return observation_; }
  // Weighted mean and a largest-weight particle of the last step's update (eq. 8; MAP).
  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::VectorXd& map_estimate() const { return map_; }
  // N_eff of the last update (before resampling).
  double ess() const { return ess_; }
  // Sum of the log normalisers so far: the SMC estimate of log p(z_1, ..., z_k).
  double log_evidence() const { return log_evidence_; }
  double last_log_normaliser() const { return last_log_normaliser_; }
  bool resampled() const { return resampled_; }
  // Accepted fraction of the last step's moves (0 when none were made).
  double acceptance_rate() const { return acceptance_rate_; }
  int steps() const { return steps_; }

 private:
  Sir(Motion motion, Observation observation, const SirParams& params, Proposal proposal)
      : motion_(std::move(motion)),
        observation_(std::move(observation)),
        proposal_(std::move(proposal)),
        params_(params),
        streams_(params.seed, 1),
        rng_(params.seed, 0) {
    validate(params_);
    if (observation_.min_state_dim() > motion_.dim()) {
      throw InvalidArgument("the observation model needs a state of dimension >= " +
                            std::to_string(observation_.min_state_dim()) +
                            ", the motion model's is " + std::to_string(motion_.dim()));
    }
    if (params_.resample_move_steps > 0 && (kWholeMotion || !kBootstrap)) {
      throw InvalidArgument(
          "resample_move_steps > 0 needs a motion model driven by Gaussian noise (a built-in "
          "model) and the bootstrap proposal: the moves run on that noise");
    }
  }
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static SirParams with_count(SirParams p, Eigen::Index n) {
    p.n_particles = static_cast<int>(n);
    return p;
  }
  int noise_dim() const {
    if constexpr (kBootstrap) {
      if constexpr (kWholeMotion) return 0; else return motion_.noise_dim();
    } else {
      return proposal_.noise_dim();
    }
  }

  // eps for the n x nr block of block b at `out` (columns `stride` apart), from b's stream. The
  // normals are drawn in single precision (core::LaneRng; twice as fast as double precision,
  // relative error < 1e-6, far below any Monte Carlo error), in one call for the whole block (so
  // the draws do not depend on the stride or on Scalar), and widened for double states.
  void draw_noise(Eigen::Index b, Eigen::Index n, int nr, Scalar* out, Eigen::Index stride) {
    const auto count = static_cast<std::size_t>(n * nr);
    if constexpr (std::is_same_v<Scalar, float>) {
      if (stride == n) {
        streams_[b].fill_normal(out, count);
        return;
      }
    }
    float* normals = scratch<float, Scratch::Normals>(count);
    streams_[b].fill_normal(normals, count);
    for (int k = 0; k < nr; ++k) {
      Eigen::Map<Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>(out + k * stride, n) =
          Eigen::Map<const Eigen::VectorXf>(normals + k * n, n).template cast<Scalar>();
    }
  }

  // x_i <- propagate(x_i, eps_i) for the particles of block b (eps kept in eps_ when the moves
  // need it, else in a block-sized buffer that stays in cache). After a lazy resampling the
  // block's previous states are gathered from their ancestors here, in cache, instead of in a
  // separate pass over all particles.
  void propagate_block(Eigen::Index b, const Eigen::VectorXd* z) {
    const BlockRange r = block_range(b, set_.size());
    const Eigen::Index n = r.size();
    const int nr = noise_dim();
    Scalar* eps_data;
    Eigen::Index stride;
    if (keep_noise()) {
      eps_data = eps_.data() + r.begin;
      stride = eps_.rows();
    } else {
      eps_data = scratch<Scalar, Scratch::Noise>(static_cast<std::size_t>(n * nr));
      stride = n;
    }
    draw_noise(b, n, nr, eps_data, stride);
    const View eps(BlockMatrix(eps_data, n, nr, Eigen::OuterStride<>(stride)));
    const Eigen::Index d = set_.dim();
    Scalar* gathered = nullptr;
    if (pending_) {
      gathered = scratch<Scalar, Scratch::Gathered>(static_cast<std::size_t>(n * d));
      gather_block(set_.states().data(), set_.size(), set_.size(), d,
                   set_.ancestors().data() + r.begin, n, gathered, n);
    }
    const View prev = pending_ ? View(BlockMatrix(gathered, n, d, Eigen::OuterStride<>(n)))
                               : View(set_.states().middleRows(r.begin, n));
    if constexpr (kBootstrap) {
      (void)z;
      motion_.propagate(prev, eps, next_.middleRows(r.begin, n));
    } else {
      proposal_.propagate(prev, eps, *z, next_.middleRows(r.begin, n));
    }
  }
  void write_uniform_weights() const {
    if (!weights_uniform_) return;
    set_.set_uniform();
    weights_uniform_ = false;
  }
  bool keep_noise() const { return params_.resample_move_steps > 0; }
  // log-likelihoods (and proposal corrections) of block b's new states, and its weight sums. The
  // log-likelihoods go to loglik_ when the moves (or a whole-array model) need them there, else
  // to a block-sized buffer.
  void weigh_block(Eigen::Index b, const Eigen::VectorXd& z) {
    const BlockRange r = block_range(b, set_.size());
    const View x(next_.middleRows(r.begin, r.size()));
    double* ll = keep_loglik() ? loglik_.data() + r.begin
                               : scratch<double, Scratch::LogLikelihood>(
                                     static_cast<std::size_t>(r.size()));
    if constexpr (!kWholeObservation) observation_.log_likelihood(x, z, ll);
    if constexpr (!kBootstrap) {
      Eigen::VectorXd correction(r.size());  // log p(x|x_prev) - log q(x|x_prev, z), eq. 5
      proposal_.log_weight(View(set_.states().middleRows(r.begin, r.size())), x, z,
                           correction.data());
      Eigen::Map<Eigen::VectorXd>(ll, r.size()) += correction;
    }
    if (weights_uniform_) {
      update_.block(b, nullptr, ll, &x, -std::log(static_cast<double>(set_.size())));
    } else {
      update_.block(b, set_.log_weights().data() + r.begin, ll, &x);
    }
  }
  bool keep_loglik() const { return kWholeObservation || keep_noise(); }

  // Propagation (and, with z, the update and the decision to resample) into fresh buffers,
  // committed only when nothing threw.
  void advance(const Eigen::VectorXd* z) {
    const Eigen::Index n = set_.size();
    const Eigen::Index blocks = block_count(n);
    streams_.reserve(blocks);
    next_.resize(n, motion_.dim());
    if (keep_noise()) eps_.resize(n, noise_dim());
    // ess_threshold 1 resamples whatever the update: its log weights are never needed.
    const bool always_resample = params_.ess_threshold >= 1.0;
    if (z) {
      if (keep_loglik()) loglik_.resize(n);
      update_.begin(n, motion_.dim(), !always_resample, std::is_same_v<Scalar, float>);
    }
    const int threads = params_.threads;
    if constexpr (!kWholeMotion && !kWholeObservation) {
      // Fused: a block's noise, states and likelihoods stay in cache between the stages.
      for_blocks(blocks, threads, [&](Eigen::Index b) {
        propagate_block(b, z);
        if (z) weigh_block(b, *z);
      });
    } else {
      if constexpr (kWholeMotion) {
        motion_.propagate_all(set_.states(), next_);
      } else {
        for_blocks(blocks, threads, [&](Eigen::Index b) { propagate_block(b, z); });
      }
      if (z) {
        if constexpr (kWholeObservation) observation_.log_likelihood_all(next_, *z, loglik_);
        for_blocks(blocks, threads, [&](Eigen::Index b) { weigh_block(b, *z); });
      }
    }
    const ReweightResult result = z ? update_.finish() : ReweightResult{-kInf, 0.0, 0};
    // Commit: the new states become the set's; the moves keep the old ones as the ancestors'
    // states (prev_). Without moves two buffers alternate, so the next propagation writes over
    // the states it has just read (still in cache at large N) rather than older ones.
    if (keep_noise()) prev_.swap(set_.states());
    set_.states().swap(next_);
    pending_ = false;
    resampled_ = false;
    if (z) {
      last_log_normaliser_ = result.log_normaliser;
      log_evidence_ += result.log_normaliser;
    }
    fused_resampling_ = false;
    if (z && result.updated()) {
      resampled_ = always_resample || result.ess <= params_.ess_threshold * static_cast<double>(n);
      // Systematic resampling reads the updated weights where the update left them; otherwise
      // they are written (the log weights only if they are kept, i.e. not about to be reset).
      fused_resampling_ = resampled_ && params_.resampling == core::ResamplingScheme::Systematic;
      if (!fused_resampling_) {
        update_.commit(set_.log_weights_buffer(), set_.weights_buffer(), threads, !resampled_);
        weights_uniform_ = false;
      }
      set_.set_updated(result);
      mean_ = update_.mean();
    } else {
      // No measurement, or nothing learnt from it: previous weights, predicted states.
      write_uniform_weights();
      resampled_ = z && set_.ess() <= params_.ess_threshold * static_cast<double>(n);
      mean_ = set_.mean();
    }
    ess_ = set_.ess();
    map_ = set_.map_estimate().template cast<double>();
  }

  void resample_and_move(const Eigen::VectorXd& z) {
    acceptance_rate_ = 0.0;
    if (!resampled_) return;
    const Eigen::Index n = set_.size();
    if (fused_resampling_) {
      update_.resample_systematic(static_cast<std::size_t>(n), rng_.uniform(),
                                  set_.ancestors_buffer(n), params_.threads);
    } else {
      set_.draw_ancestors(params_.resampling, n, rng_);
    }
    // Equal weights from now on; the arrays are written only when someone looks at them.
    weights_uniform_ = true;
    if (kLazyGather && params_.resample_move_steps == 0) {
      // The states are gathered by the next propagation (or by particles()).
      pending_ = true;
      return;
    }
    const std::int64_t* a = set_.ancestors().data();
    const int threads = params_.threads;
    gather_rows(set_.states(), a, n, next_, threads);
    set_.states().swap(next_);
    if (params_.resample_move_steps > 0) {
      // The moves need each particle's ancestor state, noise and likelihood, carried along.
      gather_rows(prev_, a, n, next_, threads);
      prev_.swap(next_);
      States moved;
      gather_rows(eps_, a, n, moved, threads);
      eps_.swap(moved);
      Eigen::VectorXd ll;
      gather_rows(loglik_, a, n, ll, threads);
      loglik_.swap(ll);
    }
    if (params_.resample_move_steps > 0) move(z);
  }

  // One block's proposals: eps', x' = propagate(x^anc, eps'), log p(z|x') and the uniforms of the
  // accept test, as block-local buffers (the fused path) or as views into whole arrays (a
  // whole-array observation model evaluates all proposals at once).
  struct Proposals {
    BlockMatrix eps, x;
    Eigen::Map<Eigen::VectorXd> ll, u;
  };
  static Proposals rows_of(States& eps, States& x, Eigen::VectorXd& ll,
                           Eigen::VectorXd& u, Eigen::Index begin, Eigen::Index n) {
    return {BlockMatrix(eps.data() + begin, n, eps.cols(), Eigen::OuterStride<>(eps.rows())),
            BlockMatrix(x.data() + begin, n, x.cols(), Eigen::OuterStride<>(x.rows())),
            Eigen::Map<Eigen::VectorXd>(ll.data() + begin, n),
            Eigen::Map<Eigen::VectorXd>(u.data() + begin, n)};
  }

  // resample_move_steps Metropolis-Hastings moves of every particle in noise space (see top).
  void move(const Eigen::VectorXd& z) {
    const Eigen::Index n = set_.size();
    const Eigen::Index blocks = block_count(n);
    std::vector<Eigen::Index> accepted(static_cast<std::size_t>(blocks), 0);
    for (int m = 0; m < params_.resample_move_steps; ++m) {
      if constexpr (!kWholeObservation) {
        // Fused: a block proposes, evaluates and accepts while its data are in cache.
        for_blocks(blocks, params_.threads, [&](Eigen::Index b) {
          const Eigen::Index size = block_range(b, n).size();
          States eps(size, noise_dim()), x(size, motion_.dim());
          Eigen::VectorXd ll(size), u(size);
          Proposals p = rows_of(eps, x, ll, u, 0, size);
          propose(b, z, p);
          accepted[static_cast<std::size_t>(b)] += accept(b, p);
        });
      } else {
        prop_eps_.resize(n, noise_dim());
        prop_x_.resize(n, motion_.dim());
        prop_ll_.resize(n);
        uniform_.resize(n);
        auto proposals = [&](Eigen::Index b) {
          const BlockRange r = block_range(b, n);
          return rows_of(prop_eps_, prop_x_, prop_ll_, uniform_, r.begin, r.size());
        };
        for_blocks(blocks, params_.threads, [&](Eigen::Index b) { propose(b, z, proposals(b)); });
        observation_.log_likelihood_all(prop_x_, z, prop_ll_);
        for_blocks(blocks, params_.threads, [&](Eigen::Index b) {
          accepted[static_cast<std::size_t>(b)] += accept(b, proposals(b));
        });
      }
    }
    Eigen::Index total = 0;
    for (Eigen::Index a : accepted) total += a;
    acceptance_rate_ = static_cast<double>(total) /
                       (static_cast<double>(n) * params_.resample_move_steps);
  }
  void propose(Eigen::Index b, const Eigen::VectorXd& z, Proposals p) {
    const BlockRange r = block_range(b, set_.size());
    const int nr = noise_dim();
    draw_noise(b, r.size(), nr, p.eps.data(), p.eps.outerStride());
    for (int k = 0; k < nr; ++k) {
      Scalar* q = p.eps.data() + k * p.eps.outerStride();
      const Scalar* e = &eps_(r.begin, k);
      const auto scale = static_cast<Scalar>(params_.move_scale);
      for (Eigen::Index i = 0; i < r.size(); ++i) q[i] = e[i] + scale * q[i];
    }
    streams_[b].fill_uniform(p.u.data(), r.size());
    if constexpr (!kWholeMotion) {
      motion_.propagate(View(prev_.middleRows(r.begin, r.size())), View(p.eps), p.x);
    }
    if constexpr (!kWholeObservation) {
      observation_.log_likelihood(View(p.x), z, p.ll.data());
    }
  }
  // Accepts or rejects block b's proposals; returns the number accepted.
  Eigen::Index accept(Eigen::Index b, const Proposals& p) {
    const BlockRange r = block_range(b, set_.size());
    const Eigen::Index n = r.size();
    // log alpha = log p(z|x') - log p(z|x) + log N(eps') - log N(eps); accept if log u < log alpha.
    Eigen::ArrayXd log_alpha = p.ll - loglik_.segment(r.begin, n);
    log_alpha -= 0.5 * (p.eps.rowwise().squaredNorm() -
                        eps_.middleRows(r.begin, n).rowwise().squaredNorm())
                           .array()
                           .template cast<double>();
    std::vector<unsigned char> take(static_cast<std::size_t>(n));
    Eigen::Index count = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      // 1 - u lies in (0, 1], so its log is finite; a NaN log alpha rejects.
      take[static_cast<std::size_t>(i)] = core::vmath::log(1.0 - p.u[i]) < log_alpha[i];
      count += take[static_cast<std::size_t>(i)];
    }
    // Accepted rows replace the current ones, column by column (contiguous: the loop vectorises).
    auto blend = [&](auto& dst, const auto& src) {
      for (Eigen::Index c = 0; c < dst.cols(); ++c) {
        auto* to = dst.data() + c * dst.rows() + r.begin;
        const auto* from = src.data() + c * src.outerStride();
        const unsigned char* t = take.data();
        for (Eigen::Index i = 0; i < n; ++i) to[i] = t[i] ? from[i] : to[i];
      }
    };
    blend(eps_, p.eps);
    blend(set_.states(), p.x);
    blend(loglik_, p.ll);
    return count;
  }

  Motion motion_;
  Observation observation_;
  Proposal proposal_;
  SirParams params_;
  BlockStreams streams_;
  core::Rng rng_;  // resampling (sequential)
  // Mutable: particles() completes a pending (lazy) resampling.
  mutable ParticleSet<Scalar> set_;
  mutable States next_;
  mutable bool pending_ = false;
  // The weights are equal (after a resampling) but set_'s weight arrays were not written yet.
  mutable bool weights_uniform_ = false;
  bool fused_resampling_ = false;  // the last update's resampling reads update_ directly
  States prev_, eps_;
  Eigen::VectorXd loglik_;
  States prop_eps_, prop_x_;
  Eigen::VectorXd prop_ll_, uniform_;
  WeightUpdate update_;
  Eigen::VectorXd mean_, map_;
  double ess_ = 0.0;
  double log_evidence_ = 0.0;
  double last_log_normaliser_ = 0.0;
  bool resampled_ = false;
  double acceptance_rate_ = 0.0;
  int steps_ = 0;
};

}  // namespace vtrack::smc
