#include "vtrack/models/box_motion.hpp"

#include <algorithm>
#include <cmath>

#include "vtrack/core/errors.hpp"

namespace vtrack::models {

const core::ParameterTable<BoxMotionParams>& BoxMotionParams::table() {
  using P = BoxMotionParams;
  static const auto t = core::ParameterTable<P>()
                            .add("noise", &P::noise)
                            .add("min_scale", &P::min_scale)
                            .add("max_scale", &P::max_scale)
                            .add("min_size", &P::min_size);
  return t;
}

void validate(const BoxMotionParams& p) {
  for (double v : p.noise) {
    require(v >= 0.0 && std::isfinite(v), "noise", v, "non-negative and finite");
  }
  require(p.min_scale > 0.0 && std::isfinite(p.min_scale), "min_scale", p.min_scale,
          "positive and finite");
  require(p.max_scale >= p.min_scale && std::isfinite(p.max_scale), "max_scale", p.max_scale,
          ">= min_scale and finite");
  require(p.min_size >= 0.0 && std::isfinite(p.min_size), "min_size", p.min_size,
          "non-negative and finite");
}

BoxMotion::BoxMotion(const BoxMotionParams& params, double reference_h, double reference_w)
    : params_(params) {
  validate(params_);
  require(reference_h > 0.0 && std::isfinite(reference_h), "reference_h", reference_h,
          "positive and finite");
  require(reference_w > 0.0 && std::isfinite(reference_w), "reference_w", reference_w,
          "positive and finite");
  h_lo_ = std::max(params_.min_size, params_.min_scale * reference_h);
  h_hi_ = std::max(h_lo_, params_.max_scale * reference_h);
  w_lo_ = std::max(params_.min_size, params_.min_scale * reference_w);
  w_hi_ = std::max(w_lo_, params_.max_scale * reference_w);
}

void BoxMotion::propagate(const StatesView<double>& prev, const StatesView<double>& eps,
                          MutableStatesView<double> next) const {
  const Eigen::Index n = prev.rows();
  const double* h = column(prev, 2);
  const double* w = column(prev, 3);
  // U's standard deviation per component, scaled by the previous box (see the file comment).
  const double* scale_of[4] = {w, h, h, w};
  for (int c = 0; c < 4; ++c) {
    const double* x = column(prev, c);
    const double* x_prev = column(prev, c + 4);
    const double* e = column(eps, c);
    const double* s = scale_of[c];
    const double k = params_.noise[static_cast<std::size_t>(c)];
    double* out = column(next, c);
    double* copy = column(next, c + 4);
    for (Eigen::Index i = 0; i < n; ++i) {
      out[i] = 2.0 * x[i] - x_prev[i] + k * s[i] * e[i];  // eq. 13
      copy[i] = x[i];
    }
  }
  double* nh = column(next, 2);
  double* nw = column(next, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    nh[i] = std::min(std::max(nh[i], h_lo_), h_hi_);
    nw[i] = std::min(std::max(nw[i], w_lo_), w_hi_);
  }
}

}  // namespace vtrack::models
