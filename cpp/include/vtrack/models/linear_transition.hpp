#pragma once
// The sampling form of a linear-Gaussian motion model: x_k = F x_{k-1} + S eps, eps ~ N(0, I_r),
// with S S^T = Q (d x r; r < d when Q is singular, e.g. the discrete white-noise acceleration of
// rgbd-glmb eq. 7 or the second-order auto-regressive model's copied half). Every built-in motion
// model of the SMC engine is one (motion.hpp); it satisfies the engine's motion concept
// (smc/model.hpp): dim(), noise_dim(), propagate(prev, eps, next) and noise_factor().
//
// Propagation skips the zeros of F and S: each state component is one loop over the particles
// summing its few nonzero terms (for constant velocity: 3 terms per component instead of 8), so
// the structured models need no hand-written kernels of their own.
#include <vector>

#include <Eigen/Core>

#include "vtrack/models/linear_gaussian.hpp"
#include "vtrack/models/states.hpp"

namespace vtrack::models {

class LinearTransition {
 public:
  // F (d x d) and the noise factor S (d x r, r >= 0); both finite.
  LinearTransition(Eigen::MatrixXd F, Eigen::MatrixXd S);
  // F and a symmetric positive semi-definite Q: S is Q's Cholesky factor when Q is positive
  // definite, otherwise V sqrt(Lambda) over Q's r nonzero eigenvalues. InvalidArgument (naming
  // `name`) when Q is not symmetric or has a negative eigenvalue.
  static LinearTransition from_covariance(Eigen::MatrixXd F, const Eigen::MatrixXd& Q,
                                          const char* name = "Q");
  // The engine's form of the Kalman-side model (models/linear_gaussian.hpp).
  static LinearTransition from_motion(const LinearGaussianMotion& motion) {
    return from_covariance(motion.F, motion.Q);
  }

  int dim() const { return static_cast<int>(F_.rows()); }
  int noise_dim() const { return static_cast<int>(S_.cols()); }
  const Eigen::MatrixXd& F() const { return F_; }
  const Eigen::MatrixXd& noise_factor() const { return S_; }
  Eigen::MatrixXd Q() const { return S_ * S_.transpose(); }

  // next = prev F^T + eps S^T for a block of particles (n x d, n x r, n x d); next may not alias
  // prev. For double and float states.
  void propagate(const StatesView<double>& prev, const StatesView<double>& eps,
                 MutableStatesView<double> next) const;
  void propagate(const StatesView<float>& prev, const StatesView<float>& eps,
                 MutableStatesView<float> next) const;

 private:
  struct Term {
    bool noise;   // from eps (else from prev)
    int column;   // of prev or eps
    double coef;
  };
  template <typename Scalar>
  void propagate_impl(const StatesView<Scalar>& prev, const StatesView<Scalar>& eps,
                      MutableStatesView<Scalar>& next) const;

  Eigen::MatrixXd F_;
  Eigen::MatrixXd S_;
  std::vector<std::vector<Term>> terms_;  // per state component: the nonzeros of its rows of F, S
};

}  // namespace vtrack::models
