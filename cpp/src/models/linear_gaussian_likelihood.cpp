#include "vtrack/models/linear_gaussian_likelihood.hpp"

#include <cmath>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"

namespace vtrack::models {

LinearGaussianLikelihood::LinearGaussianLikelihood(const LinearGaussianObservation& observation)
    : observation_(observation) {
  const auto& H = observation_.H;
  const auto& R = observation_.R;
  if (H.rows() == 0 || H.cols() == 0) throw InvalidArgument("H is empty");
  if (R.rows() != H.rows() || R.cols() != H.rows()) {
    throw InvalidArgument("R must be " + std::to_string(H.rows()) + "x" +
                          std::to_string(H.rows()) + " to match H, got " +
                          std::to_string(R.rows()) + "x" + std::to_string(R.cols()));
  }
  if (!H.allFinite()) throw InvalidArgument("H contains NaN or inf");
  // core::Gaussian checks R (finite, symmetric, positive definite) and gives its factor.
  try {
    chol_ = core::Gaussian(Eigen::VectorXd::Zero(R.rows()), R).cholesky();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(std::string("observation R: ") + e.what());
  }
  log_normaliser_ = -0.5 * static_cast<double>(R.rows()) * core::kLog2Pi -
                    chol_.diagonal().array().log().sum();
}

void LinearGaussianLikelihood::check(const Eigen::VectorXd& z) const {
  if (z.size() != observation_.H.rows()) {
    throw InvalidArgument("z must have " + std::to_string(observation_.H.rows()) +
                          " values, got " + std::to_string(z.size()));
  }
  if (!z.allFinite()) throw InvalidArgument("z contains NaN or inf");
}

void LinearGaussianLikelihood::log_likelihood(const StatesView<double>& x, const Eigen::VectorXd& z,
                       double* out) const {
  log_likelihood_impl(x, z, out);
}

void LinearGaussianLikelihood::log_likelihood(const StatesView<float>& x, const Eigen::VectorXd& z,
                       double* out) const {
  log_likelihood_impl(x, z, out);
}

template <typename Scalar>
void LinearGaussianLikelihood::log_likelihood_impl(const StatesView<Scalar>& x,
                                              const Eigen::VectorXd& z, double* out) const {
  const Eigen::Index n = x.rows();
  if (n == 0) return;
  // Residuals z - H x_i as rows (n x m), whitened by L^-1 from the right: e L^T = z - H x.
  Eigen::MatrixXd e = -(x.template cast<double>() * observation_.H.transpose());
  e.rowwise() += z.transpose();
  chol_.transpose().triangularView<Eigen::Upper>().template solveInPlace<Eigen::OnTheRight>(e);
  Eigen::Map<Eigen::VectorXd>(out, n) =
      (log_normaliser_ - 0.5 * e.rowwise().squaredNorm().array()).matrix();
}

}  // namespace vtrack::models
