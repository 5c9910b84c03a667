#include "vtrack/image/components.hpp"

#include <algorithm>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"

namespace vtrack::image {

int connected_components(const cv::Mat& mask, cv::Mat& labels, cv::Mat& stats) {
  if (mask.empty() || mask.type() != CV_8UC1) {
    throw InvalidArgument("mask must be a non-empty CV_8UC1 image");
  }
  const int n = cv::connectedComponents(mask, labels, 8, CV_32S);
  // Bounding boxes as (left, top, right, bottom) while counting, then as OpenCV's width/height.
  stats.create(n, cv::CC_STAT_MAX, CV_32S);
  stats.setTo(0);
  for (int i = 1; i < n; ++i) {
    int* s = stats.ptr<int>(i);
    s[cv::CC_STAT_LEFT] = s[cv::CC_STAT_TOP] = std::numeric_limits<int>::max();
    s[cv::CC_STAT_WIDTH] = s[cv::CC_STAT_HEIGHT] = -1;
  }
  for (int r = 0; r < mask.rows; ++r) {
    const uchar* m = mask.ptr<uchar>(r);
    const int* l = labels.ptr<int>(r);
    for (int c = 0; c < mask.cols; ++c) {
      if (!m[c]) continue;
      int* s = stats.ptr<int>(l[c]);
      s[cv::CC_STAT_LEFT] = std::min(s[cv::CC_STAT_LEFT], c);
      s[cv::CC_STAT_WIDTH] = std::max(s[cv::CC_STAT_WIDTH], c);  // the right edge for now
      s[cv::CC_STAT_TOP] = std::min(s[cv::CC_STAT_TOP], r);
      s[cv::CC_STAT_HEIGHT] = r;  // rows come in order: the last one is the bottom
      ++s[cv::CC_STAT_AREA];
    }
  }
  for (int i = 1; i < n; ++i) {
    int* s = stats.ptr<int>(i);
    s[cv::CC_STAT_WIDTH] -= s[cv::CC_STAT_LEFT] - 1;
    s[cv::CC_STAT_HEIGHT] -= s[cv::CC_STAT_TOP] - 1;
  }
  return n;
}

}  // namespace vtrack::image
