#pragma once
// The colour histograms of tracks for TrackManager's appearance (track_management.hpp; issue 12):
// the part-based paper's HSV histogram (section 3.1, 16 x 4 x 4 bins, image/color_histogram.hpp)
// of the pixels of a track's box that are foreground in the background-subtracted image y
// (y < threshold), so that the background around a person, most of a box, does not make every
// person's colours alike.
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/filters/track_management.hpp"
#include "vtrack/image/color_histogram.hpp"

namespace vtrack::filters {

// InvalidArgument naming `frame` unless it is an 8-bit BGR image (CV_8UC3) of y's size.
void check_colour_frame(const cv::Mat& frame, const cv::Mat& y);

class ForegroundColour {
 public:
  ForegroundColour() = default;

  // out[k]: the normalised histogram of the pixels of boxes[k] (x, y, w, h) with y < threshold
  // (frame and y as check_colour_frame accepts); empty when fewer than min_fraction of the box's
  // pixels are foreground (a box on a speck of noise, or mostly outside the frame).
  void measure(const cv::Mat& frame, const cv::Mat& y, float threshold,
               const std::vector<Eigen::Vector4f>& boxes, std::vector<ColourHistogram>& out);

  // The share of a box's pixels below which it has no histogram.
  static constexpr double min_fraction = 0.1;

 private:
  image::HsvBinImage bins_;
  std::vector<double> counts_;
};

}  // namespace vtrack::filters
