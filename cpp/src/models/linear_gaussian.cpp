#include "vtrack/models/linear_gaussian.hpp"

#include <cmath>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"

namespace vtrack::models {

LinearGaussianMotion LinearGaussianMotion::constant_velocity(int axes, double period,
                                                             double sigma_v) {
  if (axes < 1) throw InvalidArgument("axes must be >= 1, got " + std::to_string(axes));
  require_positive("period", period);
  require_positive("sigma_v", sigma_v);
  const int n = 2 * axes;
  LinearGaussianMotion m{Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Zero(n, n)};
  const Eigen::Vector2d g(period * period / 2.0, period);
  const Eigen::Matrix2d block = sigma_v * sigma_v * g * g.transpose();
  for (int a = 0; a < axes; ++a) {
    m.F(2 * a, 2 * a + 1) = period;
    m.Q.block<2, 2>(2 * a, 2 * a) = block;
  }
  return m;
}

LinearGaussianObservation LinearGaussianObservation::position_of_constant_velocity(
    int axes, const Eigen::MatrixXd& R) {
  if (axes < 1) throw InvalidArgument("axes must be >= 1, got " + std::to_string(axes));
  if (R.rows() != axes || R.cols() != axes) {
    throw InvalidArgument("R must be " + std::to_string(axes) + "x" + std::to_string(axes));
  }
  LinearGaussianObservation o{Eigen::MatrixXd::Zero(axes, 2 * axes), R, Eigen::MatrixXd()};
  for (int a = 0; a < axes; ++a) o.H(a, 2 * a) = 1.0;
  return o;
}

Eigen::MatrixXd LinearGaussianObservation::noise_at(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (noise_scale.size() == 0) return R;
  Eigen::MatrixXd r = R;
  r.diagonal() += (noise_scale * x).array().square().matrix();
  return r;
}

void validate(const LinearGaussianMotion& motion) {
  if (motion.F.rows() != motion.F.cols() || motion.F.rows() == 0) {
    throw InvalidArgument("motion F must be square and non-empty, got " +
                          std::to_string(motion.F.rows()) + "x" + std::to_string(motion.F.cols()));
  }
  if (!motion.F.allFinite()) throw InvalidArgument("motion F contains NaN or inf");
  core::require_covariance(motion.Q, "motion Q", false, motion.F.rows());
}

void validate(const LinearGaussianObservation& observation) {
  if (observation.H.rows() == 0 || observation.H.cols() == 0) {
    throw InvalidArgument("observation H must not be empty");
  }
  if (!observation.H.allFinite()) throw InvalidArgument("observation H contains NaN or inf");
  core::require_covariance(observation.R, "observation R", true, observation.H.rows());
}

GaussianDensity kalman_predict(const GaussianDensity& prior, const LinearGaussianMotion& motion) {
  return {motion.F * prior.mean, motion.F * prior.cov * motion.F.transpose() + motion.Q};
}

KalmanInnovation::KalmanInnovation(const GaussianDensity& predicted,
                                   const LinearGaussianObservation& observation)
    : predicted_mean_(predicted.mean), predicted_z_(observation.H * predicted.mean) {
  const Eigen::MatrixXd PHt = predicted.cov * observation.H.transpose();
  const Eigen::MatrixXd R = observation.noise_at(predicted.mean);
  Eigen::MatrixXd S = observation.H * PHt + R;
  S = 0.5 * (S + S.transpose());
  innovation_llt_.compute(S);
  if (innovation_llt_.info() != Eigen::Success) {
    throw InvalidArgument("innovation covariance H P H^T + R is not positive definite");
  }
  const Eigen::MatrixXd L = innovation_llt_.matrixL();
  log_normaliser_ = -0.5 * static_cast<double>(S.rows()) * core::kLog2Pi -
                    L.diagonal().array().log().sum();
  gain_ = innovation_llt_.solve(PHt.transpose()).transpose();  // K = P H^T S^{-1}
  const Eigen::Index n = predicted.mean.size();
  const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(n, n) - gain_ * observation.H;
  // Joseph form: stays symmetric positive semi-definite under round-off.
  posterior_cov_ = IKH * predicted.cov * IKH.transpose() + gain_ * R * gain_.transpose();
}

double KalmanInnovation::mahalanobis_squared(const Eigen::Ref<const Eigen::VectorXd>& z) const {
  // The GLMB scores every track against every detection: the whitened residual of the usual
  // measurement sizes lives on the stack (the same arithmetic, no allocation per pair).
  using Small = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 8, 1>;
  if (z.size() <= Small::MaxRowsAtCompileTime) {
    Small white = z - predicted_z_;
    innovation_llt_.matrixL().solveInPlace(white);
    return white.squaredNorm();
  }
  const Eigen::VectorXd white = innovation_llt_.matrixL().solve(z - predicted_z_);
  return white.squaredNorm();
}

double KalmanInnovation::log_likelihood(const Eigen::Ref<const Eigen::VectorXd>& z) const {
  return log_likelihood_at(mahalanobis_squared(z));
}

GaussianDensity KalmanInnovation::posterior(const Eigen::Ref<const Eigen::VectorXd>& z) const {
  return {predicted_mean_ + gain_ * (z - predicted_z_), posterior_cov_};
}

}  // namespace vtrack::models
