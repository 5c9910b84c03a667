#pragma once
// Motion models of the SMC engine, each a LinearTransition (x_k = F x_{k-1} + S eps) with its
// parameters: the random walk (mb-tbd paper Section 4, eq. 22's x + e), constant velocity in any
// number of axes with the continuous or the discrete white-noise-acceleration covariance
// (rgbd-glmb paper eq. 7 is the discrete one), and the second-order auto-regressive model of
// part-based-graphical-model-pf eq. 13.
#include <string>
#include <vector>

#include "vtrack/models/linear_transition.hpp"

namespace vtrack::models {

// x_k = x_{k-1} + e, e ~ N(0, diag(sigma^2)).
struct RandomWalkParams {
  // Standard deviation per state component (one value: the same for all `dims` components).
  std::vector<double> sigma{1.0};
  // State dimension; 0 = sigma.size().
  int dims = 0;
};
void validate(const RandomWalkParams& params);

class RandomWalk : public LinearTransition {
 public:
  explicit RandomWalk(const RandomWalkParams& params = {});
  const RandomWalkParams& params() const { return params_; }

 private:
  RandomWalkParams params_;
};

enum class AccelerationNoise { Continuous, Discrete };
// Parses "continuous" or "discrete"; InvalidArgument otherwise.
AccelerationNoise parse_acceleration_noise(const std::string& name);
const char* to_string(AccelerationNoise noise);

// Constant velocity per axis, state [p_1, v_1, p_2, v_2, ...], F = I (x) [[1, T], [0, 1]].
// Continuous white-noise acceleration of power spectral density q (Bar-Shalom et al. 2001, §6.2.2):
// Q = q (I (x) [[T^3/3, T^2/2], [T^2/2, T]]), positive definite. Discrete (piecewise-constant
// acceleration of variance q per period, rgbd-glmb eq. 7 with q = sigma_v^2):
// Q = q (I (x) g g^T), g = [T^2/2, T]^T, rank one per axis.
struct ConstantVelocityParams {
  int axes = 2;
  double period = 1.0;  // T
  double q = 1.0;       // continuous: m^2/s^3 (per unit of period); discrete: (m/s^2)^2
  AccelerationNoise noise = AccelerationNoise::Continuous;
};
void validate(const ConstantVelocityParams& params);

class ConstantVelocity : public LinearTransition {
 public:
  explicit ConstantVelocity(const ConstantVelocityParams& params = {});
  const ConstantVelocityParams& params() const { return params_; }

 private:
  ConstantVelocityParams params_;
};

// Part-based-graphical-model-pf eq. 13: X_k = 2 X_{k-1} - X_{k-2} + U_{k-1}, U ~ N(0, diag(sigma^2)).
// The state carries both X_k and X_{k-1}: [X_k (dims), X_{k-1} (dims)], so
// F = [[2 I, -I], [I, 0]] and S = [[diag(sigma)], [0]] (the copied half has no noise). Observation
// models look at the first `dims` components. The paper's X is (x, y, h, w) of a rectangle.
struct SecondOrderAutoRegressiveParams {
  std::vector<double> sigma{1.0};  // per component of X (one value: the same for all)
  int dims = 0;                    // components of X; 0 = sigma.size()
};
void validate(const SecondOrderAutoRegressiveParams& params);

class SecondOrderAutoRegressive : public LinearTransition {
 public:
  explicit SecondOrderAutoRegressive(const SecondOrderAutoRegressiveParams& params = {});
  const SecondOrderAutoRegressiveParams& params() const { return params_; }

 private:
  SecondOrderAutoRegressiveParams params_;
};

}  // namespace vtrack::models
