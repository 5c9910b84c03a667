#include "vtrack/core/gaussian.hpp"

#include <cmath>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "vtrack/core/errors.hpp"

namespace vtrack::core {

double normal_quantile(double p) {
  require(p > 0.0 && p < 1.0, "p", p, "in (0, 1)");
  // P. J. Acklam's rational approximations (central region and tails), relative error 1.15e-9.
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  constexpr double low = 0.02425;
  double x;
  if (p < low || p > 1.0 - low) {
    const double q = std::sqrt(-2.0 * std::log(p < low ? p : 1.0 - p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
    if (p > 1.0 - low) x = -x;
  } else {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }
  // One Halley step on Phi(x) - p, Phi(x) = erfc(-x / sqrt 2) / 2.
  const double e = 0.5 * std::erfc(-x / std::sqrt(2.0)) - p;
  const double u = e * std::sqrt(2.0 * M_PI) * std::exp(0.5 * x * x);
  return x - u / (1.0 + 0.5 * x * u);
}

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
