#pragma once
// Metropolis-Hastings chains (particle-filters-human-vehicle §1.3).
//
// From x_0 the chain makes N = B + c N_s proposals x' ~ q(. | x_{j-1}), each accepted with
// probability min(1, alpha), alpha = pi(x') q(x_{j-1} | x') / (pi(x_{j-1}) q(x' | x_{j-1})); on
// rejection x_j = x_{j-1}. The first B states are burn-in, then every c-th is kept:
// x_{B+c}, x_{B+2c}, ..., x_{B+c N_s} (N_s samples). A target of density zero at x_0
// (log pi = -inf) accepts the first proposal of positive density; NaN log alpha rejects.
#include <cmath>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"

namespace vtrack::smc {

struct ChainParams {
  int samples = 1000;  // N_s
  int burn_in = 500;   // B
  int thinning = 2;    // c: one kept state every c after the burn-in
};
void validate(const ChainParams& params);

struct ChainResult {
  Eigen::MatrixXd samples;     // N_s x d, one kept state per row, in chain order
  Eigen::VectorXd log_target;  // log pi of each kept state
  std::int64_t proposals = 0;  // B + c N_s
  std::int64_t accepted = 0;
  double acceptance_rate() const {
    return proposals > 0 ? static_cast<double>(accepted) / static_cast<double>(proposals) : 0.0;
  }
};

// Symmetric Gaussian random walk x' = x + A eta, eta ~ N(0, I_r), A = d x r (q ratio 1).
class RandomWalkProposal {
 public:
  explicit RandomWalkProposal(Eigen::MatrixXd factor) : factor_(std::move(factor)), eta_(factor_.cols()) {}
  // Writes a proposal from `from` to `to`; returns log q(from | to) - log q(to | from) (0 here).
  double propose(const Eigen::VectorXd& from, Eigen::VectorXd& to, core::Rng& rng) {
    rng.fill_normal(eta_.data(), static_cast<std::size_t>(eta_.size()));
    to.noalias() = from + factor_ * eta_;
    return 0.0;
  }

 private:
  Eigen::MatrixXd factor_;
  Eigen::VectorXd eta_;
};

// Runs the chain. LogTarget: double(const Eigen::VectorXd&), the log of pi up to a constant.
// Proposal: double propose(const VectorXd& from, VectorXd& to, Rng&) returning the log q ratio
// log q(from | to) - log q(to | from) (RandomWalkProposal; any other for general proposals).
template <class LogTarget, class Proposal>
ChainResult metropolis_hastings(const LogTarget& log_target, Eigen::VectorXd x,
                                const ChainParams& params, Proposal& proposal, core::Rng& rng) {
  validate(params);
  ChainResult out;
  out.samples.resize(params.samples, x.size());
  out.log_target.resize(params.samples);
  double current = log_target(x);
  Eigen::VectorXd candidate(x.size());
  const std::int64_t total =
      params.burn_in + static_cast<std::int64_t>(params.thinning) * params.samples;
  Eigen::Index kept = 0;
  for (std::int64_t j = 1; j <= total; ++j) {
    const double log_q_ratio = proposal.propose(x, candidate, rng);
    const double value = log_target(candidate);
    // log u < log alpha with u uniform on (0, 1]: accepts with probability min(1, alpha).
    if (std::log(1.0 - rng.uniform()) < value - current + log_q_ratio) {
      x.swap(candidate);
      current = value;
      ++out.accepted;
    }
    if (j > params.burn_in && (j - params.burn_in) % params.thinning == 0) {
      out.samples.row(kept) = x.transpose();
      out.log_target[kept] = current;
      ++kept;
    }
  }
  out.proposals = total;
  return out;
}

}  // namespace vtrack::smc
