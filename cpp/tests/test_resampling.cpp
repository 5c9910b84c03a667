#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/resampling.hpp"

using namespace vtrack::core;

namespace {

const ResamplingScheme kSchemes[] = {ResamplingScheme::Multinomial, ResamplingScheme::Stratified,
                                     ResamplingScheme::Systematic, ResamplingScheme::Residual};

Eigen::VectorXd random_weights_with_zeros(Rng& rng, int n) {
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) w[i] = (i % 4 == 0) ? 0.0 : rng.uniform();
  w[1] *= 20.0;  // one dominant particle
  return w / w.sum();
}

std::vector<int> offspring_counts(const std::vector<std::int64_t>& ancestors, int n) {
  std::vector<int> counts(n, 0);
  for (auto a : ancestors) ++counts[a];
  return counts;
}

class ResamplingScheme_ : public ::testing::TestWithParam<ResamplingScheme> {};

}  // namespace

TEST_P(ResamplingScheme_, IsUnbiased) {
  // E[offspring of i] = M w_i. Over T trials the mean count has standard deviation at most
  // sqrt(M w (1 - w) / T) (the multinomial's; the other schemes have less), so 5 of those plus a
  // rounding slack is a bound a correct scheme fails with probability ~1e-6 per particle.
  Rng rng(11);
  const int n = 20;
  const Eigen::VectorXd w = random_weights_with_zeros(rng, n);
  for (const std::size_t m : {std::size_t{20}, std::size_t{7}, std::size_t{53}}) {
    const int trials = 20000;
    std::vector<double> mean(n, 0.0);
    for (int t = 0; t < trials; ++t) {
      const auto counts = offspring_counts(resample(GetParam(), w, m, rng), n);
      for (int i = 0; i < n; ++i) mean[i] += counts[i];
    }
    for (int i = 0; i < n; ++i) {
      mean[i] /= trials;
      const double expected = static_cast<double>(m) * w[i];
      const double sd = std::sqrt(static_cast<double>(m) * w[i] * (1 - w[i]) / trials);
      EXPECT_NEAR(mean[i], expected, 5 * sd + 1e-12)
          << to_string(GetParam()) << " particle " << i << " M=" << m;
    }
  }
}

TEST_P(ResamplingScheme_, NeverChoosesZeroWeightParticles) {
  Rng rng(12);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(50);
  w[7] = 1e-300;  // tiny but positive: may be chosen; its zero neighbours never
  w[20] = 0.3;
  w[21] = 0.7;
  for (int trial = 0; trial < 2000; ++trial) {
    for (auto a : resample(GetParam(), w, 50, rng)) {
      ASSERT_TRUE(a == 7 || a == 20 || a == 21) << to_string(GetParam()) << " chose " << a;
    }
  }
  // Weights whose cumulative sum rounds below the last uniform point.
  Eigen::VectorXd w2 = Eigen::VectorXd::Constant(1000, 0.1);
  w2.tail(10).setZero();
  for (int trial = 0; trial < 200; ++trial) {
    for (auto a : resample(GetParam(), w2, 1000, rng)) ASSERT_LT(a, 990);
  }
}

TEST_P(ResamplingScheme_, ReturnsSortedIndicesOfTheRequestedCount) {
  Rng rng(13);
  const Eigen::VectorXd w = random_weights_with_zeros(rng, 30);
  for (std::size_t m : {std::size_t{0}, std::size_t{1}, std::size_t{30}, std::size_t{100}}) {
    const auto a = resample(GetParam(), w, m, rng);
    ASSERT_EQ(a.size(), m);
    EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
    for (auto i : a) EXPECT_TRUE(i >= 0 && i < 30);
  }
}

TEST_P(ResamplingScheme_, SameSeedSameAncestors) {
  Rng a(5), b(5);
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(40, 0.0, 1.0);
  EXPECT_EQ(resample(GetParam(), w, 40, a), resample(GetParam(), w, 40, b));
}

TEST_P(ResamplingScheme_, RejectsBadWeights) {
  Rng rng(1);
  EXPECT_THROW(resample(GetParam(), Eigen::VectorXd(), 3, rng), vtrack::InvalidArgument);
  EXPECT_THROW(resample(GetParam(), Eigen::VectorXd::Zero(3), 3, rng), vtrack::InvalidArgument);
  Eigen::VectorXd w(3);
  w << 0.5, -0.1, 0.6;
  EXPECT_THROW(resample(GetParam(), w, 3, rng), vtrack::InvalidArgument);
  w << 0.5, std::nan(""), 0.6;
  EXPECT_THROW(resample(GetParam(), w, 3, rng), vtrack::InvalidArgument);
}

INSTANTIATE_TEST_SUITE_P(AllSchemes, ResamplingScheme_, ::testing::ValuesIn(kSchemes),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(Resampling, SystematicGivesEachParticleFloorOrCeilOfItsExpectedCount) {
  Rng rng(14);
  const Eigen::VectorXd w = random_weights_with_zeros(rng, 25);
  for (int trial = 0; trial < 500; ++trial) {
    const auto counts = offspring_counts(resample(ResamplingScheme::Systematic, w, 25, rng), 25);
    for (int i = 0; i < 25; ++i) {
      const double expected = 25 * w[i];
      EXPECT_GE(counts[i], std::floor(expected) - 1e-9);
      EXPECT_LE(counts[i], std::ceil(expected) + 1e-9);
    }
  }
}

TEST(Resampling, ResidualKeepsTheDeterministicCopies) {
  Rng rng(15);
  const Eigen::VectorXd w = random_weights_with_zeros(rng, 25);
  for (int trial = 0; trial < 500; ++trial) {
    const auto counts = offspring_counts(resample(ResamplingScheme::Residual, w, 25, rng), 25);
    for (int i = 0; i < 25; ++i) EXPECT_GE(counts[i], std::floor(25 * w[i] + 1e-12));
  }
}

TEST(Resampling, ParsesSchemeNames) {
  for (auto s : kSchemes) EXPECT_EQ(parse_resampling_scheme(to_string(s)), s);
  EXPECT_THROW(parse_resampling_scheme("bogus"), vtrack::InvalidArgument);
}
