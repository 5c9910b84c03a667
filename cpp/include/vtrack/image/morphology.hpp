#pragma once
// Greyscale morphology with a square structuring element on float images.
#include <opencv2/core.hpp>

namespace vtrack::image {

// Morphological closing (dilation = max filter, then erosion = min filter) of a CV_32FC1 image
// with a size x size square centred on each pixel; pixels outside the image are ignored, as in
// cv::morphologyEx with its default border, whose result this equals exactly. size 0 or 1
// copies the image. In-place use (dst == src) is allowed. InvalidArgument for an empty or
// non-CV_32FC1 image or a size that is negative or even (other than 0).
// threads: 0 = OpenCV's pool, 1 = calling thread, T > 1 = T row stripes on the pool.
// workspace: optional buffer for the intermediate dilation (reused across calls to avoid an
// allocation per frame); it must not alias src or dst.
void close_square(const cv::Mat& src, cv::Mat& dst, int size, int threads = 0,
                  cv::Mat* workspace = nullptr);

}  // namespace vtrack::image
