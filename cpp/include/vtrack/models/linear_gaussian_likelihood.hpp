#pragma once
// The particle form of the linear-Gaussian observation z = H x + w, w ~ N(0, R)
// (models/linear_gaussian.hpp): log N(z; H x_i, R) for every particle of a block, through the
// Cholesky factor of R computed once. Satisfies the SMC engine's observation concept.
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "vtrack/models/linear_gaussian.hpp"
#include "vtrack/models/states.hpp"

namespace vtrack::models {

class LinearGaussianLikelihood {
 public:
  // InvalidArgument when H and R do not fit or R is not symmetric positive definite.
  explicit LinearGaussianLikelihood(const LinearGaussianObservation& observation);

  const LinearGaussianObservation& observation() const { return observation_; }
  int measurement_dim() const { return static_cast<int>(observation_.H.rows()); }
  int min_state_dim() const { return static_cast<int>(observation_.H.cols()); }

  // InvalidArgument unless z has measurement_dim() finite values.
  void check(const Eigen::VectorXd& z) const;
  // log N(z; H x_i, R) for the n particles of `x` (n x d, d = H's columns) into out[0..n).
  void log_likelihood(const StatesView<double>& x, const Eigen::VectorXd& z, double* out) const;
  void log_likelihood(const StatesView<float>& x, const Eigen::VectorXd& z, double* out) const;

 private:
  template <typename Scalar>
  void log_likelihood_impl(const StatesView<Scalar>& x, const Eigen::VectorXd& z, double* out) const;

  LinearGaussianObservation observation_;
  Eigen::MatrixXd chol_;    // lower L, L L^T = R
  double log_normaliser_;   // -m/2 log(2 pi) - sum log L_ii
};

}  // namespace vtrack::models
