#pragma once
// Range-bearing observation of a point target from a sensor at s = (s_x, s_y): z = [r, b] with
// r = |p - s| + w_r, b = atan2(p_y - s_y, p_x - s_x) + w_b, w_r ~ N(0, sigma_range^2),
// w_b ~ N(0, sigma_bearing^2) independent; p = (x[ix], x[iy]) is the target's position in the
// state. The bearing residual is wrapped to (-pi, pi] (computed as the angle of p - s rotated by
// -b, so it is never off by 2 pi). Satisfies the SMC engine's observation concept.
#include <Eigen/Core>

#include "vtrack/models/states.hpp"

namespace vtrack::models {

struct RangeBearingParams {
  double sigma_range = 1.0;     // m
  double sigma_bearing = 0.01;  // rad
  double sensor_x = 0.0;
  double sensor_y = 0.0;
  // Indices of the position in the state ((0, 2) for constant velocity [p_x, v_x, p_y, v_y]).
  int x_index = 0;
  int y_index = 2;
};
void validate(const RangeBearingParams& params);

class RangeBearingObservation {
 public:
  explicit RangeBearingObservation(const RangeBearingParams& params = {});
  const RangeBearingParams& params() const { return params_; }
  int measurement_dim() const { return 2; }
  // The smallest state dimension the position indices fit in.
  int min_state_dim() const;

  // InvalidArgument unless z is [range, bearing], finite.
  void check(const Eigen::VectorXd& z) const;
  // log p(z | x_i) for the n particles of `x` (n x d) into out[0..n).
  void log_likelihood(const StatesView<double>& x, const Eigen::VectorXd& z, double* out) const;
  void log_likelihood(const StatesView<float>& x, const Eigen::VectorXd& z, double* out) const;

 private:
  template <typename Scalar>
  void log_likelihood_impl(const StatesView<Scalar>& x, const Eigen::VectorXd& z, double* out) const;

  RangeBearingParams params_;
  double log_normaliser_;  // -log(2 pi) - log sigma_range - log sigma_bearing
};

}  // namespace vtrack::models
