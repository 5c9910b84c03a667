#pragma once
// KDE background model on rgI chromaticity (mb-tbd-background-subtraction.txt, section 3.1,
// eqs. 6-10). Each 8-bit BGR frame becomes a grey image y in [0, 1], CV_32FC1, in which a value
// near 1 means "looks like the background" and a value near 0 means "foreground".
//
// The model, exactly as implemented:
//   * rgI per pixel (eqs. 6-8) with the conventions of color.hpp: r = R/S, g = G/S, I = S/765
//     with S = R + G + B (the printed eq. 8 divides by 256; see color.hpp), black pixels r = g = 1/3.
//   * A stack of up to N0 = n_samples frames, sampled every K0 = period frames. Frames are
//     counted from 0 since construction or reset(): frame k is a sample time when k % K0 == 0.
//     The stack initially fills with frames 0, K0, ..., (N0 - 1) K0; from k = N0 K0 on, the
//     oldest sample is replaced every K0 frames. A sample taken at frame k is already in the stack
//     when y(k) is computed (the paper's l = 0 term is the frame K0 floor(k/K0), which is k itself
//     when k is a sample time), so at those frames every pixel has one term equal to 1.
//   * y by eq. (10):
//       y_i(k) = 1/n * sum_{l=0}^{n-1} prod_{d=r,g,I} exp(-[d_i(k) - d_i(K0(floor(k/K0) - l))]^2
//                                                       / (2 sigma_d^2))
//     This is eq. (9) without the Gaussian normalising constants, as the paper prescribes, so
//     each term lies in (0, 1] and so does their mean: y = 1 exactly when the pixel equals all
//     samples. n is the number of samples in the stack. Before the stack is full (k < N0 K0) the
//     paper's sum would reach frames before the video starts; we average over the samples that
//     exist, n = min(N0, floor(k/K0) + 1), i.e. the samples taken at frames 0, K0, ...,
//     K0 floor(k/K0). Consequently y(0) = 1 everywhere: frame 0 is its own only sample.
//   * Optional noise removal (section 3.2): a greyscale morphological closing of y with a
//     closing x closing square (morphology.hpp). Closing y (dilation, then erosion) removes small
//     dark = foreground specks; it is the paper's "erosion followed by dilation" applied to the
//     foreground image 1 - y.
//
// Learning can be frozen: while frozen, frames still advance the frame counter but no sample is
// stored, so the model stays fixed; after resume(), the next frame k with k % K0 == 0 is sampled
// again (the schedule stays aligned with the video's frame numbers). If the stack is empty
// (frozen before the first frame) y is 1 everywhere: there is no evidence of foreground.
//
// Implementation (speed): each sample is stored as its original 8-bit B, G, R in three planes
// (3 bytes per pixel and sample: 13 MB for N0 = 10 at 768x576) and its rgI is recomputed on the
// fly in float32, by the same function as the current frame's, so nothing is quantised and equal
// pixels give a kernel of exactly 1 (agreement with a float64 transcription is ~1e-5). The three
// kernels of one sample are one exp of the summed exponent, a vectorisable Cephes-style
// polynomial (relative error ~2e-7); intensity differences are exact integer differences of
// S = 765 I. The loops run over contiguous bytes and floats, so GCC vectorises them (AVX2: 8
// pixels at a time). Storing pre-scaled float rgI planes instead (12 bytes per pixel and sample)
// saves the division but was measured no faster (it moves 4x more memory), so the compact form
// stays. Rows are independent and each is computed by one thread, so results do not depend on
// the thread count.
#include <array>
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "vtrack/core/parameters.hpp"

namespace vtrack::image {

struct KdeBackgroundParams {
  // N0, the number of sample frames in the stack (eqs. 9, 10). 10 samples, as in the issue's
  // speed bar; more samples give a smoother background density but cost linearly.
  int n_samples = 10;
  // K0, frames between samples (section 3.1). With N0 = 10 the stack spans N0 K0 = 100 frames
  // (10 s of vtest.avi at 10 fps): a person must stand still for several seconds before they
  // dissolve into the background, while lighting changes are absorbed within that span. The paper
  // suggests K0 ~ frame rate x the longest stationary time (its example: 125 at 25 fps).
  // On vtest.avi (benchmarks/bgs_quality.py, sigma = (0.03, 0.03, 0.06)) K0 = 5, 10, 20 give
  // recall / precision proxies 0.87 / 0.71, 0.89 / 0.69, 0.91 / 0.65: the choice is not critical.
  int period = 10;
  // Kernel bandwidths (sigma_r, sigma_g, sigma_I) of eqs. 9, 10 -- one parameter, `bandwidth`,
  // everywhere (C++, config files, --set bandwidth=r,g,I, Python bandwidth=(r, g, I)), because
  // the three are one kernel's bandwidth vector. Fixed, never estimated from the
  // data (compressed video repeats pixel values exactly, so estimated bandwidths collapse).
  // The chromaticity of a mid-grey pixel (S ~ 300) moves by ~0.01 under the +-3 grey levels of
  // sensor and XVID noise, and by more on dark pixels (r = R/S); sigma_r = sigma_g = 0.03 covers
  // about three such steps. sigma_I = 0.06 (about 46 levels of R + G + B) is wider in absolute
  // terms: chromaticity is the robust cue, intensity varies under shadows and light changes
  // ([19] in the paper). Measured on vtest.avi (benchmarks/bgs_quality.py, closing 3, y < 0.5):
  // (0.02, 0.02, 0.06) gives recall proxy 0.92 / precision proxy 0.53, (0.03, 0.03, 0.06)
  // 0.89 / 0.69, (0.04, 0.04, 0.08) 0.81 / 0.78: the default keeps nearly every person dark
  // while halving the false foreground of the narrower kernels. Any value > 0 is accepted.
  std::array<double, 3> bandwidth = {0.03, 0.03, 0.06};
  // Side of the square structuring element of the closing of y (section 3.2); 0 or 1 = off,
  // otherwise an odd number of pixels. 3 removes pixel-level specks (sensor noise, XVID blocks);
  // the selective update's mask is taken from the closed y. Joining the fragments of a silhouette
  // (clothes close to the background colour) needs a closing the size of the people, which
  // the background model cannot know: the multi-Bernoulli tracker applies it (its closing_ratio,
  // 0.06 of the learnt person height), and in the mb pipeline (apps/pipeline.hpp) this closing
  // follows the tracker's after every frame (set_closing), so that the selective update's mask
  // is closed like the tracker's y; this value is then the first frame's and the floor (sensor
  // specks do not shrink with the people). Default 5 until issue 12, which fitted PETS09-S2L1 at
  // 768 x 576 only: resized 0.5x, 5 x 5 here joins neighbouring people (MB MOTA / IDF1 on all
  // frames, seeds 0-2: 0.456 / 0.397 with 5, 0.478 / 0.481 with 3). (At 768 x 576, one closing of
  // 5 here against 3 here and 5 in the tracker: frames 1-397, calibrated MOTA / IDF1 over seeds
  // 0-2, 0.579 / 0.601 against 0.565 / 0.565; frames 398-795, 0.477 / 0.415 against
  // 0.485 / 0.425.)
  int closing = 3;
  // Threads: 0 = OpenCV's default pool (cv::parallel_for_ over rows), 1 = the calling thread
  // only, T > 1 = rows split into T stripes on OpenCV's pool. Results are identical for every value.
  int threads = 0;
  // Selective update (beyond the paper, whose stack takes every K0-th frame whole): 0 = off,
  // the paper's schedule, which the NumPy transcription (vtrack.reference) follows.
  // With a threshold t in (0, 1], a sample frame's pixels whose y, computed from the stack before
  // the frame is added (closed as above), is below t are not taken from the frame: they repeat
  // the newest stored sample's pixel instead. A person is then not written into the background
  // samples, so the grey "ghosts" they would leave for N0 K0 frames (y ~ 0.6-0.9 where someone
  // stood at a sample time) do not appear. The new sample then enters y from the next frame on
  // (it depends on this frame's y). A pixel is skipped on at most update_max_skips consecutive
  // sample frames and then taken whatever its y: otherwise a pixel that stays foreground would
  // never be absorbed (a person present in frame 0, the first sample, would leave a permanent
  // ghost where they stood; likewise an object that stops or a fast change of light).
  // Default 0.5 with 3 skips (30 frames at K0 = 10), chosen on PETS09-S2L1 frames 1-397
  // (benchmarks/pets09.py, tracker defaults, calibrated MOTA / IDF1): 0.588 / 0.485 without it,
  // 0.544 / 0.597 with it (1 skip: 0.615 / 0.492), i.e. a small loss of MOTA for a large gain of
  // identity; frames 398-795: 0.385 / 0.383 without, 0.495 / 0.447 with it (1 skip 0.452 / 0.425).
  double update_threshold = 0.5;
  int update_max_skips = 3;
  // Selective update, static pixels (beyond the paper): with this on, a foreground pixel whose
  // colour has not changed since the previous sample frame (the frame's own rgI kernel against
  // that frame's pixel, eq. (10) with one term, is >= update_threshold) is taken from the frame
  // instead of skipped. A person walking moves out of their own pixels within a sample period;
  // what stays foreground and unchanged is a "ghost": the background uncovered where someone
  // stood in the first sample (a video that starts with people in view), which the skips would
  // otherwise keep out of the stack for update_max_skips periods (~70 frames on PETS09-S2L1).
  // Off by default (the multi-Bernoulli tracker's KDE was tuned without it); the sir pipeline
  // turns it on (apps/pipeline.hpp, sir_background_defaults).
  bool update_static = false;
  // Global illumination compensation (beyond the paper): chromaticity r, g is invariant to a
  // global gain of the light, but I is not, and eq. (10)'s intensity kernel (sigma_I = 0.06) sees
  // a few per cent of gain as foreground everywhere. With this on, the current frame's intensity
  // is compared with each sample's after scaling it by the median, over a grid of ~4096 pixels,
  // of S(sample) / S(frame) (S = R + G + B): a global gain change between the sample and the
  // frame cancels, and the people in view, a minority of the pixels, move a median little.
  // false = eq. (10) as printed, the class's default; the mb pipeline turns it on
  // (apps/pipeline.hpp, mb_background_defaults, which has the measurements).
  bool illumination_compensation = false;

  // The names of the fields (config files, --set, Python keywords).
  static const core::ParameterTable<KdeBackgroundParams>& table();
};

// InvalidArgument naming the field and its value unless n_samples >= 1, period >= 1, every
// bandwidth is finite and > 0, closing is 0 or odd and >= 0, threads >= 0, update_threshold
// is in [0, 1] and update_max_skips in [1, 255].
void validate(const KdeBackgroundParams& params);

class KdeBackground {
 public:
  // Validates `params` (see validate()).
  explicit KdeBackground(const KdeBackgroundParams& params = {});

  // Consumes the next frame (non-empty CV_8UC3, BGR) and writes y (CV_32FC1, same size, values
  // in [0, 1]). `y` is reallocated only when its size or type differs, so an external buffer of
  // the right shape is filled in place. InvalidArgument for an empty frame, a frame that is not
  // 8-bit 3-channel, or a frame whose size differs from the first frame since construction or
  // reset() (the model is left unchanged in that case).
  void apply(const cv::Mat& bgr, cv::Mat& y);

  // Changes the closing's side (0, 1 or odd; InvalidArgument otherwise) from the next frame on:
  // the mb pipeline sets it to the tracker's person-relative closing (see `closing`).
  void set_closing(int size);

  void freeze() { learning_ = false; }
  void resume() { learning_ = true; }
  bool learning() const { return learning_; }
  // Forgets every sample and the frame size; the next frame is frame 0 and may have any size.
  // Learning is resumed.
  void reset();

  const KdeBackgroundParams& params() const { return params_; }
  // Frames consumed since construction or reset() (the index k of the next frame).
  long long frame_index() const { return frame_index_; }
  // The frame indices of the samples in the stack, oldest first.
  std::vector<long long> sample_frames() const;
  int sample_count() const { return count_; }
  // Size of the frames the model is bound to; empty before the first frame.
  cv::Size frame_size() const { return size_; }

 private:
  // Stores bgr in the oldest slot; where `keep` (CV_8UC1, may be empty) is non-zero the newest
  // sample's pixel is repeated instead (selective update).
  void store_sample(const cv::Mat& bgr, const cv::Mat& keep = cv::Mat());
  void evaluate(const cv::Mat& bgr, cv::Mat& y) const;
  std::size_t plane_offset(int slot, int channel) const;
  // Illumination compensation's gain per slot (illumination_compensation; all 1 when off).
  std::vector<float> illumination_gains(const cv::Mat& bgr) const;

  KdeBackgroundParams params_;
  bool learning_ = true;
  long long frame_index_ = 0;
  cv::Size size_;
  // Ring buffer of samples: slot s holds the planes B, G, R of one frame (size_.area() bytes each).
  std::vector<unsigned char> samples_;
  std::vector<long long> sample_frame_;  // frame index stored in each slot
  int count_ = 0;                        // samples in the stack, <= n_samples
  int next_slot_ = 0;                    // slot the next sample overwrites (the oldest when full)
  cv::Mat closing_buffer_;     // y before the closing
  cv::Mat closing_workspace_;  // the closing's intermediate dilation
  cv::Mat keep_;               // selective update: pixels not taken from the sample frame
  cv::Mat skips_;              // selective update: consecutive sample frames each pixel was skipped
  cv::Mat last_sample_frame_;  // update_static: the previous sample frame as read (BGR)
};

// Binary foreground mask of a background image y (CV_32FC1): 255 where y < threshold, 0
// elsewhere (CV_8UC1, OpenCV's fgmask convention). InvalidArgument for an empty or non-CV_32FC1
// image or a threshold outside [0, 1].
void foreground_mask(const cv::Mat& y, double threshold, cv::Mat& mask);

}  // namespace vtrack::image
