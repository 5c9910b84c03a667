#pragma once
// Integral image (summed-area table) of a single-channel image with O(1) rectangle sums.
// The table is computed by cv::integral in double precision, so sums over a whole 768x576 frame
// stay exact to ~1e-10 relative; rectangles are clipped to the image, and a rectangle that is
// empty or wholly outside sums to 0 over an area of 0.
#include <opencv2/core.hpp>

namespace vtrack::image {

// Pixel rectangle: columns [x, x + width), rows [y, y + height).
struct Rect {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
};

// The pixels two rects share (width or height 0 when they share none).
inline Rect intersect(const Rect& a, const Rect& b) {
  const int x0 = a.x > b.x ? a.x : b.x, y0 = a.y > b.y ? a.y : b.y;
  const int x1 = a.x + a.width < b.x + b.width ? a.x + a.width : b.x + b.width;
  const int y1 = a.y + a.height < b.y + b.height ? a.y + a.height : b.y + b.height;
  return Rect{x0, y0, x1 > x0 ? x1 - x0 : 0, y1 > y0 ? y1 - y0 : 0};
}

class IntegralImage {
 public:
  IntegralImage() = default;
  // `image`: non-empty single-channel CV_8U, CV_32F or CV_64F.
  explicit IntegralImage(const cv::Mat& image) { compute(image); }

  // Recomputes the table for a new image, reusing the buffer when the size is unchanged.
  void compute(const cv::Mat& image);

  int rows() const { return table_.rows - 1; }
  int cols() const { return table_.cols - 1; }

  // The part of `rect` inside the image (width/height 0 when nothing is inside).
  Rect clip(const Rect& rect) const;
  // Sum of the pixels in the clipped rectangle.
  double sum(const Rect& rect) const;
  // Number of pixels in the clipped rectangle.
  long long area(const Rect& rect) const;

 private:
  cv::Mat table_;  // (rows + 1) x (cols + 1), CV_64F, table_(r, c) = sum of image[0:r, 0:c]
};

}  // namespace vtrack::image
