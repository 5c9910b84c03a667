#include "vtrack/image/kde_background.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "parallel_rows.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/image/morphology.hpp"

namespace vtrack::image {
namespace {

std::string size_string(cv::Size s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

void require_bandwidth(double sigma, const char* name) {
  if (!std::isfinite(sigma) || sigma <= 0.0) {
    throw InvalidArgument(std::string("bandwidth ") + name + " must be finite and > 0, got " +
                          std::to_string(sigma));
  }
}

// exp(-e) for e >= 0, written so that GCC vectorises it: Cephes' expf (range reduction by
// n = round(-e log2 e), degree-5 polynomial on the remainder, 2^n assembled in the exponent bits).
// Relative error below 2e-7 on the whole range; e >= 87 returns exp(-87) ~ 1.6e-38 rather
// than a denormal or 0, which is far below the 1e-3 accuracy of y.
inline float exp_neg(float e) {
  const float x = -std::min(e, 87.0f);
  const float n = std::floor(x * 1.44269504088896341f + 0.5f);
  float r = x - n * 0.693359375f;
  r = r + n * 2.12194440e-4f;
  float p = 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  p = p * r * r + r + 1.0f;
  const std::int32_t bits = (static_cast<std::int32_t>(n) + 127) << 23;
  float scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

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

}  // namespace

void validate(const KdeBackgroundParams& p) {
  if (p.n_samples < 1) {
    throw InvalidArgument("n_samples (N0) must be >= 1, got " + std::to_string(p.n_samples));
  }
  if (p.period < 1) {
    throw InvalidArgument("period (K0) must be >= 1, got " + std::to_string(p.period));
  }
  require_bandwidth(p.sigma_r, "sigma_r");
  require_bandwidth(p.sigma_g, "sigma_g");
  require_bandwidth(p.sigma_I, "sigma_I");
  if (p.closing < 0 || (p.closing > 1 && p.closing % 2 == 0)) {
    throw InvalidArgument("closing must be 0 (off), 1 (off) or an odd size in pixels, got " +
                          std::to_string(p.closing));
  }
  if (p.threads < 0) throw InvalidArgument("threads must be >= 0, got " + std::to_string(p.threads));
}

KdeBackground::KdeBackground(const KdeBackgroundParams& params) : params_(params) {
  validate(params_);
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
}

std::vector<long long> KdeBackground::sample_frames() const {
  std::vector<long long> frames;
  const int n = params_.n_samples;
  const int oldest = count_ < n ? 0 : next_slot_;
  for (int i = 0; i < count_; ++i) frames.push_back(sample_frame_[(oldest + i) % n]);
  return frames;
}

float* KdeBackground::plane(int slot, int channel) {
  return samples_.data() + (static_cast<std::size_t>(slot) * 3 + static_cast<std::size_t>(channel)) *
                               static_cast<std::size_t>(size_.area());
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
  // oldest sample once N0 are stored. The new sample is part of the stack for this frame's y.
  int new_slot = -1;
  if (learning_ && frame_index_ % params_.period == 0) {
    if (samples_.empty()) {
      samples_.resize(static_cast<std::size_t>(size_.area()) * 3 *
                      static_cast<std::size_t>(params_.n_samples));
      sample_frame_.assign(static_cast<std::size_t>(params_.n_samples), -1);
    }
    new_slot = next_slot_;
    sample_frame_[new_slot] = frame_index_;
    next_slot_ = (new_slot + 1) % params_.n_samples;
    count_ = std::min(count_ + 1, params_.n_samples);
  }
  const bool closing = params_.closing > 1;
  cv::Mat& raw = closing ? closing_buffer_ : y;
  raw.create(size_, CV_32FC1);
  evaluate(bgr, new_slot, raw);
  if (closing) close_square(raw, y, params_.closing, params_.threads, &closing_workspace_);
  ++frame_index_;
}

// Eq. (10) for every pixel, row by row. The rgI values are stored pre-scaled by
// 1 / (sqrt(2) sigma_d), so the exponent of the product of the three kernels of eq. (10) is
// the squared distance dr'^2 + dg'^2 + dI'^2 and each sample costs one exp. Per row, the
// current frame is converted once (into the new sample's slot when this frame is a sample
// time, else into a row buffer); then every sample adds its kernel product. The inner loops
// run over contiguous floats.
void KdeBackground::evaluate(const cv::Mat& bgr, int new_slot, cv::Mat& y) {
  const int cols = size_.width;
  if (count_ == 0) {  // frozen before the first sample: no background model, no evidence
    y.setTo(1.0f);
    return;
  }
  // I = S / 765 (color.hpp), so the intensity scale carries 1 / 765.
  const float scale_r = static_cast<float>(1.0 / (std::sqrt(2.0) * params_.sigma_r));
  const float scale_g = static_cast<float>(1.0 / (std::sqrt(2.0) * params_.sigma_g));
  const float scale_s = static_cast<float>(1.0 / (std::sqrt(2.0) * params_.sigma_I * 765.0));
  const float inv_n = 1.0f / static_cast<float>(count_);
  const int n = params_.n_samples;
  const int oldest = count_ < n ? 0 : next_slot_;
  std::vector<const float*> planes(static_cast<std::size_t>(count_) * 3);
  for (int i = 0; i < count_; ++i) {
    for (int c = 0; c < 3; ++c) planes[static_cast<std::size_t>(3 * i + c)] = plane((oldest + i) % n, c);
  }
  float* new_planes[3] = {nullptr, nullptr, nullptr};
  if (new_slot >= 0) {
    for (int c = 0; c < 3; ++c) new_planes[c] = plane(new_slot, c);
  }
  detail::for_rows(size_.height, params_.threads, [&](int begin, int end) {
    std::vector<float> buffer(new_slot >= 0 ? 0 : static_cast<std::size_t>(cols) * 3);
    for (int row = begin; row < end; ++row) {
      const std::size_t offset = static_cast<std::size_t>(row) * static_cast<std::size_t>(cols);
      float* cur_r = new_slot >= 0 ? new_planes[0] + offset : buffer.data();
      float* cur_g = new_slot >= 0 ? new_planes[1] + offset : buffer.data() + cols;
      float* cur_s = new_slot >= 0 ? new_planes[2] + offset : buffer.data() + 2 * cols;
      const unsigned char* in = bgr.ptr<unsigned char>(row);
      for (int x = 0; x < cols; ++x) {
        float r, g, s;
        chromaticity(in[3 * x], in[3 * x + 1], in[3 * x + 2], r, g, s);
        cur_r[x] = r * scale_r;
        cur_g[x] = g * scale_g;
        cur_s[x] = s * scale_s;
      }
      float* acc = y.ptr<float>(row);
      std::fill_n(acc, cols, 0.0f);
      for (int i = 0; i < count_; ++i) {
        const float* sr = planes[static_cast<std::size_t>(3 * i)] + offset;
        const float* sg = planes[static_cast<std::size_t>(3 * i + 1)] + offset;
        const float* ss = planes[static_cast<std::size_t>(3 * i + 2)] + offset;
        for (int x = 0; x < cols; ++x) {
          const float dr = cur_r[x] - sr[x], dg = cur_g[x] - sg[x], ds = cur_s[x] - ss[x];
          acc[x] += exp_neg(dr * dr + dg * dg + ds * ds);
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
