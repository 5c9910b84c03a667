#pragma once
// Multivariate normal distribution N(mean, covariance): sampling through the Cholesky factor and
// log-density. The covariance must be symmetric positive definite; anything else is an
// InvalidArgument that says so.
#include <string>

#include <Eigen/Core>

#include "vtrack/core/random.hpp"

namespace vtrack::core {

// Checks a covariance matrix given by a user: InvalidArgument naming `name` unless it is square
// (of size `dim` when dim >= 0), finite, symmetric (to 1e-9 of its largest entry) and positive
// definite (`definite`) or positive semi-definite (no eigenvalue below -1e-9 of its scale; a
// constant-velocity Q is singular). A negative variance accepted here would come back as a
// negative variance or NaN in every estimate.
void require_covariance(const Eigen::Ref<const Eigen::MatrixXd>& cov, const std::string& name,
                        bool definite, Eigen::Index dim = -1);

// log(2 pi): the normaliser of every Gaussian density in vtrack, -d/2 log(2 pi) - 1/2 log|C|.
inline constexpr double kLog2Pi = 1.8378770664093454835606594728112;

// The standard normal quantile Phi^-1(p), p in (0, 1) (Acklam's rational approximation refined by
// one Halley step on erfc: relative error below 1e-12). InvalidArgument outside (0, 1).
double normal_quantile(double p);

class Gaussian {
 public:
  Gaussian(Eigen::VectorXd mean, const Eigen::MatrixXd& covariance);

  int dim() const { return static_cast<int>(mean_.size()); }
  const Eigen::VectorXd& mean() const { return mean_; }
  Eigen::MatrixXd covariance() const { return chol_ * chol_.transpose(); }
  // Lower-triangular L with L L^T = covariance.
  const Eigen::MatrixXd& cholesky() const { return chol_; }

  Eigen::VectorXd sample(Rng& rng) const;
  // n samples as the columns of a dim x n matrix.
  Eigen::MatrixXd sample(Rng& rng, Eigen::Index n) const;

  // log N(x; mean, covariance) = -d/2 log(2 pi) - 1/2 log|C| - 1/2 (x-m)^T C^{-1} (x-m).
  double log_density(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // Log-density of each column of a dim x n matrix.
  Eigen::VectorXd log_density_columns(const Eigen::Ref<const Eigen::MatrixXd>& xs) const;

 private:
  Eigen::VectorXd mean_;
  Eigen::MatrixXd chol_;
  double log_normaliser_;  // -d/2 log(2 pi) - sum log L_ii
};

}  // namespace vtrack::core
