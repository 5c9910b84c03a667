#include "vtrack/image/morphology.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "parallel_rows.hpp"
#include "vtrack/core/errors.hpp"

namespace vtrack::image {
namespace {

struct Max {
  float operator()(float a, float b) const { return std::max(a, b); }
  static float identity() { return -std::numeric_limits<float>::infinity(); }
};
struct Min {
  float operator()(float a, float b) const { return std::min(a, b); }
  static float identity() { return std::numeric_limits<float>::infinity(); }
};

// column[x] = Op over the rows y0..y1 of src at column x. With a compile-time count of rows
// (kRows > 0, the window inside the image) the loop over the rows unrolls and x vectorises with
// the running value in a register; kRows = 0 is the general loop for windows clipped by a border.
template <class Op, int kRows>
void vertical(const cv::Mat& src, int y0, int y1, float* column) {
  const Op op;
  const int cols = src.cols;
  if constexpr (kRows > 0) {
    const float* in[kRows];
    for (int k = 0; k < kRows; ++k) in[k] = src.ptr<float>(y0 + k);
    for (int x = 0; x < cols; ++x) {
      float v = in[0][x];
      for (int k = 1; k < kRows; ++k) v = op(v, in[k][x]);
      column[x] = v;
    }
  } else {
    std::copy_n(src.ptr<float>(y0), cols, column);
    for (int yy = y0 + 1; yy <= y1; ++yy) {
      const float* in = src.ptr<float>(yy);
      for (int x = 0; x < cols; ++x) column[x] = op(column[x], in[x]);
    }
  }
}

// out[x] = Op over padded[x .. x + 2 radius]: padded holds the row with `radius` identity
// elements on each side, so the border pixels' windows need no clipping (an identity element
// changes nothing, which is what "pixels outside the image are ignored" means).
// kRadius > 0 unrolls the window as vertical does; kRadius = 0 makes a pass over the row per
// window element instead, which vectorises whatever the radius.
template <class Op, int kRadius>
void horizontal(const float* padded, int cols, int radius, float* out) {
  const Op op;
  if constexpr (kRadius > 0) {
    for (int x = 0; x < cols; ++x) {
      float v = padded[x];
      for (int j = 1; j <= 2 * kRadius; ++j) v = op(v, padded[x + j]);
      out[x] = v;
    }
  } else {
    std::copy_n(padded, cols, out);
    for (int j = 1; j <= 2 * radius; ++j) {
      for (int x = 0; x < cols; ++x) out[x] = op(out[x], padded[x + j]);
    }
  }
}

// dst = Op over the size x size square around each pixel of src (src and dst distinct), pixels
// outside the image ignored. Separable: the vertical Op of the window's rows into a padded row
// buffer, then the horizontal Op along it. kRadius > 0 fixes the radius at compile time (the
// sizes the trackers use), which lets both passes keep the running value in registers rather
// than make a pass over the row buffer per window row (benchmarks/cpp/morphology_micro.cpp);
// kRadius = 0 serves any radius.
template <class Op, int kRadius>
void filter_square(const cv::Mat& src, cv::Mat& dst, int radius, int threads) {
  const int rows = src.rows, cols = src.cols;
  detail::for_rows(rows, threads, [&](int begin, int end) {
    std::vector<float> padded(static_cast<std::size_t>(cols + 2 * radius), Op::identity());
    float* column = padded.data() + radius;
    for (int y = begin; y < end; ++y) {
      const int y0 = std::max(0, y - radius), y1 = std::min(rows - 1, y + radius);
      if (kRadius > 0 && y1 - y0 == 2 * kRadius) {
        vertical<Op, 2 * kRadius + 1>(src, y0, y1, column);
      } else {
        vertical<Op, 0>(src, y0, y1, column);
      }
      horizontal<Op, kRadius>(padded.data(), cols, radius, dst.ptr<float>(y));
    }
  });
}

// filter_square with the radius fixed at compile time where a tracker's closing uses it.
template <class Op>
void filter_square(const cv::Mat& src, cv::Mat& dst, int size, int threads) {
  const int radius = size / 2;
  switch (radius) {
    case 1: return filter_square<Op, 1>(src, dst, radius, threads);
    case 2: return filter_square<Op, 2>(src, dst, radius, threads);
    case 3: return filter_square<Op, 3>(src, dst, radius, threads);
    case 4: return filter_square<Op, 4>(src, dst, radius, threads);
    case 5: return filter_square<Op, 5>(src, dst, radius, threads);
    default: return filter_square<Op, 0>(src, dst, radius, threads);
  }
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
