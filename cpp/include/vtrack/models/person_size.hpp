#pragma once
// How tall the people of a scene are, learnt from the scene's own foreground (beyond the mb-tbd
// paper, whose Section 4 draws birth sizes from a fixed prior: a fixed prior in pixels fits one
// camera at one resolution and one distance).
//
// Each observed frame's foreground mask (y < threshold on the background-subtracted image y) is
// split into 8-connected components. A component touching the image's top or bottom border is
// skipped (the border cut its height; one entering at a side has its full height); the others, at
// least min_area_fraction of the image, are counted in a histogram of (log2 height, log2 area).
//
// The estimate is the median height of the components big enough to be a whole person, counted
// once each. Counting, not area-weighting: a group of people merged into one component covers
// the area of all of them, so in a crowd an area-weighted median is a group's height, while
// single people are the most numerous components once a crowd spreads. "Big enough" drops noise
// specks and fragments, which are far more numerous than people: an area of at least that of a
// person (aspect x height^2) half as tall as h, where h is the count median of a first pass whose
// floor is a person a third as tall as the area-weighted median height (which groups bias high,
// hence the third). benchmarks/person_size.py measures this statistic against the area-weighted
// median on PETS09-S2L1 and its variants and on synthetic crowds. No statistic of the foreground
// sees single people in frames where there are none: while a crowd enters as one blob the
// estimate is a group's height.
//
// Older observations are forgotten with a half-life (in observed frames), so the estimate can
// follow a scene whose people change size (a camera that zooms).
//
// Perspective (person_height_line): a camera without roll above a ground plane sees a person's
// height grow linearly with the image row of the feet below the horizon, h(y_foot) = a y_foot + b
// (the pinhole projection of a vertical segment standing on the plane; zero at the horizon). The
// same counts are kept per band of foot rows (the component's bottom row; kRowBands bands of the
// image height), each band's height is the two-pass count median above (the first floor from the
// whole image's area-weighted median, so a band of far people is not floored by near ones), and
// a band whose median is under a third of person_height() is left out: the area floor passes
// blobs as wide as they are tall, and the specks of walls, windows and tree tops above the
// people (PETS09 below 768 x 576: at 0.6x they made the slope 0.31 against the annotations' 0.23
// and the far people half their height) are no people of the scene. The line is the weighted
// Theil-Sen fit through the bands' medians (median of pairwise slopes, each pair weighted by the
// product of the bands' counts; a third of the bands can be groups or noise without moving it). It falls back to the constant person_height() when the data do not
// support a slope: fewer than three bands with min_band_count components each, a slope that is
// not positive (the horizon above the people: any camera looking down), or a line that changes
// the height by less than a tenth over the rows where people were seen (an overhead camera).
#include <vector>

#include <opencv2/core.hpp>

namespace vtrack::models {

// h(y_foot) = slope y_foot + intercept (px), clamped to [min_height, max_height]: the line's
// values at the ends of the rows where people were seen, halved and doubled (it is not
// extrapolated beyond that, e.g. to zero at the horizon). by_row false: the constant
// person_height() (slope 0).
struct PersonHeightLine {
  double slope = 0.0, intercept = 0.0;
  double min_height = 0.0, max_height = 0.0;
  bool by_row = false;
  double at(double foot_row) const;
};

class ForegroundSizeEstimator {
 public:
  static constexpr int kRowBands = 16;
  // A band counts in the line fit once it holds this many (decayed) person-sized components.
  static constexpr double kMinBandCount = 3.0;

  // half_life > 0 (observed frames; infinity = never forget); min_area_fraction in [0, 1);
  // aspect > 0 (a person's width / height, for the area a whole person covers). InvalidArgument
  // naming the argument otherwise.
  explicit ForegroundSizeEstimator(double half_life = 100.0, double min_area_fraction = 1e-4,
                                   double aspect = 0.35);

  // Adds the foreground components of y (CV_32FC1, values in [0, 1], 1 = background): pixels
  // with y < threshold are foreground.
  void observe(const cv::Mat& y, float threshold = 0.5f);
  // The height of one person (px; see the header comment), within a bin of 1/16 octave (4.4 %);
  // 0 before any component has been seen.
  double person_height() const;
  // The person height as a function of the foot row (see the header comment); the constant
  // person_height() (by_row false) when the data do not support a slope.
  PersonHeightLine person_height_line() const;
  // The decayed total area (px) of the components counted: how much evidence the estimate rests
  // on.
  double weight() const { return weight_; }
  // Number of frames observed.
  long long frames() const { return frames_; }
  void reset();

 private:
  static constexpr int kHeightBinsPerOctave = 16;
  static constexpr int kAreaBinsPerOctave = 8;
  static constexpr int kHeightBins = kHeightBinsPerOctave * 14;  // 1 to 16384 px
  static constexpr int kAreaBins = kAreaBinsPerOctave * 28;      // 1 to 2^28 px
  // Per row band, coarser areas (the floor only separates specks from people).
  static constexpr int kBandAreaBinsPerOctave = 2;
  static constexpr int kBandAreaBins = kBandAreaBinsPerOctave * 28;
  // Median height of the components whose area is at least min_area, counted once each (0 if
  // there are none).
  double count_median_height(double min_area) const;
  double area_weighted_median_height() const;
  // Two-pass count median of one row band, the first floor from `anchor` (see the header).
  double band_median_height(int band, double anchor, double* count) const;

  double decay_;
  double min_area_fraction_;
  double aspect_;
  std::vector<double> area_by_height_;  // [height bin]: the components' summed area
  std::vector<double> count_;           // [height bin * kAreaBins + area bin]
  // [(band * kHeightBins + height bin) * kBandAreaBins + area bin]
  std::vector<double> band_count_;
  int rows_ = 0;  // image height of the last frame observed (bands are fractions of it)
  double weight_ = 0.0;
  long long frames_ = 0;
  cv::Mat mask_, stats_;
};

}  // namespace vtrack::models
