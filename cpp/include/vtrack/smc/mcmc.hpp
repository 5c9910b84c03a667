#pragma once
// The MCMC particle filter of particle-filters-human-vehicle §1.3 and §3.3.
//
// The posterior is carried as N_s unweighted samples. Each step(z) runs one Metropolis-Hastings
// chain (mh.hpp: burn-in B, thinning c, N = B + c N_s proposals) on
//   reference = "all":  pi(x) ∝ p(z|x) sum_i p(x | x_{k-1}^i)                  (§1.3), O(N N_s);
//   otherwise:          pi(x) ∝ p(z|x) p(x | x*)                               (§3.3), O(N),
// with x* one previous sample: a uniformly random one ("random", Khan et al.), the most likely
// one ("map": largest pi at the previous step; at the first step largest prior density) or the
// previous point estimate ("mean"). The estimate is the sample mean (§3.3); map_estimate() is the
// kept sample of largest pi.
//
// Proposals are symmetric random walks shaped by the process noise S (S S^T = Q): for "all"
// x' = x + s S eta in state space (it needs S square and invertible, to evaluate the transition
// density); for the x* variants the chain runs on the noise eps of x = propagate(x*, eps),
// eps' = eps + s eta, with pi(eps) ∝ p(z | propagate(x*, eps)) N(eps; 0, I) -- the same chain as
// x' = x + s S eta on p(z|x) p(x|x*), and one that also works for singular S. s is
// proposal_scale. The chain starts at the predicted mean (all) or at eps = 0, i.e. x = F x*.
//
// The MH chain is sequential: steps are not threaded. With an observation model written in
// Python each chain step calls it once (on one particle): N = B + c N_s calls per step.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/parameters.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/vmath.hpp"
#include "vtrack/smc/mh.hpp"
#include "vtrack/smc/model.hpp"

namespace vtrack::smc {

enum class McmcReference { All, Random, Map, Mean };
// Parses "all", "random", "map" or "mean"; InvalidArgument otherwise.
McmcReference parse_mcmc_reference(const std::string& name);
const char* to_string(McmcReference reference);
// Every reference with its name, in the order above.
const std::vector<std::pair<std::string, McmcReference>>& mcmc_reference_names();

struct McmcParams {
  int n_particles = 1000;  // N_s, samples kept per step
  int burn_in = 500;       // B
  int thinning = 2;        // c
  McmcReference reference = McmcReference::All;
  double proposal_scale = 0.5;  // s, in units of the process noise
  std::uint64_t seed = 0;

  // Names for config files and Python keywords (core/parameters.hpp); defined in mcmc.cpp.
  static const core::ParameterTable<McmcParams>& table();
};
void validate(const McmcParams& params);

template <class Motion, class Observation>
class McmcFilter {
  static_assert(!is_whole_array_v<Motion>,
                "the MCMC filter runs its chains on the motion model's Gaussian noise");

 public:
  McmcFilter(Motion motion, Observation observation, const core::Gaussian& prior,
             const McmcParams& params)
      : motion_(std::move(motion)), observation_(std::move(observation)), params_(params),
        rng_(params.seed) {
    validate(params_);
    const int d = motion_.dim();
    if (prior.dim() != d) {
      throw InvalidArgument("prior has dimension " + std::to_string(prior.dim()) +
                            ", the motion model " + std::to_string(d));
    }
    if (observation_.min_state_dim() > d) {
      throw InvalidArgument("the observation model needs a state of dimension >= " +
                            std::to_string(observation_.min_state_dim()) +
                            ", the motion model's is " + std::to_string(d));
    }
    if (params_.reference == McmcReference::All) init_transition_density();
    samples_ = prior.sample(rng_, params_.n_particles).transpose();
    log_target_ = prior.log_density_columns(samples_.transpose());
    estimate();
  }

  // One chain for measurement z; returns the sample mean.
  const Eigen::VectorXd& step(const Eigen::VectorXd& z) {
    observation_.check(z);
    const ChainParams chain{params_.n_particles, params_.burn_in, params_.thinning};
    ChainResult result = params_.reference == McmcReference::All ? chain_all(z, chain)
                                                                  : chain_reference(z, chain);
    log_target_ = std::move(result.log_target);
    acceptance_rate_ = result.acceptance_rate();
    proposals_ = result.proposals;
    if (params_.reference == McmcReference::All) samples_ = std::move(result.samples);
    else samples_ = states_from_noise(result.samples);
    estimate();
    ++steps_;
    return mean_;
  }

  const Eigen::MatrixXd& particles() const { return samples_; }  // N_s x d
  const Eigen::VectorXd& log_target() const { return log_target_; }
  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::VectorXd& map_estimate() const { return map_; }
  double acceptance_rate() const { return acceptance_rate_; }
  std::int64_t proposals() const { return proposals_; }
  const McmcParams& params() const { return params_; }
  int steps() const { return steps_; }
  // x* of the last step (1 x d; empty for reference "all").
  const Eigen::MatrixXd& reference() const { return reference_; }

 private:
  using Row = Eigen::MatrixXd;  // 1 x d: one particle, as models see particle blocks

  void init_transition_density() {
    if constexpr (!has_noise_factor_v<Motion>) {
      throw InvalidArgument("reference 'all' needs a motion model with additive Gaussian noise");
    } else {
      const Eigen::MatrixXd& S = motion_.noise_factor();
      Eigen::FullPivLU<Eigen::MatrixXd> lu(S);
      if (S.rows() != S.cols() || lu.rank() < S.rows()) {
        throw InvalidArgument(
            "reference 'all' needs the transition density p(x_k | x_k-1), but the process noise is "
            "singular (rank " + std::to_string(lu.rank()) + " of " + std::to_string(S.rows()) +
            "); use reference 'random', 'map' or 'mean'");
      }
      noise_factor_ = S;
      noise_inverse_t_ = lu.inverse().transpose();
    }
  }

  double log_likelihood(const Row& x, const Eigen::VectorXd& z) const {
    double out = 0.0;
    if constexpr (is_whole_array_v<Observation>) {
      Eigen::VectorXd v(1);
      observation_.log_likelihood_all(x, z, v);
      out = v[0];
    } else {
      observation_.log_likelihood(models::StatesView<double>(x), z, &out);
    }
    return out;
  }

  // §1.3: pi(x) ∝ p(z|x) sum_i N(x; m_i, S S^T), m_i the prediction of sample i; in whitened
  // coordinates the sum is sum_i exp(-|x S^-T - m_i S^-T|^2 / 2) (constants dropped).
  ChainResult chain_all(const Eigen::VectorXd& z, const ChainParams& chain) {
    const Eigen::Index ns = samples_.rows();
    Eigen::MatrixXd means(ns, motion_.dim());
    const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(ns, motion_.noise_dim());
    motion_.propagate(models::StatesView<double>(samples_), models::StatesView<double>(zero),
                      means);
    const Eigen::MatrixXd white = means * noise_inverse_t_;
    Eigen::VectorXd q(ns);
    Eigen::RowVectorXd w(motion_.dim());
    Row row(1, motion_.dim());
    auto target = [&](const Eigen::VectorXd& x) {
      w.noalias() = x.transpose() * noise_inverse_t_;
      row = x.transpose();
      q.setZero();
      for (Eigen::Index c = 0; c < white.cols(); ++c) {
        const double wc = w[c];
        const double* m = white.col(c).data();
        for (Eigen::Index i = 0; i < ns; ++i) q[i] += (wc - m[i]) * (wc - m[i]);
      }
      const double peak = -0.5 * q.minCoeff();
      double sum = 0.0;
      for (Eigen::Index i = 0; i < ns; ++i) sum += core::vmath::exp(-0.5 * q[i] - peak);
      return log_likelihood(row, z) + peak + std::log(sum);
    };
    RandomWalkProposal proposal(params_.proposal_scale * noise_factor_);
    const Eigen::VectorXd start = means.colwise().mean().transpose();
    return metropolis_hastings(target, start, chain, proposal, rng_);
  }

  // §3.3: the chain on eps for x = propagate(x*, eps).
  ChainResult chain_reference(const Eigen::VectorXd& z, const ChainParams& chain) {
    Eigen::Index pick = 0;
    switch (params_.reference) {
      case McmcReference::Random:
        reference_ = samples_.row(static_cast<Eigen::Index>(
            rng_.below(static_cast<std::uint64_t>(samples_.rows()))));
        break;
      case McmcReference::Map:
        log_target_.maxCoeff(&pick);
        reference_ = samples_.row(pick);
        break;
      default:
        reference_ = mean_.transpose();
        break;
    }
    Row x(1, motion_.dim());
    Row e(1, motion_.noise_dim());
    auto target = [&](const Eigen::VectorXd& eps) {
      e = eps.transpose();
      motion_.propagate(models::StatesView<double>(reference_), models::StatesView<double>(e), x);
      return log_likelihood(x, z) - 0.5 * eps.squaredNorm();
    };
    const int r = motion_.noise_dim();
    RandomWalkProposal proposal(params_.proposal_scale * Eigen::MatrixXd::Identity(r, r));
    return metropolis_hastings(target, Eigen::VectorXd::Zero(r), chain, proposal, rng_);
  }

  Eigen::MatrixXd states_from_noise(const Eigen::MatrixXd& eps) const {
    const Eigen::MatrixXd prev = reference_.replicate(eps.rows(), 1);
    Eigen::MatrixXd x(eps.rows(), motion_.dim());
    motion_.propagate(models::StatesView<double>(prev), models::StatesView<double>(eps), x);
    return x;
  }

  void estimate() {
    mean_ = samples_.colwise().mean().transpose();
    Eigen::Index best = 0;
    log_target_.maxCoeff(&best);
    map_ = samples_.row(best).transpose();
  }

  Motion motion_;
  Observation observation_;
  McmcParams params_;
  core::Rng rng_;
  Eigen::MatrixXd samples_;
  Eigen::VectorXd log_target_;
  Eigen::MatrixXd noise_factor_, noise_inverse_t_;
  Row reference_;
  Eigen::VectorXd mean_, map_;
  double acceptance_rate_ = 0.0;
  std::int64_t proposals_ = 0;
  int steps_ = 0;
};

}  // namespace vtrack::smc
