#pragma once
// HSV color histograms of boxes, the Bhattacharyya coefficient and the color likelihood of the
// color-histogram particle filters (part-based-graphical-model-pf.txt section 3.1, eqs. 9-11,
// after Nummiaro, Koller-Meier & Van Gool, "An adaptive color-based particle filter", 2003, the
// paper's ref. [14]).
//
// HSV and its bins. Frames are 8-bit BGR. OpenCV's 8-bit HSV (COLOR_BGR2HSV) stores the hue
// H in [0, 180) (degrees / 2) so it fits a byte; 16 hue bins over 180 codes would be 11.25 codes
// wide, i.e. alternately 11 and 12 codes, unequal by 9%. We convert with COLOR_BGR2HSV_FULL
// instead, which stores H = round(256 * hue / 360) mod 256 in [0, 256), so 16 hue bins are exactly
// 16 codes = 22.5 degrees each (bin 0 = hue in [-0.7, 21.8) degrees, i.e. red; bin 15 = [336.8,
// 359.3)). S and V are in [0, 255]. A channel value c with n bins falls in bin floor(c * n / 256),
// so the paper's m = 16 x 4 x 4 = 256 bins are (H >> 4, S >> 6, V >> 6), flattened as
//   u = (h_bin * bins_s + s_bin) * bins_v + v_bin.
// Grey pixels (S = 0) have H = 0 by OpenCV's convention and land in the red hue bin with
// s_bin = 0; the paper does not separate them, and neither do we (their S and V bins still tell
// grey from color).
//
// Boxes and pixels. A box (x, y, w, h) is continuous (particle states are): x, y the top-left
// corner, w, h the size, in pixels. Its pixels are the columns [round(x), round(x + w)) and rows
// [round(y), round(y + h)) (round = floor(v + 0.5)), clipped to the frame; a box with no pixel in
// the frame has an empty histogram, which scores rho = 0 against any template.
//
// Kernel weighting (optional, Nummiaro et al. section 3): a pixel at distance r from the box
// centre counts with the Epanechnikov profile k(r) = 1 - (r / a)^2 (0 beyond a), where
// a = sqrt(Hx^2 + Hy^2) and Hx = w / 2, Hy = h / 2 are the box's half-sides, as Nummiaro et al.
// adapt a to the region. Pixels near the border, more likely background, count less; only the
// box's corners get weight 0. The distance is taken from the pixel's centre (c + 0.5, r + 0.5) to
// the continuous centre (x + w/2, y + h/2). A histogram is normalised by its total weight
// (Nummiaro's f), so it sums to 1.
//
// Speed. A filter scores many boxes per frame against one template. The frame is converted and
// quantised once per frame, over a region of interest that holds every box (HsvBinImage: OpenCV's
// integer HSV_FULL and the binning in one pass, 16-bit bin indices, one thread); each box's
// histogram then costs its own pixels only, never a color conversion, and usually less:
// ColorModel::coefficients scores N boxes in one call and derives each box's counts (or kernel
// weights, through per-bin coordinate moments) from a neighbouring box's
// (HistogramMethod::incremental). An integral histogram over the region
// (one summed-area table per bin) was measured too and dropped: with m = 256 bins its
// construction costs more than counting every box directly (benchmarks/color_histogram.py's
// docstring has the figures).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "vtrack/core/parameters.hpp"
#include "vtrack/image/integral_image.hpp"

namespace vtrack::image {

struct ColorHistogramParams {
  // Bins of H, S and V (section 3.1: m = 16 x 4 x 4). Each in [1, 256]; hue is the most
  // telling channel under changing light, so it gets the most bins.
  int bins_h = 16;
  int bins_s = 4;
  int bins_v = 4;
  // Weight pixels with Nummiaro et al.'s Epanechnikov kernel (above); off = every pixel of the box
  // counts 1. Section 3.1's "color histograms of positional information" may mean this weighting
  // (its ref. [14] uses it); the filters' benchmarks are to say which tracks better.
  bool kernel = false;

  // Names for config files and Python keywords (core/parameters.hpp): bins_h, bins_s, bins_v,
  // kernel; defined in color_histogram.cpp.
  static const core::ParameterTable<ColorHistogramParams>& table();
};

// Throws InvalidArgument naming the parameter when a bin count is outside [1, 256].
void validate(const ColorHistogramParams& params);

// Number of bins m = bins_h * bins_s * bins_v.
inline int bin_count(const ColorHistogramParams& p) { return p.bins_h * p.bins_s * p.bins_v; }

// Pixel rectangle of a continuous box (x, y, w, h) before clipping (see the file comment).
Rect pixel_rect(double x, double y, double w, double h);

// The pixels of a frame's region of interest as histogram bin indices (16-bit). Only the bin
// counts of the params matter here (kernel weighting belongs to the histogram). Reused from frame
// to frame: assign() reallocates only when the region grows.
class HsvBinImage {
 public:
  explicit HsvBinImage(const ColorHistogramParams& params = {});

  // Converts and quantises the part of `bgr` (CV_8UC3) inside `roi` (clipped to the frame; may be
  // empty). Boxes scored later must lie, once clipped to the frame, inside that part.
  void assign(const cv::Mat& bgr, const Rect& roi);
  // The whole frame.
  void assign(const cv::Mat& bgr) { assign(bgr, Rect{0, 0, bgr.cols, bgr.rows}); }

  const ColorHistogramParams& params() const { return params_; }
  int bins() const { return bin_count(params_); }
  // The quantised region, in frame coordinates (clipped to the frame).
  const Rect& roi() const { return roi_; }
  int frame_rows() const { return frame_rows_; }
  int frame_cols() const { return frame_cols_; }
  // Bin index of frame pixel (row, col), which must lie inside roi().
  std::uint16_t at(int row, int col) const { return row_ptr(row)[col - roi_.x]; }
  // Pointer to the bin indices of frame row `row` (inside roi()), starting at column roi().x.
  const std::uint16_t* row_ptr(int row) const {
    return buffer_.data() + static_cast<std::size_t>(row - roi_.y) * roi_.width;
  }

  // Clips `rect` to the frame and checks it lies inside roi(); throws InvalidArgument otherwise.
  Rect clip_inside(const Rect& rect) const;

 private:
  ColorHistogramParams params_;
  // Bin indices of the region, row-major; grows to the largest region seen, never shrinks.
  std::vector<std::uint16_t> buffer_;
  Rect roi_;
  int frame_rows_ = 0;
  int frame_cols_ = 0;
};

// Histogram of the box (x, y, w, h) into `hist` (bins.bins() values, overwritten): counts of its
// pixels, or their kernel weights when `kernel`. Returns the total (pixel count or sum of
// weights); 0 when the box has no pixel (hist is then all zeros). Divide by the total for the
// normalised histogram of eq. 10. The box, clipped to the frame, must lie inside bins.roi().
double box_histogram(const HsvBinImage& bins, double x, double y, double w, double h, bool kernel,
                     double* hist);

// Bhattacharyya coefficient rho[p, q] = sum_u sqrt(p_u q_u) (eq. 10) of the normalised
// histograms p / sum(p) and q / sum(q), for any non-negative p, q of `m` bins (counts or
// distributions). Throws InvalidArgument when a value is negative or NaN or a histogram sums to 0.
double bhattacharyya_coefficient(const double* p, const double* q, std::size_t m);
// Bhattacharyya distance d = sqrt(1 - rho) (eq. 9), with 1 - rho clamped at 0 against rounding.
double bhattacharyya_distance(double rho);

// Color likelihood of eq. 11 in the log domain:
//   log p(z | x) = -log(sqrt(2 pi) sigma) - (1 - rho) / (2 sigma^2).
// sigma is the standard deviation of the Gaussian on the distance d = sqrt(1 - rho). The paper's
// text gives sigma^2 = 0.2 for eq. 11, while its eq. 24 writes the normaliser 1/sqrt(2 pi sigma),
// which reads as sigma = 0.2; the two readings weight particles very differently
// (exp(-2.5 d^2) against exp(-12.5 d^2)), so sigma is a parameter. kDefaultColorSigma is the
// text's sigma^2 = 0.2; benchmarks/follow.py measures both readings (sigma = 0.2 tracked better
// there), and the trackers' parameters choose their own default.
constexpr double kDefaultColorSigma = 0.44721359549995793;  // sqrt(0.2)
double color_log_likelihood(double rho, double sigma);
// Elementwise over n coefficients; sigma > 0 (InvalidArgument otherwise).
void color_log_likelihood(const double* rho, std::size_t n, double sigma, double* out);

// How ColorModel::coefficients counts the histograms of many boxes (benchmarks/color_histogram.py
// measures them). Every method gives the same coefficients.
enum class HistogramMethod {
  // incremental.
  automatic,
  // Each box's pixels, one increment (or kernel weight) per pixel.
  direct,
  // Boxes in Morton order of their corners; each box's counts are the previous box's minus the
  // pixels it no longer covers plus those it newly covers (up to 4 rectangles each), or a direct
  // count when that is cheaper. Particles overlap a lot, so few pixels change. Kernel-weighted
  // histograms are updated the same way through per-bin moments of the pixels' coordinates (the
  // kernel is a quadratic in them; color_histogram.cpp's PixelMoments).
  incremental,
};

// A template histogram q (normalised) and the batch scoring of boxes against it.
class ColorModel {
 public:
  // Template from `hist` (bin_count(params) non-negative values, not all zero; normalised here).
  ColorModel(const ColorHistogramParams& params, const std::vector<double>& hist);
  // Template from the box (x, y, w, h) of a BGR frame; throws InvalidArgument when the box has no
  // pixel in the frame (or only pixels of kernel weight 0).
  static ColorModel from_box(const cv::Mat& bgr, double x, double y, double w, double h,
                              const ColorHistogramParams& params = {});

  const ColorHistogramParams& params() const { return params_; }
  // The normalised template q (sums to 1).
  const std::vector<double>& reference() const { return q_; }

  // Bhattacharyya coefficients rho[p(box_i), q] (eq. 10) of n boxes, `boxes` holding n rows
  // (x, y, w, h) with `stride` doubles between rows (4 for an N x 4 array). The boxes, clipped to
  // the frame, must lie inside bins.roi(); bins must use this model's params. A box without
  // pixels scores 0.
  void coefficients(const HsvBinImage& bins, const double* boxes, std::size_t n,
                    std::size_t stride, double* rho,
                    HistogramMethod method = HistogramMethod::automatic) const;
  // The same on a frame: quantises the smallest region holding every box into `workspace`
  // (one color conversion), then scores.
  void coefficients(const cv::Mat& bgr, const double* boxes, std::size_t n, std::size_t stride,
                    double* rho, HsvBinImage& workspace,
                    HistogramMethod method = HistogramMethod::automatic) const;

 private:
  ColorHistogramParams params_;
  std::vector<double> q_;
  std::vector<float> sqrt_q_;
};

// The smallest pixel rectangle holding the pixel rects of n boxes (rows x, y, w, h with `stride`),
// clipped to a cols x rows frame; empty when no box has a pixel in it.
Rect boxes_roi(const double* boxes, std::size_t n, std::size_t stride, int cols, int rows);

}  // namespace vtrack::image
