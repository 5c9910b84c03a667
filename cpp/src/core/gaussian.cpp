#include "vtrack/core/gaussian.hpp"

#include <cmath>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "vtrack/core/errors.hpp"

namespace vtrack::core {

void require_covariance(const Eigen::Ref<const Eigen::MatrixXd>& cov, const std::string& name,
                        bool definite, Eigen::Index dim) {
  const std::string size = std::to_string(cov.rows()) + "x" + std::to_string(cov.cols());
  if (cov.rows() != cov.cols() || (dim >= 0 && cov.rows() != dim)) {
    const std::string want = dim >= 0 ? std::to_string(dim) + "x" + std::to_string(dim) : "square";
    throw InvalidArgument(name + " must be " + want + ", got " + size);
  }
  if (cov.size() == 0) return;
  if (!cov.allFinite()) throw InvalidArgument(name + " contains NaN or inf");
  const double scale = cov.cwiseAbs().maxCoeff();
  if ((cov - cov.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    throw InvalidArgument(name + " is not symmetric");
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov, Eigen::EigenvaluesOnly);
  const double lowest = eig.eigenvalues().minCoeff();
  if (definite && !(lowest > 0.0)) {
    throw InvalidArgument(name + " must be positive definite, has eigenvalue " + value_text(lowest));
  }
  if (!definite && lowest < -1e-9 * scale) {
    throw InvalidArgument(name + " must be positive semi-definite, has eigenvalue " +
                          value_text(lowest));
  }
}

Gaussian::Gaussian(Eigen::VectorXd mean, const Eigen::MatrixXd& covariance)
    : mean_(std::move(mean)) {
  const Eigen::Index d = mean_.size();
  if (d == 0) throw InvalidArgument("mean is empty");
  if (covariance.rows() != d || covariance.cols() != d) {
    throw InvalidArgument("covariance must be " + std::to_string(d) + "x" + std::to_string(d) +
                          " to match mean, got " + std::to_string(covariance.rows()) + "x" +
                          std::to_string(covariance.cols()));
  }
  if (!mean_.allFinite()) throw InvalidArgument("mean contains NaN or inf");
  if (!covariance.allFinite()) throw InvalidArgument("covariance contains NaN or inf");
  const double scale = covariance.cwiseAbs().maxCoeff();
  if ((covariance - covariance.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    throw InvalidArgument("covariance is not symmetric");
  }
  Eigen::LLT<Eigen::MatrixXd> llt(covariance);
  if (llt.info() != Eigen::Success) {
    throw InvalidArgument("covariance is not positive definite (Cholesky factorisation failed)");
  }
  chol_ = llt.matrixL();
  const Eigen::VectorXd diag = chol_.diagonal();
  if ((diag.array() <= 0.0).any() || !diag.allFinite()) {
    throw InvalidArgument("covariance is not positive definite (singular Cholesky factor)");
  }
  log_normaliser_ = -0.5 * static_cast<double>(d) * kLog2Pi - diag.array().log().sum();
}

Eigen::VectorXd Gaussian::sample(Rng& rng) const {
  Eigen::VectorXd z(dim());
  rng.fill_normal(z.data(), static_cast<std::size_t>(z.size()));
  return mean_ + chol_.triangularView<Eigen::Lower>() * z;
}

Eigen::MatrixXd Gaussian::sample(Rng& rng, Eigen::Index n) const {
  if (n < 0) throw InvalidArgument("sample count must be >= 0, got " + std::to_string(n));
  Eigen::MatrixXd z(dim(), n);
  rng.fill_normal(z.data(), static_cast<std::size_t>(z.size()));
  Eigen::MatrixXd x = chol_.triangularView<Eigen::Lower>() * z;
  x.colwise() += mean_;
  return x;
}

double Gaussian::log_density(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (x.size() != mean_.size()) {
    throw InvalidArgument("x has dimension " + std::to_string(x.size()) + ", expected " +
                          std::to_string(mean_.size()));
  }
  const Eigen::VectorXd white = chol_.triangularView<Eigen::Lower>().solve(x - mean_);
  return log_normaliser_ - 0.5 * white.squaredNorm();
}

Eigen::VectorXd Gaussian::log_density_columns(const Eigen::Ref<const Eigen::MatrixXd>& xs) const {
  if (xs.rows() != mean_.size()) {
    throw InvalidArgument("points have dimension " + std::to_string(xs.rows()) + ", expected " +
                          std::to_string(mean_.size()));
  }
  Eigen::MatrixXd white = xs.colwise() - mean_;
  chol_.triangularView<Eigen::Lower>().solveInPlace(white);
  return (log_normaliser_ - 0.5 * white.colwise().squaredNorm().array()).matrix().transpose();
}

}  // namespace vtrack::core
