#pragma once
// The person a foreground tracker looks for: the multi-Bernoulli track-before-detect filter and
// the re-clustering SIR share it. Its height is given in pixels or learnt from the scene's own
// foreground (models::ForegroundSizeEstimator), its width a fixed fraction of the height; the
// box each tracker reports is calibrated to the annotation convention by a scale and a shift.
// Both are beyond the papers: mb-tbd Section 4 and particle-filters-human-vehicle §2.2 draw sizes
// from a fixed prior in pixels, which fits one camera at one resolution and one distance.
#include <opencv2/core.hpp>

#include "vtrack/core/parameters.hpp"
#include "vtrack/filters/tracks.hpp"
#include "vtrack/models/person_size.hpp"

namespace vtrack::filters {

struct PersonSizeParams {
  // The mean person height h: pixels, or 0 (default) to learn it as size_from_foreground x the
  // person height of the foreground components, with older frames forgotten with a half-life of
  // size_half_life observed frames (0: never forget; a camera that zooms needs one). Until the
  // components seen add up to the area of one person of the current prior, h = size_initial x
  // the image height (85 / 576: PETS09-S2L1's people).
  double height_mean = 0.0;
  // Mean width / mean height: PETS09-S2L1's MOT15 GT people are 30 x 85 px on average. The width
  // is not learnt: people walking side by side merge into one wide foreground component far more
  // often than into a tall one.
  double size_aspect = 0.35;
  // A foreground component is a little shorter than the annotated box around the person (feet
  // and head blend into the background). Tuned on PETS09-S2L1 frames 1-397 at 768 x 576
  // (benchmarks/person_size.py --sweep holds the sweep and the held-out figures).
  double size_from_foreground = 1.06;
  double size_initial = 0.15;
  double size_half_life = 0.0;
  // Standard deviation of new sizes as a fraction of the mean (PETS09's GT: 7.5 / 30 and 19 / 85),
  // and the range sizes are clamped to after each prediction, as fractions of the mean: the
  // maximum keeps a box or an ellipse from spanning two people walking side by side.
  double size_std = 0.25;
  double size_min = 0.45;
  double size_max = 2.0;

  static const core::ParameterTable<PersonSizeParams>& table();
};

// InvalidArgument naming the parameter and its value.
void validate(const PersonSizeParams& params);

// The reported box: the tracker's own box (w x h about its centre) scaled about its centre by
// (box_scale_w, box_scale_h) and its centre moved by (box_offset_x w, box_offset_y h). Only the
// output changes, never the filter's state. Each tracker sets its own defaults (the medians of
// the fits of benchmarks/pets09.py's calibration); 1, 1, 0, 0 reports the tracker's own box.
// With box_clip the reported box is then clipped to the image, as annotations box what is in
// view (PETS09-S2L1's MOT15 boxes all lie within the image's columns): the scaled box of a
// person half out of view reaches beyond the border, by more the larger the people are relative
// to the image (benchmarks/mb_perspective.py, CROPS).
struct BoxCalibrationParams {
  double box_scale_w = 1.0;
  double box_scale_h = 1.0;
  double box_offset_x = 0.0;
  double box_offset_y = 0.0;
  bool box_clip = false;

  static const core::ParameterTable<BoxCalibrationParams>& table();
};

void validate(const BoxCalibrationParams& params);

// The box of the whole person behind a tracker's box cut by the image border: a side within a
// pixel of the border is moved out until the box is at least `person` wide (left, right) or
// tall (top, bottom), the opposite side kept. A box away from the border, or already as large,
// is returned as it is. Why: the filter's box covers the part of a person in view, and the
// calibration's margin is a share of the box it scales, whereas annotations box the whole person
// with a margin and clip that to the image; the margin on the side in view must be the whole
// person's (PETS09-S2L1's central crop: the boxes of people cut by the left border were 0.41 of
// the annotation's width where the match failed).
cv::Rect2d whole_person_box(const cv::Rect2d& box, const cv::Size2d& person, const cv::Size& image);

// What both foreground trackers report: sets t's box (x, y, w, h) to the calibration of
// whole_person_box(box, person, image), clipped to the image with box_clip. Returns false when
// nothing of the box is left in the image (then the track is not reported).
bool set_calibrated_box(const BoxCalibrationParams& calibration, const cv::Rect2d& box,
                        const cv::Size2d& person, const cv::Size& image, TrackEstimate& t);

// The person height in force: height_mean when given, else size_initial x the image height
// until the foreground has shown enough evidence, then the learnt height.
class PersonHeight {
 public:
  // params must be valid (validate); image_height >= 1.
  PersonHeight(const PersonSizeParams& params, int image_height);

  double height() const { return height_; }
  // Whether height() comes from the scene's foreground.
  bool learnt() const { return learnt_; }
  // The person height at a foot row (px): size_from_foreground x the learnt perspective line
  // (models::PersonHeightLine) once learnt and supported by the data, else height().
  double height_at_foot(double foot_row) const {
    return line_.by_row ? params_.size_from_foreground * line_.at(foot_row) : height_;
  }
  // Whether height_at_foot follows the row.
  bool by_row() const { return line_.by_row; }
  // The smallest person height the line was fitted on (its value at the top row band where
  // people were seen, times size_from_foreground); 0 unless by_row. height_at_foot goes down
  // to half of it above those rows.
  double smallest_seen() const {
    return line_.by_row ? 2.0 * params_.size_from_foreground * line_.min_height : 0.0;
  }
  // Whether observe also fits the line (off by default: it costs a pass over the row bands'
  // histograms per frame, which only size_by_row uses).
  void set_fit_line(bool on) { fit_line_ = on; }
  // Whether a line must also be well supported (PersonHeightLine::well_supported) to be used.
  void set_require_well_supported_line(bool on) { require_well_supported_ = on; }

  // Counts the foreground components of y (CV_32FC1, y < threshold is foreground). Returns true
  // when height() changed. The initial guess stays until the decayed area of the components
  // counted reaches person_area px^2 (one person of the current prior: the first frames of a
  // video with people in view; a scene without motion keeps the initial guess). A height given
  // in pixels never changes.
  bool observe(const cv::Mat& y, float threshold, double person_area);

 private:
  const PersonSizeParams params_;
  models::ForegroundSizeEstimator estimator_;
  double height_;
  bool learnt_ = false;
  models::PersonHeightLine line_;
  bool fit_line_ = false;
  bool require_well_supported_ = false;
};

}  // namespace vtrack::filters
