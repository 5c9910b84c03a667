#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"

using namespace vtrack::core;

TEST(Gaussian, OneDimensionalLogDensityIsTheTextbookFormula) {
  Gaussian g(Eigen::VectorXd::Constant(1, 2.0), Eigen::MatrixXd::Constant(1, 1, 9.0));
  for (double x : {-4.0, 0.0, 2.0, 7.5}) {
    const double expected = -0.5 * std::log(2 * M_PI * 9.0) - (x - 2.0) * (x - 2.0) / 18.0;
    EXPECT_NEAR(g.log_density(Eigen::VectorXd::Constant(1, x)), expected, 1e-12);
  }
}

TEST(Gaussian, LogDensityMatchesDeterminantAndInverse) {
  Eigen::Vector3d mean(1.0, -2.0, 0.5);
  Eigen::Matrix3d cov;
  cov << 4.0, 1.2, -0.3, 1.2, 2.0, 0.4, -0.3, 0.4, 1.0;
  Gaussian g(mean, cov);
  Eigen::MatrixXd points(3, 3);
  points << 0.0, 1.0, 3.0, 0.0, -2.0, -5.0, 0.0, 0.5, 2.0;
  const Eigen::VectorXd batch = g.log_density_columns(points);
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d d = points.col(j) - mean;
    const double expected =
        -1.5 * std::log(2 * M_PI) - 0.5 * std::log(cov.determinant()) - 0.5 * d.dot(cov.inverse() * d);
    EXPECT_NEAR(g.log_density(points.col(j)), expected, 1e-12);
    EXPECT_NEAR(batch[j], expected, 1e-12);
  }
  EXPECT_TRUE(g.covariance().isApprox(cov, 1e-12));
}

TEST(Gaussian, SamplesHaveTheRequestedMeanAndCovariance) {
  Eigen::Vector2d mean(3.0, -1.0);
  Eigen::Matrix2d cov;
  cov << 2.0, -0.8, -0.8, 1.0;
  Gaussian g(mean, cov);
  Rng rng(21);
  const int n = 400'000;
  const Eigen::MatrixXd x = g.sample(rng, n);
  const Eigen::Vector2d m = x.rowwise().mean();
  const Eigen::MatrixXd centred = x.colwise() - m;
  const Eigen::Matrix2d c = centred * centred.transpose() / (n - 1);
  // Standard errors: sqrt(2/n) ~ 2.2e-3 for the mean, ~ sqrt(2 * 4 / n) ~ 4.5e-3 for C_11.
  EXPECT_NEAR(m[0], 3.0, 0.012);
  EXPECT_NEAR(m[1], -1.0, 0.008);
  EXPECT_NEAR(c(0, 0), 2.0, 0.025);
  EXPECT_NEAR(c(0, 1), -0.8, 0.015);
  EXPECT_NEAR(c(1, 1), 1.0, 0.012);
  // Single draws come from the same distribution as the batch.
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int i = 0; i < 20000; ++i) sum += g.sample(rng);
  EXPECT_NEAR(sum[0] / 20000, 3.0, 0.05);
}

TEST(Gaussian, RejectsInvalidCovariances) {
  const Eigen::Vector2d mean(0, 0);
  Eigen::Matrix2d indefinite;
  indefinite << 1.0, 2.0, 2.0, 1.0;  // eigenvalues 3 and -1
  EXPECT_THROW(Gaussian(mean, indefinite), vtrack::InvalidArgument);
  Eigen::Matrix2d singular;
  singular << 1.0, 1.0, 1.0, 1.0;
  EXPECT_THROW(Gaussian(mean, singular), vtrack::InvalidArgument);
  Eigen::Matrix2d asymmetric;
  asymmetric << 2.0, 0.5, -0.5, 2.0;
  EXPECT_THROW(Gaussian(mean, asymmetric), vtrack::InvalidArgument);
  EXPECT_THROW(Gaussian(mean, Eigen::Matrix3d::Identity()), vtrack::InvalidArgument);
  Eigen::Matrix2d with_nan = Eigen::Matrix2d::Identity();
  with_nan(0, 0) = std::nan("");
  EXPECT_THROW(Gaussian(mean, with_nan), vtrack::InvalidArgument);
  try {
    Gaussian(mean, indefinite);
  } catch (const vtrack::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("positive definite"), std::string::npos);
  }
}
