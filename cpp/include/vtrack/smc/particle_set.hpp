#pragma once
// A weighted particle set {x_i, w_i}, i = 1..N (part-based paper Section 2; the posterior
// approximation p(x|Z) ~ sum_i w_i delta(x - x_i) of particle-filters-human-vehicle eq. in §1.2).
//
// Storage: the states are an N x d column-major matrix, one particle per ROW, so each state
// component is contiguous across particles (structure of arrays). Model loops run over particles
// with unit stride and vectorise (4 doubles or 8 floats per AVX2 instruction) without gathers;
// with one particle per column (d x N) a loop over particles reads each component with stride d.
// Measured (benchmarks/cpp/smc_layout.cpp, N = 1e5, d = 4): constant-velocity propagation and the
// range-bearing likelihood are faster in this layout, resampling's gather and the weighted mean
// about equal (the figures are in that file's header).
//
// Weights are kept in the log domain (normalised: log-sum-exp = 0) together with their linear
// values exp(log w), which every update produces anyway and resampling and estimates need.
// Scalar is the state type (double; float for image-space boxes); weights are always double.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/smc/blocks.hpp"
#include "vtrack/smc/gather.hpp"
#include "vtrack/smc/reweight.hpp"

namespace vtrack::smc {

// dst <- rows ancestors[0..count) of src (column-major matrices or vectors; dst must not be
// src), in parallel over blocks of dst.
template <class Matrix>
void gather_rows(const Matrix& src, const std::int64_t* ancestors, Eigen::Index count, Matrix& dst,
                 int threads = 1) {
  static_assert(!Matrix::IsRowMajor, "particle arrays are column-major, one particle per row");
  dst.resize(count, src.cols());
  for_blocks(block_count(count), threads, [&](Eigen::Index b) {
    const BlockRange r = block_range(b, count);
    gather_block(src.data(), src.rows(), src.rows(), src.cols(), ancestors + r.begin, r.size(),
                 dst.data() + r.begin, count);
  });
}

template <typename Scalar = double, int Dim = Eigen::Dynamic>
class ParticleSet {
 public:
  using States = Eigen::Matrix<Scalar, Eigen::Dynamic, Dim>;  // N x d, one particle per row
  using State = Eigen::Matrix<Scalar, Dim, 1>;

  ParticleSet() = default;
  // Equal weights 1/N.
  explicit ParticleSet(States states) : states_(std::move(states)) { set_uniform(); }
  // Given (unnormalised) log weights; InvalidArgument if one is NaN or +inf or all are -inf.
  ParticleSet(States states, const Eigen::Ref<const Eigen::VectorXd>& log_weights)
      : states_(std::move(states)) {
    if (log_weights.size() != states_.rows()) {
      throw InvalidArgument("log_weights has " + std::to_string(log_weights.size()) +
                            " entries for " + std::to_string(states_.rows()) + " particles");
    }
    const double total = core::log_sum_exp(log_weights);
    if (!(total > -kInf) || !(total < kInf)) {
      throw InvalidArgument("log_weights must be finite or -inf and not all -inf");
    }
    log_w_ = log_weights.array() - total;
    w_ = log_w_.array().exp();
    ess_ = core::effective_sample_size(w_);
    w_.maxCoeff(&map_index_);
  }

  Eigen::Index size() const { return states_.rows(); }
  Eigen::Index dim() const { return states_.cols(); }
  const States& states() const { return states_; }
  // Mutable access for propagation in place (the weights are not touched).
  States& states() { return states_; }
  const Eigen::VectorXd& log_weights() const { return log_w_; }
  const Eigen::VectorXd& weights() const { return w_; }
  // N_eff = 1 / sum_i w_i^2 (eq. 7).
  double ess() const { return ess_; }
  // A particle of largest weight (the first in index order).
  Eigen::Index map_index() const { return map_index_; }

  // w_i <- w_i l_i / sum_j w_j l_j for log_lik_i = log l_i (eqs. 5-6 with the bootstrap proposal);
  // returns the log normaliser log sum_j w_j l_j and N_eff. See reweight.hpp for -inf and NaN.
  ReweightResult reweight(const Eigen::Ref<const Eigen::VectorXd>& log_lik, int threads = 1) {
    const ReweightResult r = smc::reweight(log_w_, w_, log_lik, threads);
    if (r.updated()) {
      ess_ = r.ess;
      map_index_ = r.map_index;
    }
    return r;
  }
  // After an external update of the log weights (normalised, as WeightUpdate::finish leaves them).
  void set_updated(const ReweightResult& r) {
    if (!r.updated()) return;
    ess_ = r.ess;
    map_index_ = r.map_index;
  }
  // Log and linear weights, for filters that fuse the update with their own per-block work.
  Eigen::VectorXd& log_weights_buffer() { return log_w_; }
  Eigen::VectorXd& weights_buffer() { return w_; }

  // Draws `count` particles by `scheme` (any of the four of core/resampling.hpp) from the current
  // weights; they get equal weights 1/count. A particle of zero weight is never drawn.
  void resample(core::ResamplingScheme scheme, Eigen::Index count, core::Rng& rng,
                int threads = 1) {
    draw_ancestors(scheme, count, rng);
    States next;
    gather_rows(states_, ancestors_.data(), count, next, threads);
    states_ = std::move(next);
    set_uniform();
  }
  // The ancestors chosen by the last resample (or draw_ancestors), for carrying per-particle data
  // along (gather_rows).
  const std::vector<std::int64_t>& ancestors() const { return ancestors_; }
  // Only the ancestor draw of resample(), for callers that gather several arrays themselves and
  // then call set_uniform() after replacing the states.
  void draw_ancestors(core::ResamplingScheme scheme, Eigen::Index count, core::Rng& rng) {
    if (count < 1) throw InvalidArgument("resampling count must be >= 1, got " + std::to_string(count));
    ancestors_.resize(static_cast<std::size_t>(count));
    core::resample(scheme, w_, static_cast<std::size_t>(count), rng, ancestors_.data());
  }
  // The ancestor array to fill (count entries), for a filter that draws them itself
  // (WeightUpdate::resample_systematic); it then gathers the states and calls set_uniform().
  std::int64_t* ancestors_buffer(Eigen::Index count) {
    ancestors_.resize(static_cast<std::size_t>(count));
    return ancestors_.data();
  }
  void set_uniform() {
    const Eigen::Index n = states_.rows();
    log_w_.setConstant(n, n > 0 ? -std::log(static_cast<double>(n)) : 0.0);
    w_.setConstant(n, n > 0 ? 1.0 / static_cast<double>(n) : 0.0);
    ess_ = static_cast<double>(n);
    map_index_ = 0;
  }

  // Weighted mean sum_i w_i x_i (part-based eq. 8), accumulated in double.
  Eigen::VectorXd mean() const {
    Eigen::VectorXd m(dim());
    for (Eigen::Index c = 0; c < dim(); ++c) m[c] = states_.col(c).template cast<double>().dot(w_);
    return m;
  }
  // Weighted covariance sum_i w_i (x_i - m)(x_i - m)^T.
  Eigen::MatrixXd covariance() const {
    const Eigen::MatrixXd centred = states_.template cast<double>().rowwise() - mean().transpose();
    return centred.transpose() * w_.asDiagonal() * centred;
  }
  State map_estimate() const { return states_.row(map_index_).transpose(); }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  States states_;
  Eigen::VectorXd log_w_;
  Eigen::VectorXd w_;
  double ess_ = 0.0;
  Eigen::Index map_index_ = 0;
  std::vector<std::int64_t> ancestors_;
};

}  // namespace vtrack::smc
