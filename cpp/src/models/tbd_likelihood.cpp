#include "vtrack/models/tbd_likelihood.hpp"

#include "vtrack/image/morphology.hpp"

#include <algorithm>
#include <cmath>
#include <string>


#include "vtrack/core/errors.hpp"

namespace vtrack::models {

const core::ParameterTable<TbdLikelihoodParams>& TbdLikelihoodParams::table() {
  using P = TbdLikelihoodParams;
  static const auto table = core::ParameterTable<P>()
                                .add("delta_f", &P::delta_f)
                                .add("delta_b", &P::delta_b)
                                .add("delta_b_row", &P::delta_b_row)
                                .add("delta_b_no_line", &P::delta_b_no_line)
                                .add_choice("delta_b_reference", &P::delta_b_reference,
                                            {{"person", P::DeltaBReference::person},
                                             {"image", P::DeltaBReference::image},
                                             {"row", P::DeltaBReference::row}})
                                .add("closing_size", &P::closing_size)
                                .add("closing_ratio", &P::closing_ratio);
  return table;
}

void validate(const TbdLikelihoodParams& p) {
  if (!(p.delta_f > 0.0) || !std::isfinite(p.delta_f)) {
    throw InvalidArgument("delta_f must be a positive finite number, got " + value_text(p.delta_f));
  }
  if (!(p.delta_b > 0.0) || !std::isfinite(p.delta_b)) {
    throw InvalidArgument("delta_b must be a positive finite number, got " + value_text(p.delta_b));
  }
  require(p.delta_b_row > 0.0 && std::isfinite(p.delta_b_row), "delta_b_row", p.delta_b_row,
          "a positive finite number");
  require(p.delta_b_no_line > 0.0 && std::isfinite(p.delta_b_no_line), "delta_b_no_line",
          p.delta_b_no_line, "a positive finite number");
  if (p.closing_size < 0 || (p.closing_size > 1 && p.closing_size % 2 == 0)) {
    throw InvalidArgument("closing_size must be 0, 1 or an odd number, got " +
                          std::to_string(p.closing_size));
  }
  require(std::isfinite(p.closing_ratio) && p.closing_ratio >= 0.0 && p.closing_ratio <= 1.0,
          "closing_ratio", p.closing_ratio, "in [0, 1]");
}

void TbdLikelihood::set_person_size(double width, double height) {
  require(std::isfinite(width) && width > 0.0, "person width", width, "a positive finite number");
  require(std::isfinite(height) && height > 0.0, "person height", height,
          "a positive finite number");
  person_width_ = width;
  person_height_ = height;
}

void TbdLikelihood::set_row_areas(std::vector<double> areas) {
  for (std::size_t r = 0; r < areas.size(); ++r) {
    if (!(std::isfinite(areas[r]) && areas[r] > 0.0)) {
      throw InvalidArgument("row area must be a positive finite number, got " +
                            value_text(areas[r]) + " at row " + std::to_string(r));
    }
  }
  row_areas_ = std::move(areas);
}

int TbdLikelihood::closing_pixels() const {
  if (params_.closing_size != 0) return params_.closing_size;
  // The odd number within 1 px of closing_ratio x height (2k + 1 for [2k, 2k + 2)); 1 = none.
  const double side = std::min(params_.closing_ratio * person_height_, 1e6);
  return 2 * static_cast<int>(std::floor(0.5 * side)) + 1;
}

TbdLikelihood::TbdLikelihood(const TbdLikelihoodParams& params) : params_(params) {
  validate(params_);
  // zeta_F = 1 / int_0^1 exp(-u / delta_F) du = 1 / (delta_F (1 - exp(-1/delta_F))).
  log_zeta_f_ = -std::log(params_.delta_f) - std::log(-std::expm1(-1.0 / params_.delta_f));
}

void TbdLikelihood::set_image(const cv::Mat& y) {
  if (y.empty()) throw InvalidArgument("y is empty");
  if (y.type() != CV_32FC1) {
    throw InvalidArgument("y must be a single-channel float32 image, got OpenCV type " +
                          std::to_string(y.type()));
  }
  // One branch-free pass (vectorised; NaN fails both comparisons), then a second only to name
  // the first bad pixel. cv::checkRange costs as much as the integral image.
  bool ok = true;
  for (int r = 0; r < y.rows; ++r) {
    const float* row = y.ptr<float>(r);
    bool row_ok = true;
    for (int c = 0; c < y.cols; ++c) row_ok &= (row[c] >= 0.0f) & (row[c] <= 1.0f);
    ok &= row_ok;
  }
  if (!ok) {
    for (int r = 0; r < y.rows; ++r) {
      for (int c = 0; c < y.cols; ++c) {
        const float v = y.at<float>(r, c);
        if (!(v >= 0.0f && v <= 1.0f)) {
          throw InvalidArgument("y must hold values in [0, 1] (no NaN), got " + value_text(v) +
                                " at row " + std::to_string(r) + ", column " + std::to_string(c));
        }
      }
    }
  }
  // The background model's separable closing (image/morphology.hpp): equal to cv::morphologyEx
  // (a max/min over a replicated border equals one over the pixels inside), single-threaded
  // because the tracker runs one per camera.
  using Reference = TbdLikelihoodParams::DeltaBReference;
  if ((params_.delta_b_reference != Reference::image ||
       (params_.closing_size == 0 && params_.closing_ratio > 0.0)) &&
      !has_person_size()) {
    throw InvalidArgument("the likelihood's delta_b_reference 'person' or 'row' and closing_ratio "
                          "need the person size (set_person_size) before the first image");
  }
  image::close_square(y, closed_, closing_pixels(), 1, &closing_workspace_);
  integral_.compute(closed_);
  // The reward's 1 / (m delta_B): eq. (20)'s image pixel count m ("image"); the person prior's
  // area ("person", see delta_b); "row" with row areas a(row_i) in m's place, pixel by pixel
  // (set_row_reward); "row" without them the prior's area on every row (see delta_b_no_line).
  const double person_area = person_width_ * person_height_;
  row_weighted_ = false;
  switch (params_.delta_b_reference) {
    case Reference::image:
      inv_m_delta_b_ = 1.0 / (static_cast<double>(y.total()) * params_.delta_b);
      break;
    case Reference::person:
      inv_m_delta_b_ = 1.0 / (person_area * params_.delta_b);
      break;
    case Reference::row:
      row_weighted_ = !row_areas_.empty();
      inv_m_delta_b_ = row_weighted_ ? 1.0 / params_.delta_b_row
                                     : 1.0 / (person_area * params_.delta_b_no_line);
      break;
  }
  if (row_weighted_) set_row_reward();
}

void TbdLikelihood::set_row_reward() {
  // Each pixel's reward (1 - y_i) / (a(row_i) delta_B) (see delta_b_row: eq. 14's weighted
  // average, normalised by the person expected on the row, not by the image), summed over boxes
  // by a second integral image.
  if (row_areas_.size() != static_cast<std::size_t>(closed_.rows)) {
    throw InvalidArgument("the likelihood's row areas cover " + std::to_string(row_areas_.size()) +
                          " rows, the image has " + std::to_string(closed_.rows));
  }
  reward_.create(closed_.size(), CV_32FC1);
  for (int r = 0; r < closed_.rows; ++r) {
    const double weight = 1.0 / row_areas_[std::size_t(r)];
    const auto c = static_cast<float>(weight * inv_m_delta_b_);
    const float* in = closed_.ptr<float>(r);
    float* out = reward_.ptr<float>(r);
    for (int col = 0; col < closed_.cols; ++col) out[col] = c * (1.0f - in[col]);
  }
  reward_integral_.compute(reward_);
}

double TbdLikelihood::row_reward(const image::Rect& r, const std::vector<image::Rect>& explained,
                                 double* y_sum) const {
  // explained_sum's and the reward's loops fused: the regions are intersected once (the same
  // sums in the same order as each alone).
  double sum = integral_.sum(r);
  double reward = reward_integral_.sum(r);
  for (const image::Rect& e : explained) {
    const image::Rect o = image::intersect(r, e);
    if (o.width == 0 || o.height == 0) continue;
    // Pixels inside an explained region are background (eq. 13): y = 1, and they earn nothing.
    sum += static_cast<double>(o.width) * o.height - integral_.sum(o);
    reward -= reward_integral_.sum(o);
  }
  // Overlapping explained regions are counted twice there: cap at "all background" (see
  // explained_sum), and the reward at 0.
  *y_sum = std::min(sum, static_cast<double>(r.width) * r.height);
  return std::max(reward, 0.0);
}

double TbdLikelihood::explained_sum(const image::Rect& rect,
                                    const std::vector<image::Rect>& explained) const {
  const image::Rect r = integral_.clip(rect);
  const double area = static_cast<double>(r.width) * r.height;
  if (area <= 0.0) return 0.0;
  double sum = integral_.sum(r);
  // Pixels of r inside an explained region count as 1 (eq. 13): add area - sum of the overlap.
  for (const image::Rect& e : explained) {
    const image::Rect o = image::intersect(r, e);
    if (o.width == 0 || o.height == 0) continue;
    sum += static_cast<double>(o.width) * o.height - integral_.sum(o);
  }
  // Explained regions that overlap each other would be counted twice there: cap at "all
  // background" so the mean stays in [0, 1].
  return std::min(sum, area);
}

double TbdLikelihood::log_likelihood(float x, float y, float w, float h,
                                     const std::vector<image::Rect>& explained) const {
  const image::Rect r = integral_.clip(box_to_rect(x, y, w, h));
  const double m_x = static_cast<double>(r.width) * r.height;
  if (m_x <= 0.0) return log_zeta_f_ - 1.0 / params_.delta_f;  // no pixel: pure background
  // log of eq. (20): m_x (1 - ybar) / (m delta_B) + log zeta_F - ybar / delta_F, with
  // m_x (1 - ybar) = m_x - sum; "row": sum_i (1 - y_i) a / a(row_i) in place of m_x - sum.
  double sum = 0.0;
  double reward = 0.0;
  if (row_weighted_) {
    reward = row_reward(r, explained, &sum);
  } else {
    sum = explained_sum(r, explained);
    reward = (m_x - sum) * inv_m_delta_b_;
  }
  const double ybar = sum / m_x;  // eq. (11)
  return reward + log_zeta_f_ - ybar / params_.delta_f;
}

void TbdLikelihood::log_likelihood(const Eigen::Ref<const BoxStates>& states, Eigen::VectorXd& out,
                                   const std::vector<image::Rect>& explained) const {
  if (!has_image()) throw InvalidArgument("TbdLikelihood: set_image() has not been called");
  out.resize(states.cols());
  for (Eigen::Index j = 0; j < states.cols(); ++j) {
    out[j] = log_likelihood(states(0, j), states(1, j), states(2, j), states(3, j), explained);
  }
}

}  // namespace vtrack::models
