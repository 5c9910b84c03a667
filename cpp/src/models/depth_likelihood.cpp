#include "vtrack/models/depth_likelihood.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "vtrack/core/errors.hpp"

namespace vtrack::models {
namespace {

// Pixel coordinate rounded to the nearest pixel boundary, clamped first so that the conversion to
// int is defined for any state (particles can stray far outside the image).
int pixel_edge(double v, int limit) {
  return static_cast<int>(std::floor(std::clamp(v, -1.0, static_cast<double>(limit) + 1.0) + 0.5));
}

}  // namespace

double kinect_raw_to_depth(double raw, double fx) {
  if (!std::isfinite(raw) || raw < 0.0 || raw >= kKinectRawMax) return 0.0;
  return 8.0 * kKinectBaseline * fx / (kKinectRawMax - raw);
}

double kinect_depth_to_raw(double depth, double fx) {
  if (!std::isfinite(depth) || !(depth > 0.0)) return kKinectNoReading;
  const double raw = kKinectRawMax - 8.0 * kKinectBaseline * fx / depth;
  return raw < 0.0 ? kKinectNoReading : raw;
}

PinholeCamera PinholeCamera::of(int width, int height, double fx, std::optional<double> fy,
                               std::optional<double> cx, std::optional<double> cy) {
  return {fx, fy.value_or(fx), cx.value_or(0.5 * (width - 1)), cy.value_or(0.5 * (height - 1)),
          width, height};
}

const core::ParameterTable<DepthLikelihoodParams>& DepthLikelihoodParams::table() {
  using P = DepthLikelihoodParams;
  static const auto table = core::ParameterTable<P>()
                                .add("person_width", &P::person_width)
                                .add("person_height", &P::person_height)
                                .add("sigma_target", &P::sigma_target)
                                .add("sigma_background", &P::sigma_background)
                                .add("tempering", &P::tempering)
                                .add("min_depth", &P::min_depth);
  return table;
}

DepthLikelihood::DepthLikelihood(DepthLikelihoodParams params) : params_(params) {
  validate(params_);
}

void validate(const DepthLikelihoodParams& p) {
  const auto& c = p.camera;
  require_positive("fx", c.fx);
  require_positive("fy", c.fy);
  require(std::isfinite(c.cx), "cx", c.cx, "finite");
  require(std::isfinite(c.cy), "cy", c.cy, "finite");
  require(c.width > 0, "camera width", c.width, "> 0");
  require(c.height > 0, "camera height", c.height, "> 0");
  require_positive("person_width", p.person_width);
  require_positive("person_height", p.person_height);
  require_positive("sigma_target", p.sigma_target);
  require_positive("sigma_background", p.sigma_background);
  require_positive("min_depth", p.min_depth);
  require(p.tempering > 0.0 && p.tempering <= 1.0, "tempering", p.tempering, "in (0, 1]");
}

DepthFrame DepthLikelihood::frame(const cv::Mat& depth) const {
  const auto& c = params_.camera;
  if (depth.empty() || depth.channels() != 1 ||
      (depth.depth() != CV_32F && depth.depth() != CV_64F)) {
    throw InvalidArgument("depth must be a non-empty single-channel float32 or float64 image");
  }
  if (depth.cols != c.width || depth.rows != c.height) {
    throw InvalidArgument("depth must be " + std::to_string(c.height) + "x" +
                          std::to_string(c.width) + " (the depth model's camera), got " +
                          std::to_string(depth.rows) + "x" + std::to_string(depth.cols));
  }
  cv::Mat d;
  depth.convertTo(d, CV_64F);
  if (!cv::checkRange(d, true, nullptr, 0.0, 1e12)) {
    throw InvalidArgument("depth must be finite and >= 0 (metres, 0 = background or no reading)");
  }
  DepthFrame out;
  out.sum.compute(d);
  out.sum_squares.compute(d.mul(d));
  return out;
}

image::Rect DepthLikelihood::footprint(double X, double Y, double D) const {
  const auto& c = params_.camera;
  if (!(D > params_.min_depth) || !std::isfinite(X) || !std::isfinite(Y) || !std::isfinite(D)) {
    return {0, 0, 0, 0};
  }
  const double u = c.cx + c.fx * X / D, v = c.cy + c.fy * Y / D;
  const double a = 0.5 * c.fx * params_.person_width / D, b = 0.5 * c.fy * params_.person_height / D;
  const int x0 = pixel_edge(u - a, c.width), x1 = pixel_edge(u + a, c.width);
  const int y0 = pixel_edge(v - b, c.height), y1 = pixel_edge(v + b, c.height);
  // Clip to the image; an empty or outside rectangle has zero size.
  const int cx0 = std::clamp(x0, 0, c.width), cx1 = std::clamp(x1, cx0, c.width);
  const int cy0 = std::clamp(y0, 0, c.height), cy1 = std::clamp(y1, cy0, c.height);
  return {cx0, cy0, cx1 - cx0, cy1 - cy0};
}

void DepthLikelihood::log_ratio(const DepthFrame& frame,
                                const Eigen::Ref<const Eigen::Matrix3Xd>& positions,
                                Eigen::Ref<Eigen::VectorXd> out, Eigen::VectorXd* visible,
                                bool viewer_reported) const {
  if (out.size() != positions.cols()) {
    throw InvalidArgument("log_ratio: out must have one entry per position");
  }
  const double st2 = params_.sigma_target * params_.sigma_target;
  const double sb2 = params_.sigma_background * params_.sigma_background;
  const double log_ratio_sigma = std::log(params_.sigma_background / params_.sigma_target);
  const double tau = params_.tempering;
  if (visible) visible->setOnes(positions.cols());
  // One pass per state: a footprint, four table look-ups per integral image, a few flops. The
  // look-ups are gathers, so this loop is not SIMD, but it is O(1) per particle and inlined.
  for (Eigen::Index p = 0; p < positions.cols(); ++p) {
    const double D = positions(2, p);
    const image::Rect r = footprint(positions(0, p), positions(1, p), D);
    double n = static_cast<double>(r.width) * r.height;
    if (n == 0.0) {
      out[p] = 0.0;
      continue;
    }
    double s1 = frame.sum.sum(r), s2 = frame.sum_squares.sum(r);
    for (const Occluder& o : frame.occluders) {
      if (!(D > o.hides_beyond) || (o.tracked && viewer_reported)) continue;
      const int x0 = std::max(r.x, o.rect.x), x1 = std::min(r.x + r.width, o.rect.x + o.rect.width);
      const int y0 = std::max(r.y, o.rect.y), y1 = std::min(r.y + r.height, o.rect.y + o.rect.height);
      if (x1 <= x0 || y1 <= y0) continue;
      const image::Rect hidden{x0, y0, x1 - x0, y1 - y0};
      n -= static_cast<double>(hidden.width) * hidden.height;
      s1 -= frame.sum.sum(hidden);
      s2 -= frame.sum_squares.sum(hidden);
    }
    if (!frame.occluders.empty()) {
      const double whole = static_cast<double>(r.width) * r.height;
      n = std::max(n, 0.0), s1 = std::max(s1, 0.0), s2 = std::max(s2, 0.0);
      if (visible) (*visible)[p] = n / whole;
    }
    // sum over T(x) of log phi_i - log varphi_i, expanded so only S1, S2, n are needed.
    out[p] = tau * (-(s2 - 2.0 * D * s1 + n * D * D) / (2.0 * st2) + s2 / (2.0 * sb2) +
                    n * log_ratio_sigma);
  }
}

}  // namespace vtrack::models
