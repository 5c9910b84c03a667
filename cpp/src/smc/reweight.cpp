#include "vtrack/smc/reweight.hpp"

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/vmath.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/smc/blocks.hpp"

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace vtrack::smc {
namespace {

using core::kInf;

// a[j] <- max(start, a[begin], ..., a[j]) for j in [begin, end), for a[j] >= 0. The scalar loop's
// chain is a compare and a conditional move per element; with AVX-512 eight elements take a
// prefix maximum within the register (three shifted maxima) and then the carry of the eight
// before: 0.55 against 1.1-1.3 ns per particle of a systematic resampling, whatever the spread of
// the weights (smc_micro.cpp's header).
void running_max(std::int64_t* a, std::int64_t begin, std::int64_t end, std::int64_t start) {
  std::int64_t j = begin;
#if defined(__AVX512F__)
  const __m512i zero = _mm512_setzero_si512();
  __m512i carry = _mm512_set1_epi64(start);
  for (; j + 8 <= end; j += 8) {
    __m512i x = _mm512_loadu_si512(a + j);
    x = _mm512_max_epi64(x, _mm512_alignr_epi64(x, zero, 7));  // with x[i - 1]
    x = _mm512_max_epi64(x, _mm512_alignr_epi64(x, zero, 6));  // with x[i - 2], x[i - 3]
    x = _mm512_max_epi64(x, _mm512_alignr_epi64(x, zero, 4));  // with x[i - 4] ... x[i - 7]
    x = _mm512_max_epi64(x, carry);
    _mm512_storeu_si512(a + j, x);
    carry = _mm512_permutexvar_epi64(_mm512_set1_epi64(7), x);  // the last, in every lane
  }
  start = _mm_cvtsi128_si64(_mm512_castsi512_si128(carry));
#endif
  for (; j < end; ++j) {
    start = std::max(start, a[j]);
    a[j] = start;
  }
}

}  // namespace

void WeightUpdate::begin(Eigen::Index n, Eigen::Index d, bool keep_log, bool single_exp) {
  n_ = n;
  d_ = d;
  keep_log_ = keep_log;
  single_exp_ = single_exp;
  if (keep_log_) updated_.resize(n);
  scaled_.resize(n);
  blocks_.assign(static_cast<std::size_t>(block_count(n)), BlockSums{-kInf, 0.0, 0.0, -1, 0});
  block_state_sums_.setZero(d, static_cast<Eigen::Index>(blocks_.size()));
}

void WeightUpdate::block(Eigen::Index b, const double* log_w, const double* log_lik,
                         const models::StatesView<double>* states, double uniform_log_w) {
  if (weigh(b, log_w, log_lik, uniform_log_w) && states && d_ > 0) sum_states(b, *states);
}

void WeightUpdate::block(Eigen::Index b, const double* log_w, const double* log_lik,
                         const models::StatesView<float>* states, double uniform_log_w) {
  if (weigh(b, log_w, log_lik, uniform_log_w) && states && d_ > 0) sum_states(b, *states);
}

template <typename Scalar>
void WeightUpdate::sum_states(Eigen::Index b, const models::StatesView<Scalar>& states) {
  // sum_i e_i x_i while the block's states are in cache (eq. 8 before normalisation).
  const BlockRange r = block_range(b, n_);
  const Eigen::Map<const Eigen::VectorXd> e(scaled_.data() + r.begin, r.size());
  if constexpr (std::is_same_v<Scalar, double>) {
    block_state_sums_.col(b).noalias() = states.transpose() * e;
  } else {
    // Each component widened into a block buffer, then Eigen's vectorised dot (over a cast
    // expression it stays scalar: 4x slower).
    alignas(64) double widened[kBlockSize];
    Eigen::Map<Eigen::VectorXd> column(widened, r.size());
    for (Eigen::Index c = 0; c < states.cols(); ++c) {
      column = states.col(c).template cast<double>();
      block_state_sums_(c, b) = column.dot(e);
    }
  }
}

bool WeightUpdate::weigh(Eigen::Index b, const double* log_w, const double* log_lik,
                         double uniform_log_w) {
  const BlockRange r = block_range(b, n_);
  const Eigen::Index n = r.size();
  // t in the whole-set array when the log weights are kept, else in a block buffer (in cache).
  alignas(64) double local[kBlockSize];
  double* t = keep_log_ ? updated_.data() + r.begin : local;
  double* e = scaled_.data() + r.begin;
  Eigen::Map<Eigen::ArrayXd> tv(t, n);
  Eigen::Map<Eigen::ArrayXd> ev(e, n);
  const Eigen::Map<const Eigen::ArrayXd> ll(log_lik, n);
  if (log_w) {
    tv = Eigen::Map<const Eigen::ArrayXd>(log_w, n) + ll;
  } else {
    tv = uniform_log_w + ll;  // the same values as an array of uniform_log_w
  }
  BlockSums& s = blocks_[static_cast<std::size_t>(b)];
  s = {-kInf, 0.0, 0.0, -1, r.begin};
  s.max = tv.maxCoeff();
  // Its first index: eight at a time (the test of a group vectorises), then within the group.
  Eigen::Index first = 0;
  for (; first + 8 <= n; first += 8) {
    bool hit = false;
    for (int k = 0; k < 8; ++k) hit |= t[first + k] == s.max;
    if (hit) break;
  }
  while (first + 1 < n && t[first] != s.max) ++first;
  s.argmax = r.begin + first;
  // exp(t - max) and its sums: zero everywhere when the whole block is -inf.
  const double shift = s.max == -kInf ? 0.0 : s.max;
  if (single_exp_) {
    for (Eigen::Index i = 0; i < n; ++i) {
      e[i] = core::vmath::exp(static_cast<float>(t[i] - shift));
    }
  } else {
    for (Eigen::Index i = 0; i < n; ++i) e[i] = core::vmath::exp(t[i] - shift);
  }
  // Eigen's sums are vectorised with a fixed order, so they are reproducible.
  s.sum = ev.sum();
  s.sum_sq = ev.square().sum();
  // A NaN or +inf t_i makes its exp(t_i - max) NaN (NaN - max, or inf - inf with max = inf; a NaN
  // max makes them all NaN), while valid t_i give e_i in [0, 1]: so the sum tells without a pass
  // of its own, and the culprit is looked up only then.
  if (std::isnan(s.sum)) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!(t[i] < kInf)) {
        s.invalid = r.begin + i;
        return false;
      }
    }
  }
  return true;
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
  const Eigen::Index argmax = blocks_[static_cast<std::size_t>(best_block)].argmax;
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
  if (log_weights && !keep_log_) {
    throw std::logic_error("WeightUpdate::commit: log weights asked for but not kept");
  }
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

void WeightUpdate::resample_systematic(std::size_t count, double offset,
                                       std::int64_t* ancestors, int threads) const {
  // The cumulative weight before block b (normalised weights: block b weighs sum_b scale_b).
  const std::size_t blocks = blocks_.size();
  std::vector<double> prefix(blocks + 1, 0.0);
  for (std::size_t b = 0; b < blocks; ++b) prefix[b + 1] = prefix[b] + blocks_[b].sum * scale_[b];
  // As core::resample's systematic scheme: the points (j + offset) / count * total, and a
  // particle whose cumulative weight is C receives the points below it not taken before it,
  // i.e. up to slot ceil(C count / total - offset).
  const auto total_points = static_cast<std::int64_t>(count);
  const double points_per_weight = static_cast<double>(count) / prefix[blocks];
  auto slot = [&](double cumulative) {
    const double p = std::ceil(cumulative * points_per_weight - offset);
    return p <= 0.0 ? std::int64_t{0}
                    : (p >= static_cast<double>(count) ? total_points : static_cast<std::int64_t>(p));
  };
  std::vector<std::int64_t> first_slot(blocks + 1);
  for (std::size_t b = 0; b <= blocks; ++b) first_slot[b] = slot(prefix[b]);
  for_blocks(static_cast<Eigen::Index>(blocks), threads, [&](Eigen::Index b) {
    const auto bi = static_cast<std::size_t>(b);
    const std::int64_t begin = first_slot[bi];
    const std::int64_t end = first_slot[bi + 1];
    if (begin == end) return;  // (a block of positive weight whose points all fall in others)
    const BlockRange r = block_range(b, n_);
    const double* e = scaled_.data() + r.begin;
    const Eigen::Index n = r.size();
    // The block's cumulative weights, prefix + f (running sum of e), with the running sum split
    // into four chains over the block's quarters that advance together: a sum's latency per
    // particle would otherwise be the loop's critical path. Quarter k starts at the sum of the
    // quarters before it, so the sums stay non-decreasing across the quarters.
    alignas(64) double cum[kBlockSize];
    const Eigen::Index q = (n + 3) / 4;
    Eigen::Index len[4];
    for (int k = 0; k < 4; ++k) len[k] = std::max<Eigen::Index>(0, std::min(q, n - k * q));
    double run[4] = {0.0, 0.0, 0.0, 0.0};
    for (Eigen::Index j = 0; j < len[3]; ++j) {
      for (int k = 0; k < 4; ++k) {
        run[k] += e[k * q + j];
        cum[k * q + j] = run[k];
      }
    }
    for (int k = 0; k < 3; ++k) {
      for (Eigen::Index j = len[3]; j < len[k]; ++j) {
        run[k] += e[k * q + j];
        cum[k * q + j] = run[k];
      }
    }
    // The first slot past each particle's cumulative weight, c_i. As an integer from the exact
    // double through its bit pattern (c + 2^52 holds c in its low bits), which vectorises where
    // a double-to-int64 conversion does not (AVX2).
    alignas(64) std::int64_t stop[kBlockSize];
    double base = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double p0 = prefix[bi];
      const double f = scale_[bi];
      const double last = static_cast<double>(end);
      const double* c = cum + k * q;
      std::int64_t* s = stop + k * q;
      for (Eigen::Index j = 0; j < len[k]; ++j) {
        const double p = std::ceil((p0 + f * (base + c[j])) * points_per_weight - offset);
        const double slot = std::min(last, std::max(0.0, p));
        s[j] = static_cast<std::int64_t>(core::vmath::bits(slot + 0x1.0p52) -
                                         core::vmath::bits(0x1.0p52));
      }
      base += run[k];
    }
    // The marks of core/resampling.cpp's systematic(): particle i writes its index into the first
    // slot it would own, c_{i-1}; a running maximum then fills the runs. Marks past the block's
    // last filled slot go to `dummy`.
    std::fill(ancestors + begin, ancestors + end, std::int64_t{0});
    std::int64_t dummy = 0;
    std::int64_t filled = begin;
    for (Eigen::Index i = 0; i < n; ++i) {
      *(filled < end ? ancestors + filled : &dummy) = r.begin + i;
      filled = stop[i];
    }
    running_max(ancestors, begin, filled, r.begin);
    Eigen::Index last_positive = n - 1;
    while (last_positive > 0 && !(e[last_positive] > 0.0)) --last_positive;
    last_positive += r.begin;
    // Round-off between the running sum and the block total: the rest to the last positive one.
    for (std::int64_t j = filled; j < end; ++j) ancestors[j] = last_positive;
  });
  if (first_slot[blocks] < total_points) {
    // Round-off at the very end: the last particle of positive weight.
    Eigen::Index last = n_ - 1;
    while (last > 0 && !(scaled_[last] > 0.0 && scale_[static_cast<std::size_t>(last / kBlockSize)] > 0.0)) --last;
    std::fill(ancestors + first_slot[blocks], ancestors + total_points, static_cast<std::int64_t>(last));
  }
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
