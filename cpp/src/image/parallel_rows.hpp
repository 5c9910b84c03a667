#pragma once
// Private helper of the image layer: run a body over row ranges with the `threads` convention of
// the public parameter structs (0 = OpenCV's pool, 1 = the calling thread, T > 1 = T stripes on
// OpenCV's pool). Each row is processed by exactly one call, whatever the split, so a body that
// computes rows independently gives identical results for every thread count.
#include <opencv2/core.hpp>

namespace vtrack::image::detail {

template <class Body>  // Body: void(int row_begin, int row_end)
void for_rows(int rows, int threads, const Body& body) {
  if (threads == 1 || rows < 2) {
    body(0, rows);
    return;
  }
  cv::parallel_for_(
      cv::Range(0, rows), [&body](const cv::Range& range) { body(range.start, range.end); },
      threads == 0 ? -1.0 : static_cast<double>(threads));
}

}  // namespace vtrack::image::detail
