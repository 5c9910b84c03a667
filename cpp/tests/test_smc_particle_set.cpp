// smc::ParticleSet and the reweighting of smc/reweight.hpp, against brute-force sums.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <vector>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/smc/particle_set.hpp"

using namespace vtrack;
using smc::ParticleSet;

namespace {

using vtrack::core::kInf;

ParticleSet<double> random_set(core::Rng& rng, Eigen::Index n, Eigen::Index d) {
  Eigen::MatrixXd x(n, d);
  rng.fill_normal(x.data(), static_cast<std::size_t>(x.size()));
  Eigen::VectorXd lw(n);
  rng.fill_normal(lw.data(), static_cast<std::size_t>(n));
  return ParticleSet<double>(x, 3.0 * lw);
}

}  // namespace

TEST(SmcParticleSet, ReweightReturnsTheLogNormaliserAndNormalisedWeights) {
  core::Rng rng(1);
  // 5000 particles: several blocks, so the blockwise sums are exercised.
  ParticleSet<double> set = random_set(rng, 5000, 3);
  const Eigen::VectorXd w0 = set.weights();
  Eigen::VectorXd log_lik(5000);
  rng.fill_normal(log_lik.data(), 5000);
  log_lik *= 4.0;
  log_lik[7] = -kInf;  // a particle the data rule out
  const auto result = set.reweight(log_lik);
  // Brute force: rho = sum_i w_i l_i, w_i' = w_i l_i / rho.
  long double rho = 0;
  for (int i = 0; i < 5000; ++i) rho += w0[i] * std::exp(static_cast<long double>(log_lik[i]));
  EXPECT_NEAR(result.log_normaliser, std::log(static_cast<double>(rho)), 1e-12);
  double sum_sq = 0;
  Eigen::Index best = 0;
  for (int i = 0; i < 5000; ++i) {
    const double expected = w0[i] * std::exp(log_lik[i]) / static_cast<double>(rho);
    EXPECT_NEAR(set.weights()[i], expected, 1e-14 + 1e-12 * expected);
    EXPECT_NEAR(std::exp(set.log_weights()[i]), set.weights()[i], 1e-15);
    sum_sq += expected * expected;
    if (expected > w0[best] * std::exp(log_lik[best]) / static_cast<double>(rho)) best = i;
  }
  EXPECT_EQ(set.weights()[7], 0.0);
  EXPECT_NEAR(set.ess(), 1.0 / sum_sq, 1e-9 / sum_sq);  // eq. 7
  EXPECT_EQ(set.map_index(), best);
  EXPECT_EQ(result.map_index, best);
}

TEST(SmcParticleSet, AllLikelihoodsZeroKeepsTheWeights) {
  core::Rng rng(2);
  ParticleSet<double> set = random_set(rng, 3000, 2);
  const Eigen::VectorXd before = set.log_weights();
  const auto result = set.reweight(Eigen::VectorXd::Constant(3000, -kInf));
  EXPECT_FALSE(result.updated());
  EXPECT_EQ(result.log_normaliser, -kInf);
  EXPECT_EQ(set.log_weights(), before);
  EXPECT_TRUE(set.mean().allFinite());
}

TEST(SmcParticleSet, NanOrPlusInfLikelihoodIsAnError) {
  core::Rng rng(3);
  ParticleSet<double> set = random_set(rng, 2500, 2);
  const Eigen::VectorXd before = set.log_weights();
  Eigen::VectorXd log_lik = Eigen::VectorXd::Zero(2500);
  log_lik[2100] = std::nan("");
  try {
    set.reweight(log_lik);
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("particle 2100"), std::string::npos) << e.what();
  }
  log_lik[2100] = kInf;
  EXPECT_THROW(set.reweight(log_lik), InvalidArgument);
  EXPECT_EQ(set.log_weights(), before);  // unchanged by the failed updates
}

TEST(SmcParticleSet, ReweightIsIdenticalForAnyThreadCount) {
  core::Rng rng(4);
  const ParticleSet<double> base = random_set(rng, 20000, 2);
  Eigen::VectorXd log_lik(20000);
  rng.fill_normal(log_lik.data(), 20000);
  ParticleSet<double> one = base, two = base, all = base;
  const auto r1 = one.reweight(log_lik, 1);
  const auto r2 = two.reweight(log_lik, 2);
  const auto r0 = all.reweight(log_lik, 0);
  EXPECT_EQ(r1.log_normaliser, r2.log_normaliser);
  EXPECT_EQ(r1.log_normaliser, r0.log_normaliser);
  EXPECT_EQ(one.weights(), two.weights());
  EXPECT_EQ(one.weights(), all.weights());
  EXPECT_EQ(one.ess(), two.ess());
}

TEST(SmcParticleSet, MeanCovarianceAndMapAreTheWeightedOnes) {
  core::Rng rng(5);
  const ParticleSet<double> set = random_set(rng, 400, 3);
  const Eigen::MatrixXd& x = set.states();
  const Eigen::VectorXd& w = set.weights();
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(3);
  for (int i = 0; i < 400; ++i) mean += w[i] * x.row(i).transpose();
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(3, 3);
  for (int i = 0; i < 400; ++i) {
    const Eigen::VectorXd d = x.row(i).transpose() - mean;
    cov += w[i] * d * d.transpose();
  }
  EXPECT_LT((set.mean() - mean).norm(), 1e-12);
  EXPECT_LT((set.covariance() - cov).norm(), 1e-12);
  Eigen::Index best;
  w.maxCoeff(&best);
  EXPECT_EQ(set.map_estimate(), x.row(best).transpose());
}

TEST(SmcParticleSet, ResamplesToAnySizeWithEveryScheme) {
  for (const auto scheme : {core::ResamplingScheme::Multinomial, core::ResamplingScheme::Stratified,
                            core::ResamplingScheme::Systematic, core::ResamplingScheme::Residual}) {
    core::Rng rng(6);
    Eigen::MatrixXf x(300, 4);  // float boxes, as the multi-Bernoulli filter's
    for (int i = 0; i < 300; ++i) x.row(i).setConstant(static_cast<float>(i));
    Eigen::VectorXd lw(300);
    for (int i = 0; i < 300; ++i) lw[i] = i % 3 == 0 ? -kInf : -0.01 * i;  // a third weigh zero
    ParticleSet<float, 4> set(x, lw);
    for (const Eigen::Index count : {50, 300, 1234}) {
      ParticleSet<float, 4> copy = set;
      copy.resample(scheme, count, rng);
      ASSERT_EQ(copy.size(), count);
      EXPECT_NEAR(copy.weights().sum(), 1.0, 1e-12);
      EXPECT_EQ(copy.ess(), static_cast<double>(count));
      for (Eigen::Index j = 0; j < count; ++j) {
        const auto a = copy.ancestors()[static_cast<std::size_t>(j)];
        EXPECT_NE(a % 3, 0) << "zero-weight particle " << a << " survived " << core::to_string(scheme);
        EXPECT_EQ(copy.states()(j, 2), static_cast<float>(a));  // the ancestor's whole row
      }
    }
  }
}

TEST(SmcParticleSet, ResamplingIsIdenticalForAnyThreadCount) {
  core::Rng r(7);
  const ParticleSet<double> base = random_set(r, 10000, 4);
  ParticleSet<double> a = base, b = base;
  core::Rng ra(8), rb(8);
  a.resample(core::ResamplingScheme::Systematic, 12000, ra, 1);
  b.resample(core::ResamplingScheme::Systematic, 12000, rb, 2);
  EXPECT_EQ(a.states(), b.states());
}

TEST(SmcParticleSet, RejectsBadWeights) {
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(3, 2);
  EXPECT_THROW(ParticleSet<double>(x, Eigen::VectorXd::Constant(3, -kInf)), InvalidArgument);
  EXPECT_THROW(ParticleSet<double>(x, Eigen::Vector3d(0.0, std::nan(""), 0.0)), InvalidArgument);
  EXPECT_THROW(ParticleSet<double>(x, Eigen::Vector2d(0.0, 0.0)), InvalidArgument);
  ParticleSet<double> set(x);
  core::Rng rng(1);
  EXPECT_THROW(set.resample(core::ResamplingScheme::Systematic, 0, rng), InvalidArgument);
}

namespace {

// A WeightUpdate of n particles (uniform prior weights) with the given log-likelihoods.
smc::ReweightResult update_with(smc::WeightUpdate& update, const Eigen::VectorXd& log_lik,
                                bool keep_log) {
  const Eigen::Index n = log_lik.size();
  update.begin(n, 0, keep_log);
  for (Eigen::Index b = 0; b < smc::block_count(n); ++b) {
    const Eigen::Index begin = smc::block_range(b, n).begin;
    update.block(b, nullptr, log_lik.data() + begin, nullptr, -std::log(static_cast<double>(n)));
  }
  return update.finish();
}

}  // namespace

TEST(SmcParticleSet, BlockwiseSystematicResamplingMatchesTheSchemeOnTheWrittenWeights) {
  // Reference: core::resample's systematic scheme on the committed weights, with the same offset.
  // The blockwise cumulative sums differ from the sequential ones by round-off only, so the
  // ancestors agree except for a point that falls within ~1e-16 of a cumulative weight.
  core::Rng rng(7);
  for (const Eigen::Index n : {1, 5, 1024, 1025, 5000, 20000}) {
    Eigen::VectorXd log_lik(n);
    rng.fill_normal(log_lik.data(), static_cast<std::size_t>(n));
    log_lik *= 3.0;
    for (Eigen::Index i = 3; i < n; i += 11) log_lik[i] = -kInf;  // zero weights, never drawn
    smc::WeightUpdate update;
    ASSERT_TRUE(update_with(update, log_lik, false).updated());
    Eigen::VectorXd log_w, w;
    update.commit(log_w, w, 1, false);
    for (const std::size_t count : {std::size_t{1}, static_cast<std::size_t>(n), std::size_t{3000}}) {
      std::vector<std::int64_t> fused(count), reference(count);
      core::Rng replay = rng;  // core::resample draws its offset, one uniform, from the generator
      const double offset = rng.uniform();
      update.resample_systematic(count, offset, fused.data(), 1);
      core::resample(core::ResamplingScheme::Systematic, w, count, replay, reference.data());
      std::size_t differ = 0;
      for (std::size_t j = 0; j < count; ++j) {
        differ += fused[j] != reference[j];
        ASSERT_GE(fused[j], 0);
        ASSERT_LT(fused[j], n);
        EXPECT_GT(w[fused[j]], 0.0) << "a zero-weight particle was drawn, n = " << n;
        if (j > 0) EXPECT_GE(fused[j], fused[j - 1]);
      }
      EXPECT_EQ(differ, 0u) << "n = " << n << ", count = " << count;
      // Any thread count: the same ancestors.
      std::vector<std::int64_t> threaded(count);
      update.resample_systematic(count, offset, threaded.data(), 2);
      EXPECT_EQ(threaded, fused);
    }
  }
}

TEST(SmcParticleSet, BlockwiseSystematicResamplingCopiesEachParticleByItsWeight) {
  // Systematic resampling gives particle i floor(N w_i) or ceil(N w_i) copies.
  core::Rng rng(11);
  const Eigen::Index n = 4096;
  Eigen::VectorXd log_lik(n);
  rng.fill_normal(log_lik.data(), static_cast<std::size_t>(n));
  smc::WeightUpdate update;
  ASSERT_TRUE(update_with(update, log_lik, false).updated());
  Eigen::VectorXd log_w, w;
  update.commit(log_w, w, 1, false);
  std::vector<std::int64_t> a(static_cast<std::size_t>(n));
  update.resample_systematic(static_cast<std::size_t>(n), 0.37, a.data(), 1);
  std::vector<int> copies(static_cast<std::size_t>(n), 0);
  for (std::int64_t i : a) ++copies[static_cast<std::size_t>(i)];
  for (Eigen::Index i = 0; i < n; ++i) {
    const double expected = static_cast<double>(n) * w[i];
    EXPECT_GE(copies[static_cast<std::size_t>(i)], std::floor(expected) - 1e-9) << i;
    EXPECT_LE(copies[static_cast<std::size_t>(i)], std::ceil(expected) + 1e-9) << i;
  }
}

TEST(SmcParticleSet, WeightUpdateWithoutLogWeightsRefusesToWriteThem) {
  Eigen::VectorXd log_lik = Eigen::VectorXd::LinSpaced(100, -3.0, 1.0);
  smc::WeightUpdate update;
  update_with(update, log_lik, false);
  Eigen::VectorXd log_w, w;
  EXPECT_THROW(update.commit(log_w, w, 1, true), std::logic_error);
  update.commit(log_w, w, 1, false);
  EXPECT_NEAR(w.sum(), 1.0, 1e-12);
}

namespace {

// gather_block against an index-by-index copy, for ancestors of every kind: sorted as systematic
// resampling leaves them (the permutation path), sorted with gaps wider than a window, shuffled
// and descending (the scalar path), and windows that reach the last source row.
template <typename T>
void check_gather_block(const std::vector<std::int64_t>& ancestors, Eigen::Index src_rows,
                        Eigen::Index cols) {
  using Matrix = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
  Matrix src(src_rows, cols);
  for (Eigen::Index i = 0; i < src.size(); ++i) src.data()[i] = static_cast<T>(i) + T(0.5);
  const auto n = static_cast<Eigen::Index>(ancestors.size());
  Matrix dst = Matrix::Constant(n, cols, T(-1));
  smc::gather_block(src.data(), src_rows, src_rows, cols, ancestors.data(), n, dst.data(), n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index c = 0; c < cols; ++c) {
      ASSERT_EQ(dst(j, c), src(ancestors[static_cast<std::size_t>(j)], c))
          << "row " << j << " column " << c << " of " << cols;
    }
  }
}

}  // namespace

TEST(SmcGather, MatchesAnIndexByIndexCopyForEveryKindOfAncestors) {
  core::Rng rng(11);
  const Eigen::Index rows = 300;
  std::vector<std::vector<std::int64_t>> cases;
  // Systematic resampling of random weights: sorted, runs of copies.
  Eigen::VectorXd w(rows);
  for (Eigen::Index i = 0; i < rows; ++i) w[i] = std::exp(2.0 * rng.normal());
  w /= w.sum();
  std::vector<std::int64_t> sorted(rows);
  core::resample(core::ResamplingScheme::Systematic, w, rows, rng, sorted.data());
  cases.push_back(sorted);
  // Sorted with gaps of 3 (16 consecutive ancestors span 45 rows: wider than a window).
  std::vector<std::int64_t> gaps;
  for (std::int64_t k = 0; k < rows; k += 3) gaps.push_back(k);
  cases.push_back(gaps);
  // Shuffled, descending, and the last rows only (a window that ends at the last source row).
  std::vector<std::int64_t> shuffled(sorted.rbegin(), sorted.rend());
  cases.push_back(shuffled);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  cases.push_back(shuffled);
  cases.push_back(std::vector<std::int64_t>(40, rows - 1));
  std::vector<std::int64_t> tail;
  for (std::int64_t k = rows - 32; k < rows; ++k) tail.insert(tail.end(), 2, k);
  cases.push_back(tail);
  for (const auto& ancestors : cases) {
    for (Eigen::Index cols : {1, 2, 3, 4, 5, 7}) {
      check_gather_block<float>(ancestors, rows, cols);
      check_gather_block<double>(ancestors, rows, cols);
      check_gather_block<std::int64_t>(ancestors, rows, cols);
    }
  }
}
