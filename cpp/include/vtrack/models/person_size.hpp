#pragma once
// How tall the people of a scene are, learnt from the scene's own foreground (beyond the mb-tbd
// paper, whose Section 4 draws birth sizes from a fixed prior: a fixed prior in pixels fits one
// camera at one resolution and one distance).
//
// Each observed frame's foreground mask (y < threshold on the background-subtracted image y) is
// split into 8-connected components; every component at least min_area_fraction of the image
// adds its area to a histogram of log2 component heights (32 bins per octave, 1 to 16384 px).
// The estimate is the area-weighted median height. Area weighting makes it robust to noise
// specks (many, but small: on PETS09-S2L1's KDE output 14566 components of which 70% are under
// 50 px carry 3% of the area) and the median to the minority of components that are a person's
// fragment or a group. Side-by-side groups barely change heights, which is why the height, not
// the width, is learnt (the tracker takes the width from a fixed aspect ratio). Older
// observations are forgotten with a half-life (in observed frames), so the estimate follows a
// scene whose people change size (a camera that zooms) while staying steady frame to frame.
//
// Measured on PETS09-S2L1 (KDE y, benchmarks/pets09.py): area-weighted median 93 px over all
// frames (the MOT15 GT's mean person height is 85 px); 87-90 px over the first 10-50 frames;
// resized 0.5x / 1.5x: 42-44 / 130-136 px; the same people cropped: 86-90 px.
#include <vector>

#include <opencv2/core.hpp>

namespace vtrack::models {

class ForegroundSizeEstimator {
 public:
  // half_life > 0 (observed frames; infinity = never forget); min_area_fraction in [0, 1).
  // InvalidArgument naming the argument otherwise.
  explicit ForegroundSizeEstimator(double half_life = 100.0, double min_area_fraction = 1e-4);

  // Adds the foreground components of y (CV_32FC1, values in [0, 1], 1 = background): pixels
  // with y < threshold are foreground.
  void observe(const cv::Mat& y, float threshold = 0.5f);
  // Area-weighted median height of the components seen (px), interpolated within its bin; 0
  // before any component has been seen.
  double median_height() const;
  // The decayed total area (px) of the components seen: how much evidence the estimate rests on.
  double weight() const { return weight_; }
  // Number of frames observed.
  long long frames() const { return frames_; }
  void reset();

 private:
  static constexpr int kBinsPerOctave = 32;
  static constexpr int kOctaves = 14;
  double decay_;
  double min_area_fraction_;
  std::vector<double> histogram_;
  double weight_ = 0.0;
  long long frames_ = 0;
  cv::Mat mask_, labels_, stats_, centroids_;
};

}  // namespace vtrack::models
