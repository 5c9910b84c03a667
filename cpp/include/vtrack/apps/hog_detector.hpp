#pragma once
// OpenCV's HOG people detector (Dalal & Triggs 2005, the default 64x128 people SVM of
// cv::HOGDescriptor::getDefaultPeopleDetector), the RGB detector of
// rgbd-glmb-switching-observation.txt (Section 4: "people are detected in the RGB image with a
// HOG detector"), wrapped with documented parameters so the CLI, config files and Python share
// them.
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/objdetect.hpp>

#include "vtrack/core/parameters.hpp"

namespace vtrack::apps {

struct HogParams {
  // SVM margin a window needs to count as a hit (cv::HOGDescriptor::detectMultiScale's
  // hitThreshold). 0 is OpenCV's default; the margin is the returned score.
  double hit_threshold = 0.0;
  // Window step in pixels, both axes (a multiple of the 8-px cell; OpenCV's default is the block
  // stride, 8). Larger is faster and misses more.
  int win_stride = 8;
  // Pixels added around the image on each side, so people at the border still fill a window.
  int padding = 8;
  // Ratio between pyramid levels (OpenCV's default is 1.05). 1.1 halves the number of levels,
  // which pays for the upscaled frame below.
  double scale = 1.1;
  // Resize factor applied to the frame before detection (boxes are mapped back; 1 = off). The
  // people SVM's window is 64x128 with the person ~48x96 inside it, so at 1 a person under ~96 px
  // tall is never found; in PETS09-S2L1 (people 53-153 px tall) the default 1.5 finds 33 of the
  // 36 people of frames 50, 100, ..., 300 with 34 boxes, against 19 of 36 at upscale 1 and scale
  // 1.05 (OpenCV's defaults), at 0.40 s instead of 0.21 s a 768x576 frame on this machine.
  double upscale = 1.5;
  // Minimum number of overlapping hits a grouped detection needs (detectMultiScale's
  // finalThreshold / groupRectangles' groupThreshold, OpenCV's default 2).
  int group_threshold = 2;
  // Grouped detections scoring below this are dropped.
  double min_score = 0.0;
  // Size of the returned box relative to the detection window, about the window's centre. The
  // people SVM was trained on 64x128 windows with the person ~48x96 inside (INRIA), so 0.75 gives
  // the person's box, which is what MOT ground truth annotates; 1 returns the raw window. On
  // PETS09-S2L1 frames 1-397 the raw windows overlap the GT boxes by IoU < 0.5 almost always (GLMB
  // MOTA -0.93, IDF1 0.03); at 0.75: MOTA 0.73, IDF1 0.60 (benchmarks/detections.py).
  double person_fraction = 0.75;

  static const core::ParameterTable<HogParams>& table();
};

// InvalidArgument naming the parameter and its value for an out-of-range one.
void validate(const HogParams& params);

struct ScoredBox {
  double x = 0, y = 0, w = 0, h = 0;  // top-left corner and size, pixels
  double score = 0;                   // SVM margin of the best window of the group
};

class HogPeopleDetector {
 public:
  explicit HogPeopleDetector(HogParams params = {});
  // People in an 8-bit BGR (or grey) frame, best score first. InvalidArgument for an empty frame,
  // another type, or a frame smaller than min_frame_size(). Not thread-safe on one instance
  // (OpenCV's HOG keeps scratch state); use one detector per thread.
  std::vector<ScoredBox> detect(const cv::Mat& frame) const;
  // The smallest frame (width, height) detect() takes: after `upscale` it must hold one 64x128
  // detection window (OpenCV's HOG reads outside smaller images: a crash, not "no people").
  cv::Size min_frame_size() const;
  // InvalidArgument naming both sizes unless a width x height frame is at least min_frame_size().
  void check_frame_size(int width, int height) const;
  const HogParams& params() const { return params_; }

 private:
  HogParams params_;
  cv::HOGDescriptor hog_;
};

}  // namespace vtrack::apps
