// The SMC engine's models (models/linear_transition.hpp, motion.hpp, range_bearing.hpp,
// linear_gaussian_likelihood.hpp) against dense matrix algebra and the papers' equations.
#include <gtest/gtest.h>

#include <cmath>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/models/linear_gaussian_likelihood.hpp"
#include "vtrack/models/linear_transition.hpp"
#include "vtrack/models/motion.hpp"
#include "vtrack/models/range_bearing.hpp"

using namespace vtrack;
using models::LinearTransition;
using models::StatesView;

namespace {

Eigen::MatrixXd normals(core::Rng& rng, Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd m(rows, cols);
  rng.fill_normal(m.data(), static_cast<std::size_t>(m.size()));
  return m;
}

// next = prev F^T + eps S^T, the dense product the sparse propagation must equal.
void expect_propagates_like_dense(const LinearTransition& t, core::Rng& rng) {
  const Eigen::MatrixXd prev = normals(rng, 37, t.dim());
  const Eigen::MatrixXd eps = normals(rng, 37, t.noise_dim());
  Eigen::MatrixXd next(37, t.dim());
  t.propagate(StatesView<double>(prev), StatesView<double>(eps), next);
  const Eigen::MatrixXd expected = prev * t.F().transpose() + eps * t.noise_factor().transpose();
  EXPECT_LT((next - expected).cwiseAbs().maxCoeff(), 1e-12);
  // Float states give the same to float precision.
  Eigen::MatrixXf nextf(37, t.dim());
  const Eigen::MatrixXf prevf = prev.cast<float>(), epsf = eps.cast<float>();
  t.propagate(StatesView<float>(prevf), StatesView<float>(epsf), nextf);
  EXPECT_LT((nextf.cast<double>() - expected).cwiseAbs().maxCoeff(), 1e-4);
}

}  // namespace

TEST(SmcModels, LinearTransitionPropagatesLikeTheDenseProduct) {
  core::Rng rng(1);
  // Sparse rows (few terms), and a dense 8 x 8 one (more terms per row than the unrolled cases).
  Eigen::MatrixXd F = normals(rng, 5, 5), S = normals(rng, 5, 3);
  F(0, 1) = F(2, 2) = F(4, 0) = 0.0;
  S(1, 0) = S(1, 1) = S(1, 2) = 0.0;
  F.row(3).setZero();
  S.row(3).setZero();  // a component that becomes 0
  expect_propagates_like_dense(LinearTransition(F, S), rng);
  expect_propagates_like_dense(LinearTransition(normals(rng, 8, 8), normals(rng, 8, 8)), rng);
  expect_propagates_like_dense(LinearTransition(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd(2, 0)), rng);
}

TEST(SmcModels, NoiseFactorFromACovarianceReproducesIt) {
  core::Rng rng(2);
  const Eigen::MatrixXd A = normals(rng, 4, 4);
  const Eigen::MatrixXd pd = A * A.transpose() + Eigen::MatrixXd::Identity(4, 4);
  const Eigen::MatrixXd B = normals(rng, 4, 2);
  const Eigen::MatrixXd psd = B * B.transpose();  // rank 2
  const auto t1 = LinearTransition::from_covariance(Eigen::MatrixXd::Identity(4, 4), pd);
  EXPECT_EQ(t1.noise_dim(), 4);
  EXPECT_LT((t1.Q() - pd).cwiseAbs().maxCoeff(), 1e-12);
  const auto t2 = LinearTransition::from_covariance(Eigen::MatrixXd::Identity(4, 4), psd);
  EXPECT_EQ(t2.noise_dim(), 2);
  EXPECT_LT((t2.Q() - psd).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::MatrixXd indefinite = pd;
  indefinite(0, 0) = -1.0;
  EXPECT_THROW(LinearTransition::from_covariance(Eigen::MatrixXd::Identity(4, 4), indefinite),
               InvalidArgument);
  Eigen::MatrixXd asymmetric = pd;
  asymmetric(0, 1) += 1.0;
  EXPECT_THROW(LinearTransition::from_covariance(Eigen::MatrixXd::Identity(4, 4), asymmetric),
               InvalidArgument);
  EXPECT_THROW(LinearTransition::from_covariance(Eigen::MatrixXd::Identity(3, 3), pd),
               InvalidArgument);
}

TEST(SmcModels, ConstantVelocityHasTheWhiteNoiseAccelerationCovariances) {
  const double T = 0.5, q = 2.0;
  const models::ConstantVelocity continuous({3, T, q, models::AccelerationNoise::Continuous});
  const models::ConstantVelocity discrete({3, T, q, models::AccelerationNoise::Discrete});
  Eigen::Matrix2d qc, qd, f;
  qc << T * T * T / 3, T * T / 2, T * T / 2, T;
  qd << T * T * T * T / 4, T * T * T / 2, T * T * T / 2, T * T;
  f << 1, T, 0, 1;
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT((continuous.Q().block<2, 2>(2 * a, 2 * a) - q * qc).norm(), 1e-12);
    EXPECT_LT((discrete.Q().block<2, 2>(2 * a, 2 * a) - q * qd).norm(), 1e-12);
    EXPECT_EQ((continuous.F().block<2, 2>(2 * a, 2 * a)), f);
  }
  // Axes are independent.
  EXPECT_EQ((continuous.Q().block<2, 2>(0, 2)), Eigen::Matrix2d::Zero());
  EXPECT_EQ(continuous.noise_dim(), 6);
  EXPECT_EQ(discrete.noise_dim(), 3);
  // Matches the Kalman-side discrete model (rgbd-glmb eq. 7) with sigma_v^2 = q.
  const auto glmb = models::LinearGaussianMotion::constant_velocity(3, T, std::sqrt(q));
  EXPECT_LT((discrete.Q() - glmb.Q).norm(), 1e-12);
  EXPECT_EQ(discrete.F(), glmb.F);
  EXPECT_THROW(models::ConstantVelocity({0, 1.0, 1.0, models::AccelerationNoise::Discrete}),
               InvalidArgument);
  EXPECT_THROW(models::ConstantVelocity({2, 1.0, -1.0, models::AccelerationNoise::Discrete}),
               InvalidArgument);
  EXPECT_THROW(models::parse_acceleration_noise("white"), InvalidArgument);
}

TEST(SmcModels, SecondOrderAutoRegressiveIsEquation13) {
  // X_k = 2 X_{k-1} - X_{k-2} + U_{k-1} on the state [X_{k-1}, X_{k-2}] -> [X_k, X_{k-1}].
  models::SecondOrderAutoRegressiveParams p;
  p.sigma = {1.0, 2.0, 3.0, 4.0};
  const models::SecondOrderAutoRegressive ar(p);
  ASSERT_EQ(ar.dim(), 8);
  ASSERT_EQ(ar.noise_dim(), 4);
  core::Rng rng(3);
  const Eigen::MatrixXd prev = normals(rng, 5, 8);
  const Eigen::MatrixXd eps = normals(rng, 5, 4);
  Eigen::MatrixXd next(5, 8);
  ar.propagate(StatesView<double>(prev), StatesView<double>(eps), next);
  for (int i = 0; i < 5; ++i) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(next(i, c), 2 * prev(i, c) - prev(i, 4 + c) + p.sigma[c] * eps(i, c), 1e-12);
      EXPECT_EQ(next(i, 4 + c), prev(i, c));
    }
  }
  p.dims = 3;
  EXPECT_THROW(models::SecondOrderAutoRegressive{p}, InvalidArgument);  // 4 sigmas, 3 dims
}

TEST(SmcModels, RandomWalkBroadcastsSigma) {
  models::RandomWalkParams p;
  p.sigma = {2.0};
  p.dims = 3;
  const models::RandomWalk rw(p);
  EXPECT_EQ(rw.Q(), 4.0 * Eigen::MatrixXd::Identity(3, 3));
  EXPECT_EQ(rw.F(), Eigen::MatrixXd::Identity(3, 3));
  p.sigma = {1.0, 0.0};
  p.dims = 0;
  EXPECT_THROW(models::RandomWalk{p}, InvalidArgument);
}

TEST(SmcModels, RangeBearingLikelihoodIsTheProductOfTwoNormals) {
  const models::RangeBearingObservation rb({2.0, 0.05, 10.0, -5.0, 0, 2});
  core::Rng rng(4);
  Eigen::MatrixXd x = 50.0 * normals(rng, 200, 4);
  // Targets straight behind the sensor, where the bearing crosses +-pi.
  x(0, 0) = -40.0;
  x(0, 2) = -5.0 + 1e-3;
  x(1, 0) = -40.0;
  x(1, 2) = -5.0 - 1e-3;
  for (const Eigen::Vector2d& z : {Eigen::Vector2d(30.0, 0.3), Eigen::Vector2d(50.0, M_PI - 1e-4),
                                  Eigen::Vector2d(50.0, -M_PI + 1e-4)}) {
    Eigen::VectorXd out(200);
    rb.log_likelihood(StatesView<double>(x), z, out.data());
    for (int i = 0; i < 200; ++i) {
      const double dx = x(i, 0) - 10.0, dy = x(i, 2) + 5.0;
      double db = std::atan2(dy, dx) - z[1];
      db = std::remainder(db, 2 * M_PI);  // wrapped to [-pi, pi]
      const double dr = std::hypot(dx, dy) - z[0];
      const double expected = -std::log(2 * M_PI * 2.0 * 0.05) - 0.5 * (dr * dr / 4.0 + db * db / 0.0025);
      EXPECT_NEAR(out[i], expected, 1e-9 * std::fabs(expected)) << i;
    }
    // Float states: residuals in float, against the same formula in double on the same (rounded)
    // states. The error is float rounding of residuals of size |x| / sigma: ~1e-5 relative.
    const Eigen::MatrixXf xf = x.cast<float>();
    rb.log_likelihood(StatesView<float>(xf), z, out.data());
    for (int i = 0; i < 200; ++i) {
      const double dx = double{xf(i, 0)} - 10.0, dy = double{xf(i, 2)} + 5.0;
      const double db = std::remainder(std::atan2(dy, dx) - z[1], 2 * M_PI);
      const double dr = std::hypot(dx, dy) - z[0];
      const double expected = -std::log(2 * M_PI * 2.0 * 0.05) - 0.5 * (dr * dr / 4.0 + db * db / 0.0025);
      EXPECT_NEAR(out[i], expected, 2e-5 * (1.0 + std::fabs(expected))) << "float " << i;
    }
  }
  EXPECT_THROW(rb.check(Eigen::Vector2d(1.0, std::nan(""))), InvalidArgument);
  EXPECT_THROW(rb.check(Eigen::Vector3d(1.0, 1.0, 1.0)), InvalidArgument);
  EXPECT_THROW(models::RangeBearingObservation({0.0, 0.1, 0, 0, 0, 2}), InvalidArgument);
}

TEST(SmcModels, LinearGaussianLikelihoodMatchesTheGaussianDensity) {
  core::Rng rng(5);
  const Eigen::MatrixXd H = normals(rng, 2, 4);
  Eigen::Matrix2d R;
  R << 2.0, 0.3, 0.3, 1.0;
  const models::LinearGaussianLikelihood g({H, R});
  const Eigen::MatrixXd x = normals(rng, 50, 4);
  const Eigen::Vector2d z(0.5, -1.0);
  Eigen::VectorXd out(50);
  g.log_likelihood(StatesView<double>(x), z, out.data());
  for (int i = 0; i < 50; ++i) {
    const core::Gaussian density(H * x.row(i).transpose(), R);
    EXPECT_NEAR(out[i], density.log_density(z), 1e-12);
  }
  Eigen::Matrix2d bad = R;
  bad(1, 1) = -1.0;
  EXPECT_THROW(models::LinearGaussianLikelihood({H, bad}), InvalidArgument);
  EXPECT_THROW(g.check(Eigen::Vector3d::Zero()), InvalidArgument);
}
