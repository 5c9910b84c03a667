#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/models/linear_gaussian.hpp"

using namespace vtrack::models;

TEST(ConstantVelocity, MatchesTheStandardGlmbScenarioModel) {
  // ../shared/data/glmb-standard/model.json: T = 1, sigma_v = 5.
  const auto m = LinearGaussianMotion::constant_velocity(2, 1.0, 5.0);
  Eigen::Matrix4d F;
  F << 1, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1;
  Eigen::Matrix4d Q;
  Q << 6.25, 12.5, 0, 0, 12.5, 25, 0, 0, 0, 0, 6.25, 12.5, 0, 0, 12.5, 25;
  EXPECT_TRUE(m.F.isApprox(F));
  EXPECT_TRUE(m.Q.isApprox(Q));
  const auto m3 = LinearGaussianMotion::constant_velocity(3, 0.5, 2.0);  // eq. (7), 3-D
  EXPECT_EQ(m3.F.rows(), 6);
  EXPECT_DOUBLE_EQ(m3.F(4, 5), 0.5);
  EXPECT_DOUBLE_EQ(m3.Q(4, 4), 4.0 * 0.125 * 0.125);
  EXPECT_THROW(LinearGaussianMotion::constant_velocity(0, 1.0, 1.0), vtrack::InvalidArgument);
  EXPECT_THROW(LinearGaussianMotion::constant_velocity(2, 1.0, -1.0), vtrack::InvalidArgument);
}

TEST(Kalman, ScalarUpdateIsTheTextbookClosedForm) {
  GaussianDensity prior{Eigen::VectorXd::Constant(1, 2.0), Eigen::MatrixXd::Constant(1, 1, 4.0)};
  LinearGaussianObservation obs{Eigen::MatrixXd::Constant(1, 1, 1.0),
                                Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd()};
  KalmanInnovation innovation(prior, obs);
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(1, 7.0);
  const GaussianDensity post = innovation.posterior(z);
  EXPECT_NEAR(post.mean[0], 2.0 + 4.0 / 5.0 * 5.0, 1e-12);  // m + P/(P+R) (z - m)
  EXPECT_NEAR(post.cov(0, 0), 4.0 * 1.0 / 5.0, 1e-12);       // P R / (P + R)
  EXPECT_NEAR(innovation.log_likelihood(z), -0.5 * std::log(2 * M_PI * 5.0) - 25.0 / 10.0, 1e-12);
}

TEST(Kalman, UpdateAgreesWithTheInformationForm) {
  const auto motion = LinearGaussianMotion::constant_velocity(2, 1.0, 5.0);
  const auto obs = LinearGaussianObservation::position_of_constant_velocity(
      2, Eigen::Matrix2d::Identity() * 100.0);
  GaussianDensity prior{Eigen::Vector4d(10, 1, -5, 2), Eigen::Matrix4d::Identity() * 50.0};
  prior.cov(0, 1) = prior.cov(1, 0) = 3.0;
  const GaussianDensity predicted = kalman_predict(prior, motion);
  EXPECT_TRUE(predicted.mean.isApprox(motion.F * prior.mean));
  const Eigen::Vector2d z(14.0, -1.0);
  const GaussianDensity post = KalmanInnovation(predicted, obs).posterior(z);
  // Information form: P+^{-1} = P^{-1} + H^T R^{-1} H; P+^{-1} m+ = P^{-1} m + H^T R^{-1} z.
  const Eigen::MatrixXd info = predicted.cov.inverse() + obs.H.transpose() * obs.R.inverse() * obs.H;
  const Eigen::VectorXd info_mean =
      predicted.cov.inverse() * predicted.mean + obs.H.transpose() * obs.R.inverse() * z;
  EXPECT_TRUE(post.cov.isApprox(info.inverse(), 1e-10));
  EXPECT_TRUE(post.mean.isApprox(info.inverse() * info_mean, 1e-10));
  // The likelihood is the Gaussian density of z under N(H m, H P H^T + R).
  const vtrack::core::Gaussian predictive(obs.H * predicted.mean,
                                          obs.H * predicted.cov * obs.H.transpose() + obs.R);
  KalmanInnovation innovation(predicted, obs);
  EXPECT_NEAR(innovation.log_likelihood(z), predictive.log_density(z), 1e-12);
}

TEST(Kalman, StateDependentNoiseIsEvaluatedAtThePredictedMean) {
  // R(x) = R + diag((A x)^2): the update equals the constant-noise update with R(predicted mean).
  GaussianDensity prior{Eigen::Vector2d(10.0, -4.0), Eigen::Matrix2d::Identity() * 9.0};
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2);
  Eigen::MatrixXd R = Eigen::MatrixXd::Identity(2, 2) * 2.0;
  Eigen::MatrixXd A(2, 2);
  A << 0.1, 0.0, 0.05, 0.2;
  const LinearGaussianObservation scaled{H, R, A};
  Eigen::MatrixXd R_at = R;
  R_at(0, 0) += 1.0 * 1.0;  // (0.1 * 10)^2
  R_at(1, 1) += 0.3 * 0.3;  // (0.05 * 10 + 0.2 * -4)^2
  EXPECT_TRUE(scaled.noise_at(prior.mean).isApprox(R_at, 1e-12));
  const LinearGaussianObservation fixed{H, R_at, Eigen::MatrixXd()};
  const Eigen::Vector2d z(12.0, -3.0);
  const GaussianDensity a = KalmanInnovation(prior, scaled).posterior(z);
  const GaussianDensity b = KalmanInnovation(prior, fixed).posterior(z);
  EXPECT_TRUE(a.mean.isApprox(b.mean, 1e-12));
  EXPECT_TRUE(a.cov.isApprox(b.cov, 1e-12));
  EXPECT_NEAR(KalmanInnovation(prior, scaled).mahalanobis_squared(z),
              KalmanInnovation(prior, fixed).mahalanobis_squared(z), 1e-12);
}
