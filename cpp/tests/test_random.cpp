#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "distributions.hpp"

using vtrack::core::Rng;

TEST(Rng, MatchesReferenceXoshiro256StarStar) {
  // First outputs of the authors' reference C code (prng.di.unimi.it) from state {1, 2, 3, 4},
  // computed by hand from its definition: result = rotl(s1 * 5, 7) * 9, then the state update.
  Rng rng = Rng::from_state({1, 2, 3, 4});
  EXPECT_EQ(rng.next(), 11520u);
  EXPECT_EQ(rng.next(), 0u);
  EXPECT_EQ(rng.next(), 1509978240u);
  EXPECT_EQ(rng.next(), 1215971899390074240u);
}

TEST(Rng, AllZeroStateIsRejected) {
  EXPECT_THROW(Rng::from_state({0, 0, 0, 0}), vtrack::InvalidArgument);
}

TEST(Rng, SameSeedSameSequenceDifferentSeedDifferent) {
  Rng a(42), b(42), c(43);
  bool any_difference = false;
  for (int i = 0; i < 1000; ++i) {
    const auto x = a.next();
    EXPECT_EQ(x, b.next());
    any_difference |= (x != c.next());
  }
  EXPECT_TRUE(any_difference);
}

TEST(Rng, StreamIsTheSeedJumpedAndSharesNoOutputWithOtherStreams) {
  Rng jumped(9);
  jumped.jump();
  jumped.jump();
  Rng stream2(9, 2);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(jumped.next(), stream2.next());

  std::set<std::uint64_t> seen;
  for (std::uint64_t s = 0; s < 4; ++s) {
    Rng rng(9, s);
    for (int i = 0; i < 10000; ++i) seen.insert(rng.next());
  }
  EXPECT_EQ(seen.size(), 40000u);  // 64-bit outputs of overlapping streams would repeat
}

TEST(Rng, UniformMomentsAndRange) {
  Rng rng(1);
  const int n = 1'000'000;
  std::vector<double> u(n);
  rng.fill_uniform(u.data(), n);
  double mean = 0, var = 0;
  for (double x : u) {
    ASSERT_GE(x, 0.0);
    ASSERT_LT(x, 1.0);
    mean += x;
  }
  mean /= n;
  for (double x : u) var += (x - mean) * (x - mean);
  var /= n;
  // Standard error of the mean is sqrt(1/12 / n) = 2.9e-4; allow 5 of them.
  EXPECT_NEAR(mean, 0.5, 1.5e-3);
  EXPECT_NEAR(var, 1.0 / 12.0, 1e-3);
}

// Chi-square of 10 equal-probability bins; 99.99th percentile of chi2(9) is 33.7.
double chi_square_deciles(const std::vector<double>& values, double (*cdf)(double)) {
  std::vector<double> counts(10, 0.0);
  for (double v : values) {
    const int bin = std::min(9, static_cast<int>(cdf(v) * 10.0));
    counts[bin] += 1.0;
  }
  const double expected = static_cast<double>(values.size()) / 10.0;
  double chi2 = 0;
  for (double c : counts) chi2 += (c - expected) * (c - expected) / expected;
  return chi2;
}

using vtrack::test_reference::normal_cdf;

TEST(Rng, NormalBatchedAndSingleFollowTheStandardNormal) {
  Rng rng(2);
  const int n = 200'001;  // odd: the batched Box-Muller must handle a half pair
  std::vector<double> batched(n);
  rng.fill_normal(batched.data(), n);
  std::vector<double> single(n);
  for (double& x : single) x = rng.normal();
  for (const auto* sample : {&batched, &single}) {
    double mean = 0, second = 0, fourth = 0;
    for (double x : *sample) {
      mean += x;
      second += x * x;
      fourth += x * x * x * x;
    }
    mean /= n;
    second /= n;
    fourth /= n;
    EXPECT_NEAR(mean, 0.0, 0.012);   // 5 standard errors
    EXPECT_NEAR(second, 1.0, 0.016);
    EXPECT_NEAR(fourth, 3.0, 0.11);
    EXPECT_LT(chi_square_deciles(*sample, normal_cdf), 33.7);
  }
  std::vector<float> as_float(1001);
  Rng again(2);
  again.fill_normal(as_float.data(), as_float.size());
  for (std::size_t i = 0; i < as_float.size(); ++i) {
    EXPECT_FLOAT_EQ(as_float[i], static_cast<float>(batched[i]));
  }
}

TEST(Rng, BelowIsUniformOverItsRange) {
  Rng rng(3);
  std::vector<double> counts(7, 0.0);
  const int n = 700'000;
  for (int i = 0; i < n; ++i) {
    const auto k = rng.below(7);
    ASSERT_LT(k, 7u);
    counts[k] += 1;
  }
  double chi2 = 0;
  for (double c : counts) chi2 += (c - n / 7.0) * (c - n / 7.0) / (n / 7.0);
  EXPECT_LT(chi2, 27.9);  // 99.99th percentile of chi2(6)
}
