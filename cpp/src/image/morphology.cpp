#include "vtrack/image/morphology.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "parallel_rows.hpp"
#include "vtrack/core/errors.hpp"

namespace vtrack::image {
namespace {

struct Max {
  float operator()(float a, float b) const { return std::max(a, b); }
};
struct Min {
  float operator()(float a, float b) const { return std::min(a, b); }
};

// dst = Op over the size x size square around each pixel of src (src and dst distinct), pixels
// outside the image ignored. Separable: the vertical Op of the rows in the window into a row
// buffer, then the horizontal Op along that buffer; both inner loops run over contiguous floats.
template <class Op>
void filter_square(const cv::Mat& src, cv::Mat& dst, int size, int threads) {
  const Op op;
  const int rows = src.rows, cols = src.cols, radius = size / 2;
  detail::for_rows(rows, threads, [&](int begin, int end) {
    std::vector<float> column(static_cast<std::size_t>(cols));
    for (int y = begin; y < end; ++y) {
      const int y0 = std::max(0, y - radius), y1 = std::min(rows - 1, y + radius);
      std::copy_n(src.ptr<float>(y0), cols, column.data());
      for (int yy = y0 + 1; yy <= y1; ++yy) {
        const float* in = src.ptr<float>(yy);
        for (int x = 0; x < cols; ++x) column[x] = op(column[x], in[x]);
      }
      float* out = dst.ptr<float>(y);
      // Interior: the whole window is inside the row.
      const int inner_begin = std::min(radius, cols), inner_end = std::max(inner_begin, cols - radius);
      for (int x = inner_begin; x < inner_end; ++x) out[x] = column[x - radius];
      for (int j = 1; j <= 2 * radius; ++j) {
        for (int x = inner_begin; x < inner_end; ++x) out[x] = op(out[x], column[x - radius + j]);
      }
      // Borders: the window is clipped to the row.
      for (int x = 0; x < cols; ++x) {
        if (x >= inner_begin && x < inner_end) x = inner_end;
        if (x >= cols) break;
        const int x0 = std::max(0, x - radius), x1 = std::min(cols - 1, x + radius);
        float v = column[x0];
        for (int xx = x0 + 1; xx <= x1; ++xx) v = op(v, column[xx]);
        out[x] = v;
      }
    }
  });
}

}  // namespace

void close_square(const cv::Mat& src, cv::Mat& dst, int size, int threads, cv::Mat* workspace) {
  if (src.empty()) throw InvalidArgument("image is empty");
  if (src.type() != CV_32FC1) {
    throw InvalidArgument("image must be single-channel float32 (CV_32FC1), got OpenCV type " +
                          std::to_string(src.type()));
  }
  if (size < 0 || (size > 1 && size % 2 == 0)) {
    throw InvalidArgument("closing size must be 0, 1 or an odd number of pixels, got " +
                          std::to_string(size));
  }
  if (threads < 0) throw InvalidArgument("threads must be >= 0, got " + std::to_string(threads));
  if (size <= 1) {
    if (dst.data != src.data) src.copyTo(dst);
    return;
  }
  cv::Mat local;
  cv::Mat& dilated = workspace ? *workspace : local;
  dilated.create(src.size(), CV_32FC1);
  filter_square<Max>(src, dilated, size, threads);
  dst.create(src.size(), CV_32FC1);  // keeps src's buffer when dst == src (in-place)
  filter_square<Min>(dilated, dst, size, threads);
}

}  // namespace vtrack::image
