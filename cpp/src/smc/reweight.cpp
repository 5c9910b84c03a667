#include "vtrack/smc/reweight.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/vmath.hpp"
#include "vtrack/smc/blocks.hpp"

namespace vtrack::smc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

void WeightUpdate::begin(Eigen::Index n, Eigen::Index d) {
  n_ = n;
  d_ = d;
  updated_.resize(n);
  scaled_.resize(n);
  blocks_.assign(static_cast<std::size_t>(block_count(n)), BlockSums{-kInf, 0.0, 0.0, -1});
  block_state_sums_.setZero(d, static_cast<Eigen::Index>(blocks_.size()));
}

void WeightUpdate::block(Eigen::Index b, const double* log_w, const double* log_lik,
                         const models::StatesView<double>* states) {
  const BlockRange r = block_range(b, n_);
  double* t = updated_.data() + r.begin;
  double* e = scaled_.data() + r.begin;
  const double* lw = log_w;
  const double* ll = log_lik;
  const Eigen::Index n = r.size();
  Eigen::Map<Eigen::ArrayXd> tv(t, n);
  Eigen::Map<Eigen::ArrayXd> ev(e, n);
  tv = Eigen::Map<const Eigen::ArrayXd>(lw, n) + Eigen::Map<const Eigen::ArrayXd>(ll, n);
  BlockSums& s = blocks_[static_cast<std::size_t>(b)];
  s = {-kInf, 0.0, 0.0, -1};
  // A NaN or +inf anywhere makes the sum NaN or +inf (-inf entries alone give -inf): one
  // vectorised pass instead of a test per particle; the culprit is looked up only then.
  const double check = tv.sum();
  if (std::isnan(check) || check == kInf) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!(t[i] < kInf)) {
        s.invalid = r.begin + i;
        return;
      }
    }  // (not found: finite values whose sum overflowed; carry on)
  }
  s.max = tv.maxCoeff();
  // exp(t - max): zero everywhere when the whole block is -inf. Eigen's sums are vectorised with a
  // fixed order, so they are reproducible.
  const double shift = s.max == -kInf ? 0.0 : s.max;
  for (Eigen::Index i = 0; i < n; ++i) e[i] = core::vmath::exp(t[i] - shift);
  s.sum = ev.sum();
  s.sum_sq = ev.square().sum();
  if (states && d_ > 0) {
    // sum_i e_i x_i while the block's states are in cache (eq. 8 before normalisation).
    block_state_sums_.col(b).noalias() = states->transpose() * ev.matrix();
  }
}

ReweightResult WeightUpdate::finish() {
  double peak = -kInf;
  Eigen::Index best_block = 0;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const BlockSums& s = blocks_[b];
    if (s.invalid >= 0) {
      throw InvalidArgument("log-likelihood of particle " + std::to_string(s.invalid) +
                            " is NaN or +inf (a likelihood must be finite; 0 is -inf)");
    }
    if (s.max > peak) {
      peak = s.max;
      best_block = static_cast<Eigen::Index>(b);
    }
  }
  if (peak == -kInf || n_ == 0) return {-kInf, 0.0, 0};  // nothing learnt: weights kept
  // The particle of largest weight: the first maximum of the first block that holds one.
  Eigen::Index argmax = block_range(best_block, n_).begin;
  while (updated_[argmax] != peak) ++argmax;
  // Blocks combined in order: total = sum_b sum_b' e^(max_b - peak).
  double total = 0.0;
  double total_sq = 0.0;
  scale_.resize(blocks_.size());
  mean_.setZero(d_);
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const double f = std::exp(blocks_[b].max - peak);
    scale_[b] = f;
    total += blocks_[b].sum * f;
    total_sq += blocks_[b].sum_sq * f * f;
    if (d_ > 0) mean_ += f * block_state_sums_.col(static_cast<Eigen::Index>(b));
  }
  for (double& f : scale_) f /= total;
  mean_ /= total;
  log_total_ = peak + std::log(total);
  return {log_total_, total * total / total_sq, argmax};
}

void WeightUpdate::commit(Eigen::VectorXd& log_w, Eigen::VectorXd& weights, int threads,
                          bool log_weights) const {
  log_w.resize(n_);
  weights.resize(n_);
  for_blocks(static_cast<Eigen::Index>(blocks_.size()), threads, [&](Eigen::Index b) {
    const BlockRange r = block_range(b, n_);
    const double f = scale_[static_cast<std::size_t>(b)];
    for (Eigen::Index i = r.begin; i < r.end; ++i) weights[i] = scaled_[i] * f;
    if (!log_weights) return;
    for (Eigen::Index i = r.begin; i < r.end; ++i) log_w[i] = updated_[i] - log_total_;
  });
}

ReweightResult reweight(Eigen::VectorXd& log_w, Eigen::VectorXd& weights,
                        const Eigen::Ref<const Eigen::VectorXd>& log_lik, int threads) {
  if (log_lik.size() != log_w.size()) {
    throw InvalidArgument("log_lik has " + std::to_string(log_lik.size()) + " entries for " +
                          std::to_string(log_w.size()) + " particles");
  }
  WeightUpdate update;
  update.begin(log_w.size());
  const Eigen::VectorXd& lw = log_w;
  for_blocks(block_count(log_w.size()), threads,
             [&](Eigen::Index b) {
               const Eigen::Index begin = block_range(b, lw.size()).begin;
               update.block(b, lw.data() + begin, log_lik.data() + begin);
             });
  const ReweightResult result = update.finish();
  if (result.updated()) update.commit(log_w, weights, threads);
  return result;
}

}  // namespace vtrack::smc
