#include "vtrack/filters/appearance.hpp"

#include <algorithm>
#include <string>

#include "vtrack/core/errors.hpp"

namespace vtrack::filters {

void check_colour_frame(const cv::Mat& frame, const cv::Mat& y) {
  if (y.empty() || y.type() != CV_32FC1) {
    throw InvalidArgument("y must be a non-empty single-channel float32 image");
  }
  if (frame.empty() || frame.type() != CV_8UC3) {
    throw InvalidArgument("frame must be an 8-bit BGR image with 3 channels, got " +
                          (frame.empty() ? std::string("an empty image")
                                         : std::to_string(frame.channels()) + " channels of depth " +
                                               std::to_string(frame.depth())));
  }
  if (frame.rows != y.rows || frame.cols != y.cols) {
    throw InvalidArgument("frame must have y's size " + std::to_string(y.rows) + " x " +
                          std::to_string(y.cols) + " (height x width), got " +
                          std::to_string(frame.rows) + " x " + std::to_string(frame.cols));
  }
}

void ForegroundColour::measure(const cv::Mat& frame, const cv::Mat& y, float threshold,
                               const std::vector<Eigen::Vector4f>& boxes,
                               std::vector<ColourHistogram>& out) {
  check_colour_frame(frame, y);
  out.assign(boxes.size(), {});
  const int m = bins_.bins();
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const Eigen::Vector4f& b = boxes[k];
    const image::Rect rect = image::pixel_rect(b[0], b[1], b[2], b[3]);
    // Each box is quantised on its own: the boxes cover a few percent of the frame.
    bins_.assign(frame, rect);
    const image::Rect r = bins_.roi();
    if (r.width <= 0 || r.height <= 0) continue;
    counts_.assign(std::size_t(m), 0.0);
    long long n = 0;
    for (int row = r.y; row < r.y + r.height; ++row) {
      const float* yr = y.ptr<float>(row);
      const std::uint16_t* idx = bins_.row_ptr(row);
      for (int c = 0; c < r.width; ++c) {
        if (yr[r.x + c] < threshold) {
          counts_[idx[c]] += 1.0;
          ++n;
        }
      }
    }
    const double area = double(rect.width) * double(rect.height);
    if (n == 0 || double(n) < min_fraction * area) continue;
    ColourHistogram& h = out[k];
    h.resize(std::size_t(m));
    for (int u = 0; u < m; ++u) h[std::size_t(u)] = float(counts_[std::size_t(u)] / double(n));
  }
}

}  // namespace vtrack::filters
