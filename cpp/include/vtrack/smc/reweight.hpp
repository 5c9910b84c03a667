#pragma once
// Reweighting a particle set: log w_i <- log w_i + log l_i, normalised, with the log normaliser
// log sum_i w_i l_i returned (part-based paper eqs. 5-6; the multi-Bernoulli filter's log rho of
// eqs. 23-24 and the particle GLMB's log eta are this number) and the effective sample size of
// eq. 7 computed on the way. One exponential per particle, in blocks (blocks.hpp) so that the
// result is identical for any thread count.
//
// Conventions (the "vanishing weights" rule of DESIGN.md, never NaN):
//  - every l_i = 0 (log l_i = -inf; or their weighted sum underflows): nothing is learnt, the
//    weights stay as they were, the log normaliser is -inf (so a log evidence becomes -inf);
//  - a NaN or +inf log l_i is a modelling error: InvalidArgument naming the particle.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "vtrack/models/states.hpp"

namespace vtrack::smc {

struct ReweightResult {
  double log_normaliser;   // log sum_i w_i l_i (w normalised before the update)
  double ess;              // N_eff = 1 / sum_i w_i^2 after the update (eq. 7); 0 if nothing learnt
  Eigen::Index map_index;  // a particle of largest updated weight (the first one in index order)
  bool updated() const { return log_normaliser > -std::numeric_limits<double>::infinity(); }
};

// The stages of a reweighting, so that a filter can fuse the per-block one with its own work
// (propagation and likelihood; see sir.hpp):
//   begin(n, d); for every block, in parallel: block(b, ...); finish(); commit(...).
class WeightUpdate {
 public:
  // n particles; with d > 0 the blocks also sum their weighted states (for mean()). Without
  // keep_log the updated log weights are not stored (a filter that resamples whatever the result
  // saves a pass over memory): commit() then writes only the linear weights. With single_exp the
  // exponentials exp(t_i - max) are taken in single precision (relative error 1e-7, zero below
  // e^-87.3), for a filter whose states are single precision anyway; weights, sums and the log
  // normaliser stay double.
  void begin(Eigen::Index n, Eigen::Index d = 0, bool keep_log = true, bool single_exp = false);
  // For the particles of block b: t_i = log_w_i + log_lik_i, exp(t_i - max_b t) and the block's
  // sums; with `states` (the block's n_b x d rows) also sum_i exp(t_i - max_b t) x_i. log_w and
  // log_lik point at the block's first particle; log_w = nullptr means every log_w_i is
  // `uniform_log_w` (equal weights, e.g. right after resampling). Thread-safe across blocks.
  void block(Eigen::Index b, const double* log_w, const double* log_lik,
             const models::StatesView<double>* states = nullptr, double uniform_log_w = 0.0);
  // The same for float states (the sums are accumulated in double), and without states.
  void block(Eigen::Index b, const double* log_w, const double* log_lik,
             const models::StatesView<float>* states, double uniform_log_w = 0.0);
  void block(Eigen::Index b, const double* log_w, const double* log_lik, std::nullptr_t,
             double uniform_log_w) {
    weigh(b, log_w, log_lik, uniform_log_w);
  }
  // Combines the blocks in order. InvalidArgument on a NaN or +inf t_i. Writes nothing.
  ReweightResult finish();
  // The weighted mean sum_i w_i x_i under the updated weights (part-based eq. 8), after finish()
  // of an update (result.updated()) whose blocks were given their states.
  const Eigen::VectorXd& mean() const { return mean_; }
  // Writes the normalised weights exp(log w) and, with log_weights, the normalised log weights
  // (a filter about to resample skips them: they become -log N). Only after an update.
  void commit(Eigen::VectorXd& log_w, Eigen::VectorXd& weights, int threads,
              bool log_weights = true) const;
  // Systematic resampling (core/resampling.hpp) of `count` particles from the updated weights,
  // read where the blocks left them (the weights are never written out): `offset` is the scheme's
  // one uniform in [0, 1). After finish() of an update. Each block fills the output slots its
  // cumulative weight covers, so blocks run in parallel with the same result for any `threads`.
  // The cumulative sums are formed per block (block prefix + the block's running sum), so near a
  // point the choice can differ by round-off (1e-16 relative) from core::resample on the committed
  // weights; a particle of zero weight is never drawn.
  void resample_systematic(std::size_t count, double offset, std::int64_t* ancestors,
                           int threads) const;

 private:
  struct BlockSums {
    double max;
    double sum;     // sum_i exp(t_i - max)
    double sum_sq;  // sum_i exp(t_i - max)^2
    Eigen::Index invalid;  // first index with NaN or +inf t_i, or -1
    Eigen::Index argmax;   // first index of the block's max
  };
  // block() without the state sums; false when the block holds an invalid t_i (nothing summed).
  bool weigh(Eigen::Index b, const double* log_w, const double* log_lik, double uniform_log_w);
  template <typename Scalar>
  void sum_states(Eigen::Index b, const models::StatesView<Scalar>& states);

  Eigen::Index n_ = 0;
  Eigen::Index d_ = 0;
  bool keep_log_ = true;
  bool single_exp_ = false;
  Eigen::VectorXd updated_;  // t (only with keep_log)
  Eigen::VectorXd scaled_;   // exp(t - block max)
  std::vector<BlockSums> blocks_;
  Eigen::MatrixXd block_state_sums_;  // d x blocks
  std::vector<double> scale_;  // per block: exp(max_b - max) / total
  double log_total_ = 0.0;
  Eigen::VectorXd mean_;
};

// One-call reweighting of a normalised log-weight vector (and its linear weights), for particle
// sets that are not fused with a propagation step.
ReweightResult reweight(Eigen::VectorXd& log_w, Eigen::VectorXd& weights,
                        const Eigen::Ref<const Eigen::VectorXd>& log_lik, int threads = 1);

}  // namespace vtrack::smc
