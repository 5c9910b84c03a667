#include "vtrack/image/kde_background.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "parallel_rows.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/vmath.hpp"
#include "vtrack/image/morphology.hpp"

namespace vtrack::image {
namespace {

std::string size_string(cv::Size s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

void require_bandwidth(double sigma, const char* name) {
  require(std::isfinite(sigma) && sigma > 0.0, name, sigma, "finite and > 0");
}

// exp(-e) for e >= 0 (core::vmath::exp, vectorised by GCC): relative error below 1e-7; e >= 87
// gives exp(-87) ~ 1.6e-38 rather than 0, far below the 1e-3 accuracy of y.
inline float exp_neg(float e) { return core::vmath::exp(-std::min(e, 87.0f)); }

// Chromaticity (eqs. 6, 7) of one pixel from its channel sum, as in color.hpp: black pixels are
// the neutral grey point 1/3. The current frame and the samples go through this same function,
// so equal pixels give exactly equal values and a kernel of exactly 1.
inline void chromaticity(float b, float g, float r, float& cr, float& cg, float& sum) {
  sum = b + g + r;
  const float inv = 1.0f / std::max(sum, 1.0f);
  // Both quotients are computed unconditionally and then selected: a select of two values,
  // unlike a conditional division, vectorises under GCC's default -ftrapping-math.
  const float qr = r * inv, qg = g * inv;
  const bool black = sum == 0.0f;
  cr = black ? 1.0f / 3.0f : qr;
  cg = black ? 1.0f / 3.0f : qg;
}

// The exponent factors 1 / (2 sigma_d^2) of eq. (10). Intensity differences are taken on the
// channel sum S = 765 I (an exact integer), so its factor carries 1 / 765^2.
struct Exponents {
  float r, g, s;
};

template <class Bandwidth>
Exponents exponents(const Bandwidth& sigma) {
  return {static_cast<float>(0.5 / (sigma[0] * sigma[0])),
          static_cast<float>(0.5 / (sigma[1] * sigma[1])),
          static_cast<float>(0.5 / (sigma[2] * sigma[2] * 765.0 * 765.0))};
}

// Eq. (10)'s kernel of one pixel (B, G, R) against another, without the mean over samples.
float pixel_kernel(const unsigned char* a, const unsigned char* b, const Exponents& k) {
  float ra, ga, sa, rb, gb, sb;
  chromaticity(a[0], a[1], a[2], ra, ga, sa);
  chromaticity(b[0], b[1], b[2], rb, gb, sb);
  const float dr = ra - rb, dg = ga - gb, ds = sa - sb;
  return exp_neg(dr * dr * k.r + dg * dg * k.g + ds * ds * k.s);
}

}  // namespace

const core::ParameterTable<KdeBackgroundParams>& KdeBackgroundParams::table() {
  using P = KdeBackgroundParams;
  static const auto table = core::ParameterTable<P>()
                                .add("n_samples", &P::n_samples)
                                .add("period", &P::period)
                                .add("bandwidth", &P::bandwidth)
                                .add("closing", &P::closing)
                                .add("threads", &P::threads)
                                .add("update_threshold", &P::update_threshold)
                                .add("update_max_skips", &P::update_max_skips)
                                .add("update_static", &P::update_static)
                                .add("illumination_compensation", &P::illumination_compensation);
  return table;
}

void validate(const KdeBackgroundParams& p) {
  if (p.n_samples < 1) {
    throw InvalidArgument("n_samples (N0) must be >= 1, got " + std::to_string(p.n_samples));
  }
  if (p.period < 1) {
    throw InvalidArgument("period (K0) must be >= 1, got " + std::to_string(p.period));
  }
  require_bandwidth(p.bandwidth[0], "bandwidth[0] (sigma_r)");
  require_bandwidth(p.bandwidth[1], "bandwidth[1] (sigma_g)");
  require_bandwidth(p.bandwidth[2], "bandwidth[2] (sigma_I)");
  if (p.closing < 0 || (p.closing > 1 && p.closing % 2 == 0)) {
    throw InvalidArgument("closing must be 0 (off), 1 (off) or an odd size in pixels, got " +
                          std::to_string(p.closing));
  }
  if (p.threads < 0) throw InvalidArgument("threads must be >= 0, got " + std::to_string(p.threads));
  if (!(p.update_threshold >= 0.0 && p.update_threshold <= 1.0)) {
    throw InvalidArgument("update_threshold must be in [0, 1], got " +
                          std::to_string(p.update_threshold));
  }
  if (p.update_max_skips < 1 || p.update_max_skips > 255) {
    throw InvalidArgument("update_max_skips must be in [1, 255], got " +
                          std::to_string(p.update_max_skips));
  }
}

KdeBackground::KdeBackground(const KdeBackgroundParams& params) : params_(params) {
  validate(params_);
}

void KdeBackground::set_closing(int size) {
  KdeBackgroundParams p = params_;
  p.closing = size;
  validate(p);
  params_.closing = size;
}

void KdeBackground::reset() {
  learning_ = true;
  frame_index_ = 0;
  size_ = cv::Size();
  samples_.clear();
  samples_.shrink_to_fit();
  sample_frame_.clear();
  count_ = 0;
  next_slot_ = 0;
  skips_.release();
  last_sample_frame_.release();
}

std::vector<long long> KdeBackground::sample_frames() const {
  std::vector<long long> frames;
  const int n = params_.n_samples;
  const int oldest = count_ < n ? 0 : next_slot_;
  for (int i = 0; i < count_; ++i) frames.push_back(sample_frame_[(oldest + i) % n]);
  return frames;
}

std::size_t KdeBackground::plane_offset(int slot, int channel) const {
  return (static_cast<std::size_t>(slot) * 3 + static_cast<std::size_t>(channel)) *
         static_cast<std::size_t>(size_.area());
}

void KdeBackground::store_sample(const cv::Mat& bgr, const cv::Mat& keep) {
  const std::size_t area = static_cast<std::size_t>(size_.area());
  if (samples_.empty()) {
    samples_.resize(area * 3 * static_cast<std::size_t>(params_.n_samples));
    sample_frame_.assign(static_cast<std::size_t>(params_.n_samples), -1);
  }
  const int slot = next_slot_;
  std::vector<cv::Mat> planes;
  for (int c = 0; c < 3; ++c) {
    planes.emplace_back(size_, CV_8UC1, samples_.data() + plane_offset(slot, c));
  }
  cv::split(bgr, planes);  // writes into the slot's memory: the headers match in size and type
  if (!keep.empty() && count_ > 0) {
    // Selective update: foreground pixels repeat the newest sample (the slot before this one).
    const int newest = (slot + params_.n_samples - 1) % params_.n_samples;
    for (int c = 0; c < 3; ++c) {
      const cv::Mat previous(size_, CV_8UC1, samples_.data() + plane_offset(newest, c));
      previous.copyTo(planes[c], keep);
    }
  }
  sample_frame_[slot] = frame_index_;
  next_slot_ = (slot + 1) % params_.n_samples;
  count_ = std::min(count_ + 1, params_.n_samples);
}

std::vector<float> KdeBackground::illumination_gains(const cv::Mat& bgr) const {
  std::vector<float> gain(static_cast<std::size_t>(params_.n_samples), 1.0f);
  if (!params_.illumination_compensation) return gain;
  // A grid of ~4096 pixels at any resolution; pixels darker than S = 30 (of 765) in the frame
  // are left out, their ratio being mostly sensor noise.
  constexpr int kMinS = 30;
  const int step = std::max(1, static_cast<int>(std::lround(std::sqrt(size_.area() / 4096.0))));
  std::vector<std::size_t> where;
  std::vector<float> frame_s;
  for (int row = step / 2; row < size_.height; row += step) {
    const unsigned char* in = bgr.ptr<unsigned char>(row);
    for (int x = step / 2; x < size_.width; x += step) {
      const int s = in[3 * x] + in[3 * x + 1] + in[3 * x + 2];
      if (s < kMinS) continue;
      where.push_back(static_cast<std::size_t>(row) * static_cast<std::size_t>(size_.width) + x);
      frame_s.push_back(static_cast<float>(s));
    }
  }
  if (where.size() < 16) return gain;  // a dark frame: nothing to measure a gain on
  std::vector<float> ratio(where.size());
  const std::size_t mid = ratio.size() / 2;
  for (int slot = 0; slot < count_; ++slot) {  // the filled slots are 0 .. count_ - 1
    const unsigned char* sb = samples_.data() + plane_offset(slot, 0);
    const unsigned char* sg = samples_.data() + plane_offset(slot, 1);
    const unsigned char* sr = samples_.data() + plane_offset(slot, 2);
    for (std::size_t i = 0; i < where.size(); ++i) {
      const std::size_t p = where[i];
      ratio[i] = static_cast<float>(sb[p] + sg[p] + sr[p]) / frame_s[i];
    }
    std::nth_element(ratio.begin(), ratio.begin() + static_cast<std::ptrdiff_t>(mid), ratio.end());
    if (ratio[mid] > 0.0f) gain[static_cast<std::size_t>(slot)] = ratio[mid];
  }
  return gain;
}

void KdeBackground::apply(const cv::Mat& bgr, cv::Mat& y) {
  if (bgr.empty()) throw InvalidArgument("frame is empty");
  if (bgr.type() != CV_8UC3) {
    throw InvalidArgument("frame must be 8-bit with 3 channels (BGR, CV_8UC3), got depth " +
                          std::to_string(bgr.depth()) + " with " + std::to_string(bgr.channels()) +
                          " channels");
  }
  if (size_.area() == 0) {
    size_ = bgr.size();
  } else if (bgr.size() != size_) {
    throw InvalidArgument("frame size changed mid-stream: frame " + std::to_string(frame_index_) +
                          " is " + size_string(bgr.size()) + ", the model holds " +
                          size_string(size_) + " frames (call reset() to start a new stream)");
  }
  // The sample schedule of section 3.1: frames 0, K0, 2 K0, ...; the ring buffer replaces the
  // oldest sample once N0 are stored.
  const bool sample = learning_ && frame_index_ % params_.period == 0;
  // Selective update: the sample is chosen by this frame's y, so it is stored after y (see
  // KdeBackgroundParams::update_threshold); the first sample is always the whole frame.
  const bool selective = sample && params_.update_threshold > 0.0 && count_ > 0;
  if (sample && !selective) store_sample(bgr);
  const bool closing = params_.closing > 1;
  cv::Mat& raw = closing ? closing_buffer_ : y;
  raw.create(size_, CV_32FC1);
  evaluate(bgr, raw);
  if (closing) close_square(raw, y, params_.closing, params_.threads, &closing_workspace_);
  if (selective) {
    // keep = foreground and skipped fewer than update_max_skips times in a row; skips counts the
    // consecutive foreground sample frames (reset where the pixel is background).
    if (skips_.size() != size_) skips_ = cv::Mat::zeros(size_, CV_8UC1);
    const float threshold = static_cast<float>(params_.update_threshold);
    const auto max_skips = static_cast<unsigned char>(params_.update_max_skips);
    keep_.create(size_, CV_8UC1);
    // Only while the stack fills: the first sample is stored whole, people included.
    const bool filling = count_ < params_.n_samples;
    const bool check_static = params_.update_static && filling && !last_sample_frame_.empty();
    const Exponents k = exponents(params_.bandwidth);
    for (int r = 0; r < size_.height; ++r) {
      const float* yr = y.ptr<float>(r);
      unsigned char* sr = skips_.ptr<unsigned char>(r);
      unsigned char* kr = keep_.ptr<unsigned char>(r);
      const unsigned char* now = bgr.ptr<unsigned char>(r);
      const unsigned char* before = check_static ? last_sample_frame_.ptr<unsigned char>(r) : nullptr;
      for (int c = 0; c < size_.width; ++c) {
        const bool foreground =
            yr[c] < threshold &&
            !(check_static && pixel_kernel(now + 3 * c, before + 3 * c, k) >= threshold);
        kr[c] = (foreground && sr[c] < max_skips) ? 255 : 0;
        sr[c] = foreground ? static_cast<unsigned char>(std::min(sr[c] + 1, 255)) : 0;
      }
    }
    store_sample(bgr, keep_);
  }
  if (sample && params_.update_static) {
    if (count_ < params_.n_samples) {
      bgr.copyTo(last_sample_frame_);
    } else {
      last_sample_frame_.release();
    }
  }
  ++frame_index_;
}

// Eq. (10) for every pixel, row by row. Per row, the current frame's r, g and S are computed
// once; then each sample adds its product of three kernels, exp(-(dr^2/2sr^2 + dg^2/2sg^2 +
// dI^2/2sI^2)), one exp per sample. The inner loops are over contiguous floats and bytes.
void KdeBackground::evaluate(const cv::Mat& bgr, cv::Mat& y) const {
  const int cols = size_.width;
  if (count_ == 0) {  // frozen before the first sample: no background model, no evidence
    y.setTo(1.0f);
    return;
  }
  const Exponents k = exponents(params_.bandwidth);
  const float inv_n = 1.0f / static_cast<float>(count_);
  const int n = params_.n_samples;
  const int oldest = count_ < n ? 0 : next_slot_;
  // Illumination compensation: the frame's S is scaled by each sample's gain when compared with
  // it (1 without compensation, which keeps eq. 10 as printed).
  const std::vector<float> gain = illumination_gains(bgr);
  detail::for_rows(size_.height, params_.threads, [&](int begin, int end) {
    std::vector<float> buffer(static_cast<std::size_t>(cols) * 3);
    float* cur_r = buffer.data();
    float* cur_g = cur_r + cols;
    float* cur_s = cur_g + cols;
    for (int row = begin; row < end; ++row) {
      const unsigned char* in = bgr.ptr<unsigned char>(row);
      for (int x = 0; x < cols; ++x) {
        chromaticity(in[3 * x], in[3 * x + 1], in[3 * x + 2], cur_r[x], cur_g[x], cur_s[x]);
      }
      float* acc = y.ptr<float>(row);
      std::fill_n(acc, cols, 0.0f);
      const std::size_t offset = static_cast<std::size_t>(row) * cols;
      for (int i = 0; i < count_; ++i) {
        const int slot = (oldest + i) % n;
        const unsigned char* sb = samples_.data() + plane_offset(slot, 0) + offset;
        const unsigned char* sg = samples_.data() + plane_offset(slot, 1) + offset;
        const unsigned char* sr = samples_.data() + plane_offset(slot, 2) + offset;
        const float gs = gain[static_cast<std::size_t>(slot)];
        for (int x = 0; x < cols; ++x) {
          float r, g, s;
          chromaticity(sb[x], sg[x], sr[x], r, g, s);
          const float dr = cur_r[x] - r, dg = cur_g[x] - g, ds = cur_s[x] * gs - s;
          acc[x] += exp_neg(dr * dr * k.r + dg * dg * k.g + ds * ds * k.s);
        }
      }
      for (int x = 0; x < cols; ++x) acc[x] *= inv_n;
    }
  });
}

void foreground_mask(const cv::Mat& y, double threshold, cv::Mat& mask) {
  if (y.empty()) throw InvalidArgument("y is empty");
  if (y.type() != CV_32FC1) {
    throw InvalidArgument("y must be single-channel float32 (CV_32FC1), got OpenCV type " +
                          std::to_string(y.type()));
  }
  if (!(threshold >= 0.0 && threshold <= 1.0)) {
    throw InvalidArgument("threshold must be in [0, 1], got " + std::to_string(threshold));
  }
  cv::compare(y, threshold, mask, cv::CMP_LT);
}

}  // namespace vtrack::image
