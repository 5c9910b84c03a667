#include <gtest/gtest.h>

#include <cmath>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/weights.hpp"

using namespace vtrack::core;

TEST(LogSumExp, AgreesWithTheNaiveSumWhereThatIsSafe) {
  Eigen::VectorXd x(4);
  x << -1.0, 0.5, 2.0, -3.0;
  EXPECT_NEAR(log_sum_exp(x), std::log(std::exp(-1.0) + std::exp(0.5) + std::exp(2.0) + std::exp(-3.0)),
              1e-14);
}

TEST(LogSumExp, StableForHugeAndTinyValues) {
  Eigen::VectorXd big(2);
  big << 1000.0, 1000.0;
  EXPECT_NEAR(log_sum_exp(big), 1000.0 + std::log(2.0), 1e-12);
  Eigen::VectorXd small(2);
  small << -1000.0, -1000.0;
  EXPECT_NEAR(log_sum_exp(small), -1000.0 + std::log(2.0), 1e-12);
}

TEST(LogSumExp, EmptyAndAllMinusInfinityGiveMinusInfinity) {
  EXPECT_EQ(log_sum_exp(Eigen::VectorXd()), -kInf);
  EXPECT_EQ(log_sum_exp(Eigen::VectorXd::Constant(3, -kInf)), -kInf);
  Eigen::VectorXd with_inf(2);
  with_inf << 0.0, kInf;
  EXPECT_EQ(log_sum_exp(with_inf), kInf);
}

TEST(LogSumExp, NanIsAnError) {
  Eigen::VectorXd x(2);
  x << 0.0, std::nan("");
  EXPECT_THROW(log_sum_exp(x), vtrack::InvalidArgument);
}

TEST(NormalizeLogWeights, SumsToOneAndReturnsTheLogTotal) {
  Eigen::VectorXd x(3);
  x << std::log(1.0), std::log(3.0), -kInf;
  Eigen::VectorXd w;
  const double total = normalize_log_weights(x, w);
  EXPECT_NEAR(total, std::log(4.0), 1e-14);
  EXPECT_NEAR(w[0], 0.25, 1e-15);
  EXPECT_NEAR(w[1], 0.75, 1e-15);
  EXPECT_EQ(w[2], 0.0);
}

TEST(NormalizeLogWeights, AllVanishingWeightsBecomeUniformWithoutNaN) {
  Eigen::VectorXd w;
  EXPECT_EQ(normalize_log_weights(Eigen::VectorXd::Constant(4, -kInf), w), -kInf);
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(w[i], 0.25);
  // Far below double's range, yet still well defined relative to each other.
  Eigen::VectorXd tiny(2);
  tiny << -1e6, -1e6 + std::log(3.0);
  normalize_log_weights(tiny, w);
  EXPECT_NEAR(w[1], 0.75, 1e-9);
}

TEST(NormalizeLogWeights, InfiniteWeightsShareTheMass) {
  Eigen::VectorXd x(3);
  x << kInf, 0.0, kInf;
  Eigen::VectorXd w;
  normalize_log_weights(x, w);
  EXPECT_DOUBLE_EQ(w[0], 0.5);
  EXPECT_DOUBLE_EQ(w[1], 0.0);
  EXPECT_DOUBLE_EQ(w[2], 0.5);
}

TEST(EffectiveSampleSize, ClosedForms) {
  EXPECT_DOUBLE_EQ(effective_sample_size(Eigen::VectorXd::Constant(10, 0.1)), 10.0);
  Eigen::VectorXd one_hot = Eigen::VectorXd::Zero(10);
  one_hot[3] = 1.0;
  EXPECT_DOUBLE_EQ(effective_sample_size(one_hot), 1.0);
  Eigen::VectorXd w(3);
  w << 0.1, 0.2, 0.7;
  EXPECT_NEAR(effective_sample_size(w), 1.0 / (0.01 + 0.04 + 0.49), 1e-12);  // eq. 7
  EXPECT_NEAR(effective_sample_size(w * 1e-300), 1.0 / 0.54, 1e-9);         // scale-invariant
  EXPECT_EQ(effective_sample_size(Eigen::VectorXd::Zero(5)), 0.0);
}

TEST(EffectiveSampleSize, LogDomainVersion) {
  Eigen::VectorXd lw(3);
  lw << std::log(0.1) + 500, std::log(0.2) + 500, std::log(0.7) + 500;
  EXPECT_NEAR(effective_sample_size_log(lw), 1.0 / 0.54, 1e-9);
  EXPECT_EQ(effective_sample_size_log(Eigen::VectorXd::Constant(3, -kInf)), 0.0);
}

TEST(EffectiveSampleSize, NegativeOrNonFiniteWeightsAreErrors) {
  Eigen::VectorXd w(2);
  w << 0.5, -0.1;
  EXPECT_THROW(effective_sample_size(w), vtrack::InvalidArgument);
  w << 0.5, kInf;
  EXPECT_THROW(effective_sample_size(w), vtrack::InvalidArgument);
}
