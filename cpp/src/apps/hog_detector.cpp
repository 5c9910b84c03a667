#include "vtrack/apps/hog_detector.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"

namespace vtrack::apps {

const core::ParameterTable<HogParams>& HogParams::table() {
  using P = HogParams;
  static const auto table = core::ParameterTable<P>()
                                .add("hit_threshold", &P::hit_threshold)
                                .add("win_stride", &P::win_stride)
                                .add("padding", &P::padding)
                                .add("scale", &P::scale)
                                .add("upscale", &P::upscale)
                                .add("group_threshold", &P::group_threshold)
                                .add("min_score", &P::min_score)
                                .add("person_fraction", &P::person_fraction);
  return table;
}

void validate(const HogParams& p) {
  if (!std::isfinite(p.hit_threshold)) {
    throw InvalidArgument("hit_threshold must be finite, got " + std::to_string(p.hit_threshold));
  }
  if (p.win_stride < 8 || p.win_stride % 8 != 0) {
    throw InvalidArgument("win_stride must be a positive multiple of 8 (the HOG cell), got " +
                          std::to_string(p.win_stride));
  }
  if (p.padding < 0 || p.padding % 8 != 0) {
    throw InvalidArgument("padding must be a non-negative multiple of 8, got " +
                          std::to_string(p.padding));
  }
  if (!(p.scale > 1.0 && p.scale <= 2.0)) {
    throw InvalidArgument("scale must lie in (1, 2], got " + std::to_string(p.scale));
  }
  if (!(p.upscale >= 0.25 && p.upscale <= 4.0)) {
    throw InvalidArgument("upscale must lie in [0.25, 4], got " + std::to_string(p.upscale));
  }
  if (p.group_threshold < 0) {
    throw InvalidArgument("group_threshold must be >= 0, got " + std::to_string(p.group_threshold));
  }
  if (!std::isfinite(p.min_score)) {
    throw InvalidArgument("min_score must be finite, got " + std::to_string(p.min_score));
  }
  if (!(p.person_fraction > 0 && p.person_fraction <= 1)) {
    throw InvalidArgument("person_fraction must lie in (0, 1], got " +
                          std::to_string(p.person_fraction));
  }
}

HogPeopleDetector::HogPeopleDetector(HogParams params) : params_(params) {
  validate(params_);
  hog_.setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector());
}

namespace {

// The side cv::resize gives a side of `n` pixels at `factor` (it rounds to nearest).
int resized(int n, double factor) { return cvRound(n * factor); }

}  // namespace

cv::Size HogPeopleDetector::min_frame_size() const {
  const cv::Size window = hog_.winSize;
  cv::Size min(static_cast<int>(window.width / params_.upscale),
               static_cast<int>(window.height / params_.upscale));
  while (resized(min.width, params_.upscale) < window.width) ++min.width;
  while (resized(min.height, params_.upscale) < window.height) ++min.height;
  return min;
}

void HogPeopleDetector::check_frame_size(int width, int height) const {
  const cv::Size min = min_frame_size();
  if (width >= min.width && height >= min.height) return;
  throw InvalidArgument("frame is " + std::to_string(width) + "x" + std::to_string(height) +
                        ", smaller than the HOG people detector's " +
                        std::to_string(hog_.winSize.width) + "x" +
                        std::to_string(hog_.winSize.height) + " window at upscale " +
                        value_text(params_.upscale) + ": frames must be at least " +
                        std::to_string(min.width) + "x" + std::to_string(min.height));
}

std::vector<ScoredBox> HogPeopleDetector::detect(const cv::Mat& frame) const {
  if (frame.empty() || frame.depth() != CV_8U || (frame.channels() != 3 && frame.channels() != 1)) {
    throw InvalidArgument("frame must be a non-empty 8-bit BGR or grey image");
  }
  check_frame_size(frame.cols, frame.rows);
  cv::Mat image = frame;
  if (params_.upscale != 1.0) {
    cv::resize(frame, image, cv::Size(), params_.upscale, params_.upscale, cv::INTER_LINEAR);
  }
  std::vector<cv::Rect> found;
  std::vector<double> weights;
  const cv::Size stride(params_.win_stride, params_.win_stride);
  const cv::Size pad(params_.padding, params_.padding);
  hog_.detectMultiScale(image, found, weights, params_.hit_threshold, stride, pad, params_.scale,
                        params_.group_threshold);
  std::vector<ScoredBox> out;
  const double back = 1.0 / params_.upscale;
  for (std::size_t i = 0; i < found.size(); ++i) {
    const double score = i < weights.size() ? weights[i] : 0.0;
    if (score < params_.min_score) continue;
    // The person's box: the window scaled by person_fraction about its centre, in frame pixels.
    const double w = found[i].width * back, h = found[i].height * back;
    const double cx = found[i].x * back + w / 2, cy = found[i].y * back + h / 2;
    const double pw = w * params_.person_fraction, ph = h * params_.person_fraction;
    out.push_back({cx - pw / 2, cy - ph / 2, pw, ph, score});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const ScoredBox& a, const ScoredBox& b) { return a.score > b.score; });
  return out;
}

}  // namespace vtrack::apps
