#pragma once
// Test helper for the foreground trackers: people rendered into a background-subtracted image y
// (1 = background) with one shape at every size, so a likelihood or a tracker that fits people
// alike at every size can be checked against the rendering.
#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

namespace people_scene {

// A person of w x h centred at (cx, cy): y = min(y, 1 - g(dx / (w/2)) g(dy / (h/2))), with
// g(t) = 1 for |t| <= 0.5, falling linearly to 0 at |t| = 1.1: a dark core and a soft border.
inline void render_person(cv::Mat& y, double cx, double cy, double w, double h) {
  auto g = [](double t) { return std::clamp((1.1 - std::fabs(t)) / 0.6, 0.0, 1.0); };
  const int r0 = std::max(0, int(std::floor(cy - 0.55 * h)));
  const int r1 = std::min(y.rows, int(std::ceil(cy + 0.55 * h)) + 1);
  const int c0 = std::max(0, int(std::floor(cx - 0.55 * w)));
  const int c1 = std::min(y.cols, int(std::ceil(cx + 0.55 * w)) + 1);
  for (int r = r0; r < r1; ++r)
    for (int c = c0; c < c1; ++c) {
      const double f = g((c + 0.5 - cx) / (0.5 * w)) * g((r + 0.5 - cy) / (0.5 * h));
      y.at<float>(r, c) = std::min(y.at<float>(r, c), float(1.0 - f));
    }
}

}  // namespace people_scene
