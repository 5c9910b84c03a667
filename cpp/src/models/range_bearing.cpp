#include "vtrack/models/range_bearing.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/vmath.hpp"

namespace vtrack::models {

void validate(const RangeBearingParams& p) {
  require(p.sigma_range > 0.0 && std::isfinite(p.sigma_range), "sigma_range", p.sigma_range,
          "positive and finite");
  require(p.sigma_bearing > 0.0 && std::isfinite(p.sigma_bearing), "sigma_bearing",
          p.sigma_bearing, "positive and finite");
  require(std::isfinite(p.sensor_x), "sensor x", p.sensor_x, "finite");
  require(std::isfinite(p.sensor_y), "sensor y", p.sensor_y, "finite");
  require(p.x_index >= 0, "x_index", p.x_index, ">= 0");
  require(p.y_index >= 0 && p.y_index != p.x_index, "y_index", p.y_index, ">= 0 and != x_index");
}

RangeBearingObservation::RangeBearingObservation(const RangeBearingParams& params)
    : params_(params) {
  validate(params_);
  log_normaliser_ =
      -core::kLog2Pi - std::log(params_.sigma_range) - std::log(params_.sigma_bearing);
}

int RangeBearingObservation::min_state_dim() const {
  return std::max(params_.x_index, params_.y_index) + 1;
}

void RangeBearingObservation::check(const Eigen::VectorXd& z) const {
  if (z.size() != 2) {
    throw InvalidArgument("z must be [range, bearing], got " + std::to_string(z.size()) +
                          " values");
  }
  if (!z.allFinite()) throw InvalidArgument("z contains NaN or inf");
}

void RangeBearingObservation::log_likelihood(const StatesView<double>& x, const Eigen::VectorXd& z,
                       double* out) const {
  log_likelihood_impl(x, z, out);
}

void RangeBearingObservation::log_likelihood(const StatesView<float>& x, const Eigen::VectorXd& z,
                       double* out) const {
  log_likelihood_impl(x, z, out);
}

// Computed in the states' precision: float states give float residuals (twice the vector width
// and a shorter atan2), whose error is far below the states' own rounding, then a double
// log-likelihood.
template <typename Scalar>
void RangeBearingObservation::log_likelihood_impl(const StatesView<Scalar>& x,
                                             const Eigen::VectorXd& z, double* out) const {
  const Eigen::Index n = x.rows();
  if (n == 0) return;
  const Scalar* px = column(x, params_.x_index);
  const Scalar* py = column(x, params_.y_index);
  const auto sx = static_cast<Scalar>(params_.sensor_x);
  const auto sy = static_cast<Scalar>(params_.sensor_y);
  const auto range = static_cast<Scalar>(z[0]);
  const auto c = static_cast<Scalar>(std::cos(z[1]));
  const auto s = static_cast<Scalar>(std::sin(z[1]));
  const auto inv_r = static_cast<Scalar>(1.0 / params_.sigma_range);
  const auto inv_b = static_cast<Scalar>(1.0 / params_.sigma_bearing);
  const double norm = log_normaliser_;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Scalar dx = px[i] - sx;
    const Scalar dy = py[i] - sy;
    const Scalar dr = (std::sqrt(dx * dx + dy * dy) - range) * inv_r;
    // Bearing of (dx, dy) minus b: the angle of (dx, dy) rotated by -b, in (-pi, pi].
    const Scalar db = core::vmath::atan2(c * dy - s * dx, c * dx + s * dy) * inv_b;
    out[i] = norm - 0.5 * static_cast<double>(dr * dr + db * db);
  }
}

}  // namespace vtrack::models
