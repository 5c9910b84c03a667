#include "vtrack/filters/person_prior.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vtrack/core/errors.hpp"

namespace vtrack::filters {

const core::ParameterTable<PersonSizeParams>& PersonSizeParams::table() {
  using P = PersonSizeParams;
  static const auto table = core::ParameterTable<P>()
                                .add("height_mean", &P::height_mean)
                                .add("size_aspect", &P::size_aspect)
                                .add("size_from_foreground", &P::size_from_foreground)
                                .add("size_initial", &P::size_initial)
                                .add("size_half_life", &P::size_half_life)
                                .add("size_std", &P::size_std)
                                .add("size_min", &P::size_min)
                                .add("size_max", &P::size_max);
  return table;
}

void validate(const PersonSizeParams& p) {
  require(std::isfinite(p.height_mean) && p.height_mean >= 0.0, "height_mean", p.height_mean,
          ">= 0 (0: learnt)");
  require_positive("size_aspect", p.size_aspect);
  require_positive("size_from_foreground", p.size_from_foreground);
  require(p.size_initial > 0.0 && p.size_initial <= 1.0, "size_initial", p.size_initial,
          "in (0, 1]");
  require(std::isfinite(p.size_half_life) && p.size_half_life >= 0.0, "size_half_life",
          p.size_half_life, ">= 0 (0: never forget)");
  require(std::isfinite(p.size_std) && p.size_std >= 0.0, "size_std", p.size_std, ">= 0");
  require(p.size_min > 0.0 && p.size_min <= 1.0, "size_min", p.size_min, "in (0, 1]");
  require(std::isfinite(p.size_max) && p.size_max >= 1.0, "size_max", p.size_max,
          ">= 1 and finite");
}

const core::ParameterTable<BoxCalibrationParams>& BoxCalibrationParams::table() {
  using P = BoxCalibrationParams;
  static const auto table = core::ParameterTable<P>()
                                .add("box_scale_w", &P::box_scale_w)
                                .add("box_scale_h", &P::box_scale_h)
                                .add("box_offset_x", &P::box_offset_x)
                                .add("box_offset_y", &P::box_offset_y)
                                .add("box_clip", &P::box_clip);
  return table;
}

void validate(const BoxCalibrationParams& p) {
  require_positive("box_scale_w", p.box_scale_w);
  require_positive("box_scale_h", p.box_scale_h);
  require(std::isfinite(p.box_offset_x), "box_offset_x", p.box_offset_x, "finite");
  require(std::isfinite(p.box_offset_y), "box_offset_y", p.box_offset_y, "finite");
}

namespace {

// One axis of whole_person_box: the interval [start, start + length) within a pixel of 0 or of
// `extent` grows to `size` away from that border.
void grow_out_of_border(double& start, double& length, double size, double extent) {
  if (length >= size) return;
  if (start <= 1.0) {
    start += length - size;
    length = size;
  } else if (start + length >= extent - 1.0) {
    length = size;
  }
}

}  // namespace

cv::Rect2d whole_person_box(const cv::Rect2d& box, const cv::Size2d& person, const cv::Size& image) {
  cv::Rect2d whole = box;
  grow_out_of_border(whole.x, whole.width, person.width, image.width);
  grow_out_of_border(whole.y, whole.height, person.height, image.height);
  return whole;
}

bool set_calibrated_box(const BoxCalibrationParams& c, const cv::Rect2d& box, const cv::Size2d& person,
                        const cv::Size& image, TrackEstimate& t) {
  const cv::Rect2d whole = whole_person_box(box, person, image);
  t.w = whole.width * c.box_scale_w;
  t.h = whole.height * c.box_scale_h;
  const double cx = whole.x + 0.5 * whole.width, cy = whole.y + 0.5 * whole.height;
  t.x = cx + c.box_offset_x * whole.width - 0.5 * t.w;
  t.y = cy + c.box_offset_y * whole.height - 0.5 * t.h;
  if (!c.box_clip) return true;
  const double x1 = std::min(t.x + t.w, double(image.width));
  const double y1 = std::min(t.y + t.h, double(image.height));
  t.x = std::max(t.x, 0.0);
  t.y = std::max(t.y, 0.0);
  t.w = std::max(x1 - t.x, 0.0);
  t.h = std::max(y1 - t.y, 0.0);
  return t.w > 0.0 && t.h > 0.0;
}

PersonHeight::PersonHeight(const PersonSizeParams& params, int image_height)
    : params_(params),
      estimator_(params.size_half_life > 0.0 ? params.size_half_life
                                             : std::numeric_limits<double>::infinity(),
                 1e-4, params.size_aspect),
      height_(params.height_mean > 0.0 ? params.height_mean
                                       : params.size_initial * image_height) {}

bool PersonHeight::observe(const cv::Mat& y, float threshold, double person_area) {
  if (params_.height_mean > 0.0) return false;  // given in pixels
  estimator_.observe(y, threshold);
  if (!learnt_ && estimator_.weight() < person_area) return false;
  const double h = params_.size_from_foreground * estimator_.person_height();
  if (!(h > 0.0)) return false;
  learnt_ = true;
  height_ = h;
  if (fit_line_) {
    line_ = estimator_.person_height_line();
    // A line the bands do not support well is no line: height_ then serves every row.
    if (require_well_supported_ && !line_.well_supported()) line_.by_row = false;
  }
  return true;
}

}  // namespace vtrack::filters
