#pragma once
// Track-before-detect likelihood of a background-subtracted image (mb-tbd-background-subtraction
// paper, eqs. 11-20).
//
// The input y is an H x W float32 image with y_i in [0, 1], near 1 for background. For a
// rectangle T(x) holding m_x pixels of the m = H*W of the image, with mean value ybar (eq. 11),
// the per-target factor of the separable likelihood (eq. 20) is
//
//   g_y(x) = exp(m_x (1 - ybar) / (m delta_B)) * zeta_F exp(-ybar / delta_F)
//
// and the whole-image likelihood is g(y | X) = f(y) prod_j g_y(x_j) with
// f(y) = zeta_B exp(sum_i y_i / (m delta_B)) (eq. 20), which cancels in the multi-Bernoulli
// update (eqs. 4, 23), so only g_y is computed. zeta_B cancels with f(y); zeta_F does not cancel:
// it decides whether rho = <p, g_y> is above or below 1, i.e. whether a region raises or lowers
// the existence probability. We take zeta_F as the constant that makes g_F(ybar) a probability
// density on [0, 1] (Fig. 1(a)): zeta_F = 1 / (delta_F (1 - exp(-1 / delta_F))).
//
// Every evaluation is O(1): ybar comes from an integral image of y. Rectangles are clipped to the
// image (m_x counts only the pixels inside); a rectangle with no pixel inside has no evidence for
// a target and is scored as pure background (ybar = 1, m_x = 0), so a track that leaves the image
// dies.
//
// The filter evaluates each Bernoulli component with the other targets' regions filled with
// background (the `explained` rectangles), the construction of eq. (13) applied to all targets but
// the one evaluated. Eq. (20) assumes targets do not overlap; without this, a box half on a
// tracked person collects the same foreground reward as the track and survives as a duplicate.
//
// Before the sums, y may be morphologically closed (dilation then erosion of y, i.e. erosion then
// dilation of the foreground 1 - y, as Section 3.2 says): this removes foreground specks smaller
// than the structuring element, which would otherwise lower ybar_B (eq. 14) and feed births.
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/core/parameters.hpp"
#include "vtrack/image/integral_image.hpp"

namespace vtrack::models {

// Box states are columns (x, y, w, h): top-left corner and size in pixels (float).
using BoxStates = Eigen::Matrix<float, 4, Eigen::Dynamic>;

struct TbdLikelihoodParams {
  // delta_F of g_F(ybar) = zeta_F exp(-ybar / delta_F) (Section 3.2, eq. 20): the smaller, the
  // more a rectangle is penalised for holding background (ybar near 1), and the tighter the
  // boxes. With 0.1, log g_F = 2.3 - 10 ybar: g_F alone favours ybar < 0.23, and each background
  // column added to a 40 x 100 box costs ~0.2 nats. (0.25 was tried: boxes came out ~30% too
  // large, because missing foreground costs more than including background.)
  double delta_f = 0.1;
  // delta_B of g_B(ybar_B) = zeta_B exp(ybar_B / delta_B) (eqs. 15-18): the reward for covering
  // foreground. As printed (delta_b_reference "image", the default), 1 / (m delta_B) per unit of
  // 1 - y covered, m the image's pixel count: it depends on the target's share of the image,
  // m_x / m, not on the resolution, so it holds when a video is resized. With 1e-3 a 40 x 100 px
  // person in a 768 x 576 image (0.9% of it) collects 0.009 (1 - ybar) / 1e-3, i.e. +7 nats at
  // ybar = 0.2. Default 2e-3, tuned on vtrack's KDE output of PETS09-S2L1 (benchmarks/pets09.py,
  // the sweep in its docstring): the KDE's y holds grey "ghosts" (y ~ 0.6-0.8) where people
  // stood in the background samples, and with 1e-3 their reward drew boxes over them and over
  // pairs of people (calibrated second half: MOTA 0.18 with 1.5e-3, 0.32 with 2e-3, 0.31 with
  // 2.5e-3, which loses the smallest, farthest people).
  // With delta_b_reference "person", m is replaced by the area a of the people size prior (the
  // tracker's mean width x height, set_person_size): a person-sized box of mean y ybar earns
  // (1 - ybar) / delta_B nats whatever their share of the image (a crop, a closer camera); 0.35
  // is the equivalent of 2e-3 "image" for PETS09-S2L1 at 768 x 576 with a 30 x 85 px prior
  // (2e-3 x 442368 / 2550). Measured (issue 12; size prior learnt with a 100-frame half-life, MB
  // MOTA / IDF1 on all
  // frames, seed 0): on PETS09's central 512 x 384 crop "image" 2e-3 gave 0.270 / 0.363 and
  // "person" 0.35 0.428 / 0.408; on the 1.5x zoom 0.252 / 0.393 against 0.438 / 0.379; but on the
  // 320 x 240 synthetic scene of tests/test_track_video.py (people 1.2% of the image, twice
  // PETS09's share, and cleaner y) "person" 0.35 gave 0.618 / 0.803 against 0.938 / 0.968 with
  // "image" 2e-3: a person-relative reward needs another value there, so it is not the default.
  //
  // With delta_b_reference "row", eq. (20) with the image's pixel count m replaced pixel by pixel
  // by a(row_i), the area of the person the prior expects centred on that row (the tracker's
  // person height line by foot row, set_row_areas; without one the prior's mean area on every
  // row, with delta_b_no_line), and delta_b_row for delta_B: each pixel earns (1 - y_i) / (a(row_i) delta_b_row),
  // so a person-sized box of mean ybar earns about (1 - ybar) / delta_b_row nats on every row,
  // at every resolution and whatever the people's share of the image. Why: with "image" or
  // "person" the reward grows with the box's pixel count m_x while the penalty -ybar / delta_F
  // does not, so the best box takes a strip of mean y_s iff y_s < (k + ybar) / (1 + k) with
  // k = m_x delta_F / (m delta_B): 0.14 for a 60 px PETS09 person (boxes shrink to the dark
  // core) and 0.73 for a 130 px one (boxes reach over grey background), so one box calibration
  // cannot fit both. With "row", k = m_x delta_F / (a(row) delta_b_row) is the same for every
  // person-sized box. It is eq. (14)'s "weighted average" with the pixel weights 1 / a(row_i)
  // (delta_B absorbing their scale): the weights do not depend on the state X, so eqs.
  // (15)-(20) go through unchanged with m_x (1 - ybar) / m replaced by sum_{i in T(x)} (1 - y_i)
  // / a(row_i), and f(y) still cancels. (Until 2026-11-28 the weights were a / (a(row_i) m), a
  // the prior's mean person area: k then grew with the people's share of the image, 2.25 times
  // PETS09's on its central 512 x 384 crop and its 1.5x zoom, where boxes grew over ghosts and
  // pairs and MB's MOTA fell from 0.61 to 0.39; benchmarks/mb_perspective.py, CROPS.) (A normaliser taken at each box's own row instead would make g_B
  // depend on X beyond eq. (13)'s fill, and its gradient in the box's row would pull boxes up the
  // image, towards smaller a.) The price: inside one box the upper rows weigh more than the lower
  // ones, so the best box reaches a little further up than down (in the unit test 0.58 of the
  // half-height above the centre against 0.54 below, at every size, which a calibration absorbs).
  // The multi-Bernoulli tracker uses it with size_by_row only.
  double delta_b = 2e-3;
  // The delta_B of the "row" reference while row areas are set (a person height line is in
  // force), per person area: a person-sized box of mean ybar earns about (1 - ybar) /
  // delta_b_row. 0.52 is the 3e-3 per image pixel chosen on PETS09-S2L1 frames 1-397 among 2e-3
  // and 3e-3 (benchmarks/mb_perspective.py; the larger delta_B cut the far people's false
  // positives of the first half) for its 30 x 85 px mean person at 768 x 576 (3e-3 x 442368 /
  // 2550).
  double delta_b_row = 0.52;
  // The delta_B of the "row" reference without row areas (a scene that shows no perspective, or
  // too few people yet to fit a line): every row's area is the prior's mean person area a, so a
  // box of m_x pixels earns m_x (1 - ybar) / (a delta_b_no_line) whatever the image size. Until
  // 2026-11-28 it was eq. (20) per image pixel with delta_b, whose k = m_x delta_F / (m delta_B)
  // fell with the people's share of the image: with people a tenth of a 640 x 480 image, boxes
  // shrank to 0.7 x the people (benchmarks/synthetic_people.py, "far": MB MOTA -0.35). Lower
  // than delta_b_row, because one area now stands for people of every size: one smaller than the
  // mean earns less (at 0.52 tests/test_multi_bernoulli.py's 768 x 576 scene of 70-140 px people
  // lost its smaller ones: MOTA 0.565). 0.2 is the best of 0.17-0.35 on a tuning split of
  // synthetic scenes without perspective (synthetic_people.py's docstring: the smaller, the more
  // small people found; the larger, the fewer pairs boxed as one in dense scenes).
  double delta_b_no_line = 0.2;
  enum class DeltaBReference { image, person, row };
  DeltaBReference delta_b_reference = DeltaBReference::image;
  // Side of the square structuring element of the morphological closing of y (Section 3.2), which
  // removes foreground specks and joins the fragments of a silhouette. closing_size > 1 (odd):
  // that many pixels; 1: off; 0 (default): closing_ratio times the person height (set_person_size),
  // rounded to the odd number 2k + 1 for a product in [2k, 2k + 2) (so off below 2 px). The fragments to join scale with the people,
  // so a fixed pixel size fits one resolution: vtrack's KDE closes y with 3 x 3 (pixel noise) and
  // this closing adds the person-sized part. 0.06 is 5 px for PETS09-S2L1's 85 px people at
  // 768 x 576, the closing its defaults were tuned with. Measured (benchmarks/pets09.py, MB MOTA /
  // IDF1, all frames, seeds 0-2, learnt prior): at 0.5x (384 x 288) a 5 x 5 closing gave 0.456 /
  // 0.397 and 3 x 3 0.478 / 0.481; at 1.5x, 5 x 5 0.538 / 0.501, 7 x 7 0.519 / 0.493 (seeds 0-1).
  // (Earlier, at 768 x 576: 7 x 7 was worse than 5 x 5, second half MOTA 0.24 vs 0.32.)
  int closing_size = 0;
  double closing_ratio = 0.06;

  static const core::ParameterTable<TbdLikelihoodParams>& table();
};

// Throws InvalidArgument naming the parameter when a value is out of range.
void validate(const TbdLikelihoodParams& params);

class TbdLikelihood {
 public:
  explicit TbdLikelihood(const TbdLikelihoodParams& params = {});

  const TbdLikelihoodParams& params() const { return params_; }
  // log zeta_F (see above).
  double log_zeta_f() const { return log_zeta_f_; }

  // The people size prior's mean width and height (px, > 0) that the "person" delta_B reference
  // and the closing_ratio refer to; the tracker sets it whenever its prior changes.
  void set_person_size(double width, double height);
  bool has_person_size() const { return person_height_ > 0.0; }
  // The "row" reference's a(row): one area (px^2, positive, finite) per image row, or empty for
  // the constant person area; applies from the next set_image, whose y must then have
  // areas.size() rows. The tracker sets it whenever its person height line changes.
  void set_row_areas(std::vector<double> areas);
  const std::vector<double>& row_areas() const { return row_areas_; }
  // The closing's side in pixels in force (0 or 1: none).
  int closing_pixels() const;

  // Takes a new image: H x W single-channel float32 with values in [0, 1] (NaN or values outside
  // are an InvalidArgument naming `y`). Applies the closing and computes the integral image.
  // InvalidArgument when the parameters refer to the person size and none was set.
  void set_image(const cv::Mat& y);
  bool has_image() const { return !closed_.empty(); }
  int width() const { return closed_.cols; }
  int height() const { return closed_.rows; }
  // y after the closing (what the likelihood sees).
  const cv::Mat& processed_image() const { return closed_; }
  const image::IntegralImage& integral() const { return integral_; }

  // log g_y(x) of eq. (20) for one box (x, y, w, h), on y with the pixel rectangles `explained`
  // filled with background (y = 1), as eq. (13) fills the regions of the other targets. The
  // rectangles are added independently: where two overlap, a pixel counts twice (the sum is
  // capped so that ybar <= 1).
  double log_likelihood(float x, float y, float w, float h,
                        const std::vector<image::Rect>& explained = {}) const;
  // Sum of y over `rect` (clipped to the image) with the `explained` rectangles filled with 1.
  double explained_sum(const image::Rect& rect, const std::vector<image::Rect>& explained) const;
  // log g_y of every column of `states` into `out` (resized to states.cols()).
  void log_likelihood(const Eigen::Ref<const BoxStates>& states, Eigen::VectorXd& out,
                      const std::vector<image::Rect>& explained = {}) const;

 private:
  TbdLikelihoodParams params_;
  double log_zeta_f_;
  // Fills reward_ and its integral image from closed_ and the row areas.
  void set_row_reward();
  // "row": the sum over `rect` (clipped) of the reward image without the `explained`
  // rectangles, and in *y_sum that of y with them as background (explained_sum), in one pass
  // over the explained rectangles.
  double row_reward(const image::Rect& rect, const std::vector<image::Rect>& explained,
                    double* y_sum) const;

  double inv_m_delta_b_ = 0.0;  // 1 / (m delta_B) or 1 / (a delta_B), set with the image
  // The "row" reference with row areas: rewards from reward_integral_ (set with the image).
  bool row_weighted_ = false;
  double person_width_ = 0.0;
  double person_height_ = 0.0;
  std::vector<double> row_areas_;
  cv::Mat closed_;
  // "row": (1 - y_i) / (a(row_i) delta_B) of the closed y, and its integral image.
  cv::Mat reward_;
  image::IntegralImage reward_integral_;
  cv::Mat closing_workspace_;  // the intermediate dilation, reused across frames
  image::IntegralImage integral_;
};

// Pixel rectangle of a float box: columns [round(x), round(x + w)), rows likewise (not clipped).
// Inline, with comparisons rather than std::fmin / std::fmax: it runs once per particle and box,
// and without -ffinite-math-only GCC calls libm for fmin / fmax (which cost the MB pipeline more
// than the rest of the likelihood together). NaN clamps to -1e8 exactly as fmax then fmin did.
inline image::Rect box_to_rect(float x, float y, float w, float h) {
  // lround on floats that may be huge: clamp first so the int conversion is defined; the
  // integral image clips to the image anyway.
  auto px = [](float v) {
    const float c = v > -1e8f ? (v < 1e8f ? v : 1e8f) : -1e8f;
    return static_cast<int>(std::lround(c));
  };
  const int x0 = px(x);
  const int y0 = px(y);
  return {x0, y0, px(x + w) - x0, px(y + h) - y0};
}

}  // namespace vtrack::models
