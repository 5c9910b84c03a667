#include "vtrack/models/person_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/image/components.hpp"

namespace vtrack::models {

namespace {

int log2_bin(double value, int bins_per_octave, int bins) {
  return std::clamp(static_cast<int>(std::log2(value) * bins_per_octave), 0, bins - 1);
}

// The value at which the cumulative weight of a log2-binned histogram reaches half its total,
// interpolated linearly in log2 within the bin; 0 for an empty histogram.
double log2_binned_median(const std::vector<double>& histogram, int bins_per_octave) {
  double total = 0.0;
  for (double h : histogram) total += h;
  if (!(total > 0.0)) return 0.0;
  const double half = 0.5 * total;
  double below = 0.0;
  for (std::size_t b = 0; b < histogram.size(); ++b) {
    if (below + histogram[b] >= half && histogram[b] > 0.0) {
      const double frac = (half - below) / histogram[b];
      return std::exp2((static_cast<double>(b) + frac) / bins_per_octave);
    }
    below += histogram[b];
  }
  return std::exp2(static_cast<double>(histogram.size()) / bins_per_octave);
}

// The value at which the cumulative weight of (value, weight) pairs reaches half the total (the
// lower weighted median); 0 when empty. Sorts `pairs`.
double weighted_median(std::vector<std::pair<double, double>>& pairs) {
  if (pairs.empty()) return 0.0;
  std::sort(pairs.begin(), pairs.end());
  double total = 0.0;
  for (const auto& p : pairs) total += p.second;
  double below = 0.0;
  for (const auto& p : pairs) {
    below += p.second;
    if (below >= 0.5 * total) return p.first;
  }
  return pairs.back().first;
}

}  // namespace

double PersonHeightLine::at(double foot_row) const {
  if (!by_row) return intercept;
  return std::clamp(slope * foot_row + intercept, min_height, max_height);
}

ForegroundSizeEstimator::ForegroundSizeEstimator(double half_life, double min_area_fraction,
                                                 double aspect)
    : min_area_fraction_(min_area_fraction), aspect_(aspect) {
  require(half_life > 0.0, "half_life", half_life, "> 0");
  require(min_area_fraction >= 0.0 && min_area_fraction < 1.0, "min_area_fraction",
          min_area_fraction, "in [0, 1)");
  require(aspect > 0.0 && std::isfinite(aspect), "aspect", aspect, "> 0 and finite");
  decay_ = std::isinf(half_life) ? 1.0 : std::exp2(-1.0 / half_life);
  area_by_height_.assign(kHeightBins, 0.0);
  count_.assign(static_cast<std::size_t>(kHeightBins) * kAreaBins, 0.0);
  band_count_.assign(static_cast<std::size_t>(kRowBands) * kHeightBins * kBandAreaBins, 0.0);
}

void ForegroundSizeEstimator::reset() {
  std::fill(area_by_height_.begin(), area_by_height_.end(), 0.0);
  std::fill(count_.begin(), count_.end(), 0.0);
  std::fill(band_count_.begin(), band_count_.end(), 0.0);
  weight_ = 0.0;
  frames_ = 0;
}

void ForegroundSizeEstimator::observe(const cv::Mat& y, float threshold) {
  if (y.empty() || y.type() != CV_32FC1) {
    throw InvalidArgument("y must be a non-empty single-channel float32 image");
  }
  cv::compare(y, threshold, mask_, cv::CMP_LT);
  const int n = image::connected_components(mask_, stats_);
  if (decay_ < 1.0) {
    for (double& a : area_by_height_) a *= decay_;
    for (double& c : count_) c *= decay_;
    for (double& c : band_count_) c *= decay_;
    weight_ *= decay_;
  }
  const double min_area = std::max(min_area_fraction_ * static_cast<double>(y.total()), 1.0);
  for (int i = 1; i < n; ++i) {  // label 0 is the background
    const int* s = stats_.ptr<int>(i);
    const double area = s[cv::CC_STAT_AREA];
    // A component cut by the top or bottom border has lost height (one cut at the sides has not).
    const bool height_cut = s[cv::CC_STAT_TOP] == 0 ||
                            s[cv::CC_STAT_TOP] + s[cv::CC_STAT_HEIGHT] == y.rows;
    if (area < min_area || height_cut) continue;
    const int hb = log2_bin(s[cv::CC_STAT_HEIGHT], kHeightBinsPerOctave, kHeightBins);
    const int ab = log2_bin(area, kAreaBinsPerOctave, kAreaBins);
    area_by_height_[static_cast<std::size_t>(hb)] += area;
    count_[static_cast<std::size_t>(hb) * kAreaBins + static_cast<std::size_t>(ab)] += 1.0;
    // The foot row: the component's last row, as a band of the image height.
    const int foot = s[cv::CC_STAT_TOP] + s[cv::CC_STAT_HEIGHT] - 1;
    const int band = std::min(kRowBands - 1, foot * kRowBands / y.rows);
    const int bab = log2_bin(area, kBandAreaBinsPerOctave, kBandAreaBins);
    band_count_[(static_cast<std::size_t>(band) * kHeightBins + static_cast<std::size_t>(hb)) *
                    kBandAreaBins +
                static_cast<std::size_t>(bab)] += 1.0;
    weight_ += area;
  }
  rows_ = y.rows;
  ++frames_;
}

double ForegroundSizeEstimator::area_weighted_median_height() const {
  return log2_binned_median(area_by_height_, kHeightBinsPerOctave);
}

double ForegroundSizeEstimator::count_median_height(double min_area) const {
  // Area bins from the one holding min_area on (a component of that bin is within 1/8 octave of
  // it: the threshold only has to separate specks from people, so a bin's resolution suffices).
  const int first = log2_bin(std::max(min_area, 1.0), kAreaBinsPerOctave, kAreaBins);
  std::vector<double> by_height(kHeightBins, 0.0);
  for (int hb = 0; hb < kHeightBins; ++hb) {
    const double* row = &count_[static_cast<std::size_t>(hb) * kAreaBins];
    for (int ab = first; ab < kAreaBins; ++ab) by_height[static_cast<std::size_t>(hb)] += row[ab];
  }
  return log2_binned_median(by_height, kHeightBinsPerOctave);
}

double ForegroundSizeEstimator::person_height() const {
  const double anchor = area_weighted_median_height();
  if (!(anchor > 0.0)) return 0.0;
  // The area of a person of height h (see the header for the two passes).
  auto person_area = [this](double h) { return aspect_ * h * h; };
  const double first = count_median_height(person_area(anchor / 3.0));
  if (!(first > 0.0)) return anchor;
  const double second = count_median_height(person_area(first / 2.0));
  return second > 0.0 ? second : first;
}

}  // namespace vtrack::models

namespace vtrack::models {

double ForegroundSizeEstimator::band_median_height(int band, double anchor, double* count) const {
  std::vector<double> by_height(kHeightBins, 0.0);
  // Count median of the band's components whose area is at least min_area (to a bin).
  auto median = [&](double min_area, double* total) {
    const int first = log2_bin(std::max(min_area, 1.0), kBandAreaBinsPerOctave, kBandAreaBins);
    double sum = 0.0;
    for (int hb = 0; hb < kHeightBins; ++hb) {
      const double* row =
          &band_count_[(static_cast<std::size_t>(band) * kHeightBins + hb) * kBandAreaBins];
      double c = 0.0;
      for (int ab = first; ab < kBandAreaBins; ++ab) c += row[ab];
      by_height[static_cast<std::size_t>(hb)] = c;
      sum += c;
    }
    if (total) *total = sum;
    return log2_binned_median(by_height, kHeightBinsPerOctave);
  };
  auto person_area = [this](double h) { return aspect_ * h * h; };
  const double first = median(person_area(anchor / 3.0), nullptr);
  if (!(first > 0.0)) {
    *count = 0.0;
    return 0.0;
  }
  return median(person_area(first / 2.0), count);
}

PersonHeightLine ForegroundSizeEstimator::person_height_line() const {
  PersonHeightLine line;
  const double h = person_height();
  line.intercept = h;
  if (!(h > 0.0) || rows_ < 1) return line;
  // (foot row at the band's centre, band median height, count) of the supported bands.
  struct Point {
    double row, height, count;
  };
  std::vector<Point> points;
  for (int b = 0; b < kRowBands; ++b) {
    double count = 0.0;
    const double m = band_median_height(b, h, &count);
    // A band whose median is under a third of the person height holds no people but specks
    // (see the header: the area floor passes blobs as wide as they are tall).
    if (m >= h / 3.0 && count >= kMinBandCount) {
      points.push_back({(b + 0.5) * rows_ / kRowBands, m, count});
    }
  }
  if (points.size() < 3) return line;
  // Weighted Theil-Sen: the weighted median of the pairwise slopes, then of the intercepts.
  std::vector<std::pair<double, double>> pairs;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size(); ++j) {
      pairs.emplace_back((points[j].height - points[i].height) / (points[j].row - points[i].row),
                         points[i].count * points[j].count);
    }
  }
  const double slope = weighted_median(pairs);
  pairs.clear();
  for (const auto& p : points) pairs.emplace_back(p.height - slope * p.row, p.count);
  const double intercept = weighted_median(pairs);
  const double top = points.front().row, bottom = points.back().row;
  // Not supported: see the header comment.
  if (!(slope > 0.0) || slope * (bottom - top) < 0.1 * h) return line;
  const double h_top = slope * top + intercept, h_bottom = slope * bottom + intercept;
  if (!(h_top > 0.0)) return line;
  line.slope = slope;
  line.intercept = intercept;
  line.min_height = 0.5 * h_top;
  line.max_height = 2.0 * h_bottom;
  line.by_row = true;
  return line;
}

}  // namespace vtrack::models
