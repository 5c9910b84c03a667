#include "vtrack/image/integral_image.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"

namespace vtrack::image {

void IntegralImage::compute(const cv::Mat& image) {
  if (image.empty()) throw InvalidArgument("image is empty");
  if (image.channels() != 1) {
    throw InvalidArgument("image must have 1 channel, got " + std::to_string(image.channels()));
  }
  const int depth = image.depth();
  if (depth != CV_8U && depth != CV_32F && depth != CV_64F) {
    throw InvalidArgument("image must be uint8, float32 or float64");
  }
  cv::integral(image, table_, CV_64F);
  // A NaN or inf pixel makes the total (and every sum over it) NaN or inf: checked in O(1) on the
  // total, since finite float pixels cannot overflow a double sum.
  if (depth != CV_8U && !std::isfinite(table_.at<double>(table_.rows - 1, table_.cols - 1))) {
    table_.release();
    throw InvalidArgument("image contains NaN or inf (or its sum overflows a double)");
  }
}

Rect IntegralImage::clip(const Rect& rect) const {
  // 64-bit arithmetic so x + width cannot overflow for extreme inputs.
  const long long x0 = std::clamp<long long>(rect.x, 0, cols());
  const long long y0 = std::clamp<long long>(rect.y, 0, rows());
  const long long x1 = std::clamp<long long>(static_cast<long long>(rect.x) + rect.width, x0, cols());
  const long long y1 = std::clamp<long long>(static_cast<long long>(rect.y) + rect.height, y0, rows());
  return Rect{static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1 - x0),
              static_cast<int>(y1 - y0)};
}

double IntegralImage::sum(const Rect& rect) const {
  if (table_.empty()) throw InvalidArgument("integral image has not been computed");
  const Rect r = clip(rect);
  if (r.width == 0 || r.height == 0) return 0.0;
  const double* top = table_.ptr<double>(r.y);
  const double* bottom = table_.ptr<double>(r.y + r.height);
  return bottom[r.x + r.width] - bottom[r.x] - top[r.x + r.width] + top[r.x];
}

long long IntegralImage::area(const Rect& rect) const {
  const Rect r = clip(rect);
  return static_cast<long long>(r.width) * r.height;
}

}  // namespace vtrack::image
