#include "vtrack/models/person_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"

namespace vtrack::models {

ForegroundSizeEstimator::ForegroundSizeEstimator(double half_life, double min_area_fraction)
    : min_area_fraction_(min_area_fraction) {
  require(half_life > 0.0, "half_life", half_life, "> 0");
  require(min_area_fraction >= 0.0 && min_area_fraction < 1.0, "min_area_fraction",
          min_area_fraction, "in [0, 1)");
  decay_ = std::isinf(half_life) ? 1.0 : std::exp2(-1.0 / half_life);
  histogram_.assign(kBinsPerOctave * kOctaves, 0.0);
}

void ForegroundSizeEstimator::reset() {
  std::fill(histogram_.begin(), histogram_.end(), 0.0);
  weight_ = 0.0;
  frames_ = 0;
}

void ForegroundSizeEstimator::observe(const cv::Mat& y, float threshold) {
  if (y.empty() || y.type() != CV_32FC1) {
    throw InvalidArgument("y must be a non-empty single-channel float32 image");
  }
  cv::compare(y, threshold, mask_, cv::CMP_LT);
  const int n = cv::connectedComponentsWithStats(mask_, labels_, stats_, centroids_, 8, CV_32S);
  if (decay_ < 1.0) {
    for (double& h : histogram_) h *= decay_;
    weight_ *= decay_;
  }
  const double min_area = min_area_fraction_ * static_cast<double>(y.total());
  const int bins = static_cast<int>(histogram_.size());
  for (int i = 1; i < n; ++i) {  // label 0 is the background
    const double area = stats_.at<int>(i, cv::CC_STAT_AREA);
    if (area < std::max(min_area, 1.0)) continue;
    const double height = stats_.at<int>(i, cv::CC_STAT_HEIGHT);
    const int bin = std::clamp(static_cast<int>(std::log2(height) * kBinsPerOctave), 0, bins - 1);
    histogram_[static_cast<std::size_t>(bin)] += area;
    weight_ += area;
  }
  ++frames_;
}

double ForegroundSizeEstimator::median_height() const {
  double total = 0.0;
  for (double h : histogram_) total += h;
  if (!(total > 0.0)) return 0.0;
  const double half = 0.5 * total;
  double below = 0.0;
  for (std::size_t b = 0; b < histogram_.size(); ++b) {
    if (below + histogram_[b] >= half && histogram_[b] > 0.0) {
      // Linear within the bin's log2 range [b, b + 1) / kBinsPerOctave.
      const double frac = (half - below) / histogram_[b];
      return std::exp2((static_cast<double>(b) + frac) / kBinsPerOctave);
    }
    below += histogram_[b];
  }
  return std::exp2(static_cast<double>(histogram_.size()) / kBinsPerOctave);
}

}  // namespace vtrack::models
