// core/vmath.hpp against libm, and core::LaneRng's draws against their distributions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "vtrack/core/lane_rng.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/vmath.hpp"
#include "vtrack/core/weights.hpp"
#include "distributions.hpp"

using namespace vtrack::core;

using vtrack::test_reference::ks_statistic;
using vtrack::test_reference::normal_cdf;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

}  // namespace

TEST(SmcVmath, ExpIsWithinTwoUlpOfLibm) {
  Rng rng(1);
  for (int i = 0; i < 200000; ++i) {
    const double x = rng.uniform(-708.0, 709.0);
    const double expected = std::exp(x);
    EXPECT_LE(std::fabs(vmath::exp(x) - expected), 2 * kEps * expected) << x;
  }
  EXPECT_EQ(vmath::exp(0.0), 1.0);
  EXPECT_EQ(vmath::exp(-kInf), 0.0);
  EXPECT_EQ(vmath::exp(-800.0), 0.0);  // below 2^-1022: flushed to zero
  EXPECT_EQ(vmath::exp(710.0), kInf);
  EXPECT_TRUE(std::isnan(vmath::exp(std::nan(""))));
}

TEST(SmcVmath, LogIsWithinTwoUlpOfLibm) {
  Rng rng(2);
  for (int i = 0; i < 200000; ++i) {
    // Uniform exponents from 2^-1000 to 2^1000, and values near 1 where log is small.
    const double x = i % 2 ? std::exp2(rng.uniform(-1000.0, 1000.0)) : rng.uniform(0.5, 2.0);
    const double expected = std::log(x);
    EXPECT_LE(std::fabs(vmath::log(x) - expected), 2 * kEps * std::fabs(expected) + 1e-300) << x;
  }
  EXPECT_EQ(vmath::log(1.0), 0.0);
  EXPECT_NEAR(vmath::log(0x1.0p-52), -52 * std::log(2.0), 1e-13);
}

TEST(SmcVmath, Atan2MatchesLibmInEveryQuadrant) {
  Rng rng(3);
  for (int i = 0; i < 200000; ++i) {
    const double y = rng.uniform(-10.0, 10.0) * std::exp2(rng.uniform(-20.0, 20.0));
    const double x = rng.uniform(-10.0, 10.0) * std::exp2(rng.uniform(-20.0, 20.0));
    const double expected = std::atan2(y, x);
    EXPECT_LE(std::fabs(vmath::atan2(y, x) - expected), 2 * kEps * std::fabs(expected)) << y << " " << x;
  }
  EXPECT_EQ(vmath::atan2(0.0, 0.0), 0.0);
  EXPECT_EQ(vmath::atan2(0.0, 1.0), 0.0);
  EXPECT_NEAR(vmath::atan2(1.0, 0.0), M_PI / 2, 1e-16);
  EXPECT_NEAR(vmath::atan2(0.0, -1.0), M_PI, 1e-15);
  EXPECT_NEAR(vmath::atan2(-1.0, -1.0), -3 * M_PI / 4, 1e-15);
}

TEST(SmcVmath, SinglePrecisionAtan2IsAccurateInEveryQuadrant) {
  Rng rng(5);
  for (int i = 0; i < 200000; ++i) {
    const auto y = static_cast<float>(rng.uniform(-10.0, 10.0) * std::exp2(rng.uniform(-20.0, 20.0)));
    const auto x = static_cast<float>(rng.uniform(-10.0, 10.0) * std::exp2(rng.uniform(-20.0, 20.0)));
    const double expected = std::atan2(static_cast<double>(y), static_cast<double>(x));
    EXPECT_NEAR(vmath::atan2(y, x), expected, 3e-7) << y << " " << x;
  }
  EXPECT_EQ(vmath::atan2(0.0f, 0.0f), 0.0f);
  EXPECT_EQ(vmath::atan2(0.0f, 1.0f), 0.0f);
  EXPECT_NEAR(vmath::atan2(-1.0f, -1.0f), -3 * M_PI / 4, 3e-7);
  EXPECT_NEAR(vmath::atan2(0.0f, -1.0f), M_PI, 3e-7);
}

TEST(SmcVmath, ReducedSinCosMatchLibm) {
  for (int i = -1000; i <= 1000; ++i) {
    const double x = M_PI / 4 * i / 1000.0;
    double s, c;
    vmath::sincos_reduced(x, s, c);
    EXPECT_NEAR(s, std::sin(x), 2 * kEps);
    EXPECT_NEAR(c, std::cos(x), 2 * kEps);
    float sf, cf;
    vmath::sincos_reduced(static_cast<float>(x), sf, cf);
    EXPECT_NEAR(sf, std::sin(static_cast<float>(x)), 3e-7);
    EXPECT_NEAR(cf, std::cos(static_cast<float>(x)), 3e-7);
  }
}

TEST(SmcVmath, SinglePrecisionLogIsAccurate) {
  Rng rng(4);
  for (int i = 0; i < 100000; ++i) {
    const float x = static_cast<float>(std::exp2(rng.uniform(-31.0, 1.0)));
    const double expected = std::log(static_cast<double>(x));
    EXPECT_NEAR(vmath::log(x), expected, 4e-7 * std::max(1.0, std::fabs(expected))) << x;
  }
}

TEST(SmcVmath, SinglePrecisionExpIsAccurate) {
  Rng rng(6);
  for (int i = 0; i < 200000; ++i) {
    const auto x = static_cast<float>(rng.uniform(-87.3, 88.3));
    const double expected = std::exp(static_cast<double>(x));
    EXPECT_LE(std::fabs(vmath::exp(x) - expected), 1e-7 * expected) << x;
  }
  EXPECT_EQ(vmath::exp(0.0f), 1.0f);
  EXPECT_EQ(vmath::exp(-std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_EQ(vmath::exp(-90.0f), 0.0f);  // below 2^-126: flushed to zero
  EXPECT_EQ(vmath::exp(89.0f), std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(vmath::exp(std::nanf(""))));
}

TEST(SmcLaneRng, IsDefinedByItsSourceAndItsLanesDiffer) {
  Rng a(9, 3), b(9, 3);
  LaneRng la(a), lb(b);
  std::vector<double> x(1001), y(1001);
  la.fill_normal(x.data(), x.size());
  lb.fill_normal(y.data(), y.size());
  EXPECT_EQ(x, y);
  // Made one after another from the same source, generators draw different streams.
  LaneRng lc(a);
  lc.fill_normal(y.data(), y.size());
  EXPECT_NE(x, y);
  // The eight lanes are not copies of one another.
  EXPECT_NE(x[0], x[1]);
}

TEST(SmcLaneRng, NormalsPassKolmogorovSmirnovAndMoments) {
  Rng source(21);
  LaneRng rng(source);
  const std::size_t n = 200000;
  std::vector<double> d(n);
  rng.fill_normal(d.data(), n);
  std::vector<float> f(n + 7);  // a size that is not a multiple of a chunk
  rng.fill_normal(f.data(), f.size());
  // KS critical value at alpha = 0.001: 1.95 / sqrt(n).
  const double critical = 1.95 / std::sqrt(static_cast<double>(n));
  EXPECT_LT(ks_statistic(d, normal_cdf), critical);
  EXPECT_LT(ks_statistic(std::vector<double>(f.begin(), f.begin() + n), normal_cdf), critical);
  for (const auto* sample : {&d}) {
    double m = 0, v = 0, k = 0;
    for (double x : *sample) {
      m += x;
      v += x * x;
      k += x * x * x * x;
    }
    m /= n;
    v /= n;
    k /= n;
    // Standard errors: 1/sqrt(n) = 0.0022 for the mean, sqrt(2/n) = 0.0032 for the variance,
    // sqrt(96/n) = 0.022 for the fourth moment; 5 of them.
    EXPECT_NEAR(m, 0.0, 0.011);
    EXPECT_NEAR(v, 1.0, 0.016);
    EXPECT_NEAR(k, 3.0, 0.11);
  }
  // Pairs share a radius but not an angle: their product averages zero (E[z0 z1] = 0).
  double cross = 0;
  for (std::size_t j = 0; j + 8 < n; j += 16) {
    for (int l = 0; l < 8; ++l) cross += d[j + l] * d[j + l + 8];
  }
  EXPECT_NEAR(cross / (n / 2), 0.0, 0.016);
}

TEST(SmcLaneRng, UniformsLieInTheUnitIntervalAndAreUniform) {
  Rng source(22);
  LaneRng rng(source);
  std::vector<double> u(100003);
  rng.fill_uniform(u.data(), u.size());
  EXPECT_GE(*std::min_element(u.begin(), u.end()), 0.0);
  EXPECT_LT(*std::max_element(u.begin(), u.end()), 1.0);
  EXPECT_LT(ks_statistic(u, [](double x) { return x; }), 1.95 / std::sqrt(100003.0));
}
