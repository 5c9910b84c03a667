#pragma once
// Linear-Gaussian motion and observation models and the Kalman recursion for Gaussian track
// densities (used by the GLMB filter's Gaussian tracks and by any Kalman-based tracker).
#include <Eigen/Core>
#include <Eigen/Cholesky>

namespace vtrack::models {

// x_k = F x_{k-1} + v,  v ~ N(0, Q).
struct LinearGaussianMotion {
  Eigen::MatrixXd F;
  Eigen::MatrixXd Q;

  // Constant velocity in `axes` dimensions, rgbd-glmb-switching-observation.txt eq. (7): state
  // [p_1, v_1, p_2, v_2, ...], F = I ⊗ [[1, T], [0, 1]], Q = sigma_v^2 (I ⊗ g g^T) with
  // g = [T^2/2, T]^T (a white-noise acceleration of standard deviation sigma_v per axis).
  // axes = 3 is the paper's 3-D model; axes = 2 is the standard GLMB benchmark's.
  static LinearGaussianMotion constant_velocity(int axes, double period, double sigma_v);
};

// z = H x + w,  w ~ N(0, R(x)), R(x) = R + diag((A x)^2): a noise that may grow with the state.
struct LinearGaussianObservation {
  Eigen::MatrixXd H;
  Eigen::MatrixXd R;
  // A (z_dim x x_dim), or empty for the constant R: the standard deviation that component i of the
  // noise gains per unit of (A x)_i, e.g. a box detector whose corner errors are a fraction of the
  // box's width and height. The Kalman recursion evaluates R(x) at the predicted mean (the usual
  // linearisation of a state-dependent noise); the particle GLMB's eq. (2) uses R alone.
  Eigen::MatrixXd noise_scale;

  // R(x) at the state x.
  Eigen::MatrixXd noise_at(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  // Positions of a constant-velocity state (eq. 2's H = [1 0 1 0 1 0] pattern, one row per axis)
  // with noise covariance R (axes x axes).
  static LinearGaussianObservation position_of_constant_velocity(int axes,
                                                                 const Eigen::MatrixXd& R);
};

// InvalidArgument naming the matrix unless F is square and finite and Q a covariance of its
// size (symmetric, positive semi-definite: core::require_covariance).
void validate(const LinearGaussianMotion& motion);
// InvalidArgument naming the matrix unless H is finite with rows = R's size and R is a positive
// definite covariance (eq. 2's likelihood needs R^-1).
void validate(const LinearGaussianObservation& observation);

struct GaussianDensity {
  Eigen::VectorXd mean;
  Eigen::MatrixXd cov;
};

// Chapman-Kolmogorov step: N(F m, F P F^T + Q).
GaussianDensity kalman_predict(const GaussianDensity& prior, const LinearGaussianMotion& motion);

// The measurement-independent half of a Kalman update, computed once per track and reused for
// every measurement (a GLMB update scores each track against every detection).
class KalmanInnovation {
 public:
  KalmanInnovation(const GaussianDensity& predicted, const LinearGaussianObservation& observation);

  // log N(z; H m, S) with S = H P H^T + R: the track's measurement likelihood (eq. 2).
  double log_likelihood(const Eigen::Ref<const Eigen::VectorXd>& z) const;
  // Squared Mahalanobis distance (z - H m)^T S^{-1} (z - H m), for gating.
  double mahalanobis_squared(const Eigen::Ref<const Eigen::VectorXd>& z) const;
  // log_likelihood(z) from z's mahalanobis_squared (a gate has computed it already).
  double log_likelihood_at(double mahalanobis_squared) const {
    return log_normaliser_ - 0.5 * mahalanobis_squared;
  }
  // Posterior N(m + K (z - H m), (I - K H) P) in Joseph form.
  GaussianDensity posterior(const Eigen::Ref<const Eigen::VectorXd>& z) const;

 private:
  Eigen::VectorXd predicted_mean_;
  Eigen::VectorXd predicted_z_;
  Eigen::LLT<Eigen::MatrixXd> innovation_llt_;
  double log_normaliser_;
  Eigen::MatrixXd gain_;
  Eigen::MatrixXd posterior_cov_;
};

}  // namespace vtrack::models
