#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/models/tbd_likelihood.hpp"

#include "people_scene.hpp"

using vtrack::InvalidArgument;
using vtrack::models::BoxStates;
using vtrack::models::TbdLikelihood;
using vtrack::models::TbdLikelihoodParams;

namespace {

cv::Mat random_image(int rows, int cols, vtrack::core::Rng& rng) {
  cv::Mat y(rows, cols, CV_32F);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) y.at<float>(r, c) = static_cast<float>(rng.uniform());
  return y;
}

struct PixelBox {
  int x0, y0, x1, y1;  // clipped, [x0, x1) x [y0, y1)
};

PixelBox clipped(const cv::Mat& y, float x, float yy, float w, float h) {
  const int x0 = static_cast<int>(std::lround(x)), y0 = static_cast<int>(std::lround(yy));
  const int x1 = static_cast<int>(std::lround(x + w)), y1 = static_cast<int>(std::lround(yy + h));
  return {std::clamp(x0, 0, y.cols), std::clamp(y0, 0, y.rows), std::clamp(x1, 0, y.cols),
          std::clamp(y1, 0, y.rows)};
}

// log g(y | X) - log f(y) by brute force from eqs. (11)-(14) and (19): fill the target regions
// with 1 to get ybar_B (eq. 13-14), then log g_B(ybar_B) + sum_j log g_F(ybar_j), minus
// log f(y) = log zeta_B + sum_i y_i / (m delta_B) (zeta_B = 1 here; it cancels). zeta_F is
// obtained by numerical integration of exp(-u / delta_F) on [0, 1].
double brute_force_log_ratio(const cv::Mat& y, const std::vector<std::array<float, 4>>& boxes,
                             const TbdLikelihoodParams& p) {
  double integral = 0.0;
  const int steps = 200000;
  for (int k = 0; k < steps; ++k) integral += std::exp(-(k + 0.5) / steps / p.delta_f) / steps;
  const double log_zeta_f = -std::log(integral);
  cv::Mat filled = y.clone();
  double log_gf = 0.0;
  for (const auto& b : boxes) {
    const PixelBox pb = clipped(y, b[0], b[1], b[2], b[3]);
    double sum = 0.0;
    int count = 0;
    for (int r = pb.y0; r < pb.y1; ++r)
      for (int c = pb.x0; c < pb.x1; ++c) {
        sum += y.at<float>(r, c);
        filled.at<float>(r, c) = 1.0f;
        ++count;
      }
    const double ybar = count ? sum / count : 1.0;
    log_gf += log_zeta_f - ybar / p.delta_f;
  }
  const double m = static_cast<double>(y.total());
  const double ybar_b = cv::sum(filled)[0] / m;              // eq. (14)
  const double log_gb = ybar_b / p.delta_b;                   // log g_B, zeta_B = 1
  const double log_f = cv::sum(y)[0] / (m * p.delta_b);       // log f(y), zeta_B = 1
  return log_gb + log_gf - log_f;
}

// Eq. (20) as printed: delta_B relative to the image's pixel count m, no closing.
TbdLikelihoodParams printed() {
  TbdLikelihoodParams p;
  p.delta_b = 2e-3;
  p.delta_b_reference = TbdLikelihoodParams::DeltaBReference::image;
  p.closing_ratio = 0.0;
  return p;
}

}  // namespace

TEST(TbdLikelihood, SeparableFormMatchesBruteForceOfEq19) {
  vtrack::core::Rng rng(5);
  TbdLikelihoodParams p = printed();
  p.delta_f = 0.3;
  p.delta_b = 0.05;
  for (int trial = 0; trial < 30; ++trial) {
    const cv::Mat y = random_image(24 + int(rng.below(20)), 30 + int(rng.below(20)), rng);
    TbdLikelihood lik(p);
    lik.set_image(y);
    // Non-overlapping boxes: one in the left third, one in the right third (possibly sticking
    // out of the image), plus sometimes one wholly outside.
    std::vector<std::array<float, 4>> boxes = {
        {float(rng.uniform(-5, 5)), float(rng.uniform(-5, 10)), float(rng.uniform(1, 9)),
         float(rng.uniform(1, 30))},
        {float(rng.uniform(22, 30)), float(rng.uniform(-5, 20)), float(rng.uniform(1, 30)),
         float(rng.uniform(1, 30))},
    };
    if (trial % 3 == 0) boxes.push_back({-50.f, -50.f, 10.f, 10.f});
    double sum = 0.0;
    for (const auto& b : boxes) sum += lik.log_likelihood(b[0], b[1], b[2], b[3]);
    EXPECT_NEAR(sum, brute_force_log_ratio(y, boxes, p), 1e-6 * (1 + std::fabs(sum)));
  }
}

// Eq. (13): the other targets' regions filled with background. Evaluating a box with those
// regions as `explained` equals evaluating it on an image where they are set to 1.
TEST(TbdLikelihood, ExplainedRegionsAreBackgroundAsInEq13) {
  vtrack::core::Rng rng(8);
  const TbdLikelihoodParams p = printed();
  for (int trial = 0; trial < 30; ++trial) {
    const cv::Mat y = random_image(40, 50, rng);
    // Two disjoint rectangles (columns < 34 and >= 35), partly outside the image at times.
    const std::vector<vtrack::image::Rect> explained = {
        {int(rng.below(20)) - 5, int(rng.below(20)) - 5, int(rng.below(20)), int(rng.below(30))},
        {35 + int(rng.below(10)), int(rng.below(30)), int(rng.below(20)), int(rng.below(20))}};
    cv::Mat filled = y.clone();
    for (const auto& e : explained) {
      const cv::Rect r = cv::Rect(e.x, e.y, e.width, e.height) & cv::Rect(0, 0, 50, 40);
      if (r.area() > 0) filled(r).setTo(1.0f);
    }
    TbdLikelihood lik(p), reference(p);
    lik.set_image(y);
    reference.set_image(filled);
    const float bx = float(rng.uniform(-10, 45)), by = float(rng.uniform(-10, 35));
    const float bw = float(rng.uniform(1, 40)), bh = float(rng.uniform(1, 40));
    EXPECT_NEAR(lik.log_likelihood(bx, by, bw, bh, explained),
                reference.log_likelihood(bx, by, bw, bh), 1e-9);
  }
}

TEST(TbdLikelihood, BatchedEqualsSingle) {
  vtrack::core::Rng rng(6);
  const cv::Mat y = random_image(40, 50, rng);
  TbdLikelihood lik(printed());
  lik.set_image(y);
  BoxStates s(4, 100);
  for (int j = 0; j < 100; ++j)
    s.col(j) << float(rng.uniform(-10, 50)), float(rng.uniform(-10, 40)),
        float(rng.uniform(0, 30)), float(rng.uniform(0, 30));
  Eigen::VectorXd out;
  lik.log_likelihood(s, out);
  ASSERT_EQ(out.size(), 100);
  for (int j = 0; j < 100; ++j)
    EXPECT_DOUBLE_EQ(out[j], lik.log_likelihood(s(0, j), s(1, j), s(2, j), s(3, j)));
}

TEST(TbdLikelihood, ForegroundScoresAboveOneBackgroundBelow) {
  cv::Mat y(100, 120, CV_32F, cv::Scalar(1.0f));
  y(cv::Rect(40, 20, 20, 50)).setTo(0.1f);
  TbdLikelihood lik;  // the defaults: delta_B relative to the person size
  lik.set_person_size(20, 50);
  lik.set_image(y);
  const double on = lik.log_likelihood(40, 20, 20, 50);
  EXPECT_GT(on, 0.0);                                     // rho > 1 raises r (eq. 23)
  EXPECT_LT(lik.log_likelihood(0, 0, 20, 50), 0.0);       // background lowers it
  EXPECT_GT(on, lik.log_likelihood(45, 25, 20, 50));      // a shifted box scores less
  EXPECT_GT(on, lik.log_likelihood(35, 15, 30, 60));      // so does a larger one
}

TEST(TbdLikelihood, AllBackgroundAndAllForegroundAreFinite) {
  for (float v : {0.0f, 1.0f}) {
    cv::Mat y(30, 40, CV_32F, cv::Scalar(v));
    TbdLikelihood lik;
    lik.set_person_size(8, 20);
    lik.set_image(y);
    for (float w : {0.0f, 1.0f, 10.0f, 100.0f}) {
      const double l = lik.log_likelihood(5, 5, w, w);
      EXPECT_TRUE(std::isfinite(l)) << v << " " << w;
    }
    EXPECT_TRUE(std::isfinite(lik.log_likelihood(-1e30f, 1e30f, 1e30f, -5.0f)));
  }
}

TEST(TbdLikelihood, ClosingRemovesSpecks) {
  cv::Mat y(40, 40, CV_32F, cv::Scalar(1.0f));
  y.at<float>(20, 20) = 0.0f;  // a one-pixel speck
  y(cv::Rect(5, 5, 6, 6)).setTo(0.0f);  // a blob larger than the element survives
  TbdLikelihoodParams p = printed();
  p.closing_size = 3;
  TbdLikelihood lik(p);
  lik.set_image(y);
  EXPECT_FLOAT_EQ(lik.processed_image().at<float>(20, 20), 1.0f);
  EXPECT_DOUBLE_EQ(lik.integral().sum({15, 15, 10, 10}), 100.0);
  EXPECT_DOUBLE_EQ(lik.integral().sum({5, 5, 6, 6}), 0.0);
}

// closing_size 0: the closing's side follows the person height (closing_ratio x height, to the
// odd number 2k + 1 for a product in [2k, 2k + 2)); below 2 px there is none.
TEST(TbdLikelihood, ClosingFollowsThePersonHeight) {
  TbdLikelihoodParams p;  // closing_size 0, closing_ratio 0.06
  TbdLikelihood lik(p);
  for (const auto& [height, side] : std::vector<std::pair<double, int>>{
           {20.0, 1}, {33.0, 1}, {34.0, 3}, {85.0, 5}, {99.0, 5}, {100.0, 7}, {127.5, 7},
           {200.0, 13}}) {
    lik.set_person_size(0.35 * height, height);
    EXPECT_EQ(lik.closing_pixels(), side) << height;
  }
  cv::Mat y(40, 40, CV_32F, cv::Scalar(1.0f));
  y.at<float>(20, 20) = 0.0f;
  lik.set_person_size(10, 30);  // 1.8 px: no closing, the speck stays
  lik.set_image(y);
  EXPECT_FLOAT_EQ(lik.processed_image().at<float>(20, 20), 0.0f);
  lik.set_person_size(20, 60);  // 3.6 px: 3 x 3
  lik.set_image(y);
  EXPECT_FLOAT_EQ(lik.processed_image().at<float>(20, 20), 1.0f);
}

// With delta_b_reference "person" a person's score does not depend on the image around them nor
// on the resolution: the same person in a larger image (a crop, inverted) and the whole scene
// upsampled 2x (boxes and person size 2x) score the same. With "image" (eq. 20 as printed) the
// larger image lowers the reward m_x (1 - ybar) / (m delta_B).
TEST(TbdLikelihood, PersonReferenceIsScaleFree) {
  cv::Mat y(100, 120, CV_32F, cv::Scalar(0.95f));
  y(cv::Rect(40, 20, 20, 50)).setTo(0.1f);
  cv::Mat large(200, 240, CV_32F, cv::Scalar(0.95f));
  y.copyTo(large(cv::Rect(0, 0, 120, 100)));
  cv::Mat up;
  cv::resize(y, up, cv::Size(240, 200), 0, 0, cv::INTER_NEAREST);
  TbdLikelihoodParams person;
  person.closing_ratio = 0.0;
  person.delta_b_reference = TbdLikelihoodParams::DeltaBReference::person;
  person.delta_b = 0.35;
  TbdLikelihood a(person), b(person), c(person);
  a.set_person_size(20, 50);
  b.set_person_size(20, 50);
  c.set_person_size(40, 100);
  a.set_image(y);
  b.set_image(large);
  c.set_image(up);
  const double score = a.log_likelihood(38, 18, 24, 54);
  EXPECT_GT(score, 0.0);
  EXPECT_NEAR(b.log_likelihood(38, 18, 24, 54), score, 1e-9);
  EXPECT_NEAR(c.log_likelihood(76, 36, 48, 108), score, 1e-9);
  TbdLikelihood d(printed()), e(printed());
  d.set_image(y);
  e.set_image(large);
  EXPECT_LT(e.log_likelihood(38, 18, 24, 54), d.log_likelihood(38, 18, 24, 54) - 1.0);
}

namespace {

// The box that maximises log g_y among boxes centred on the person's column whose half-width,
// top and bottom are fractions 0.3, 0.32, ..., 1.3 of the person's half-size from its centre
// (brute force; the profile and the row weights are mirror-symmetric in x): the fractions of
// the best box as (half-width, top, bottom).
std::array<double, 3> best_box_fractions(const TbdLikelihood& lik, double cx, double cy, double w,
                                         double h) {
  double best = -std::numeric_limits<double>::infinity();
  std::array<double, 3> arg{};
  for (int i = 0; i <= 50; ++i)
    for (int t = 0; t <= 50; ++t)
      for (int b = 0; b <= 50; ++b) {
        const double fx = 0.3 + 0.02 * i, ft = 0.3 + 0.02 * t, fb = 0.3 + 0.02 * b;
        const double score = lik.log_likelihood(float(cx - fx * 0.5 * w), float(cy - ft * 0.5 * h),
                                                float(fx * w), float((ft + fb) * 0.5 * h));
        if (score > best) best = score, arg = {fx, ft, fb};
      }
  return arg;
}

}  // namespace

// The "row" reference (delta_b): people 80, 160 and 320 px tall, each centred on the row where the
// person height line puts a person of their size (h = 0.8 row, a(row) = 0.4 h(row)^2), all of one
// shape. The best box covers the same fraction of each of them with "row", because k =
// m_x a delta_F / (a(row) m delta_B) is the same for each; with eq. (20) as printed ("image", the
// same delta_B, which the middle person's k equals), k is 16 times larger for the near person
// than for the far one, and the best box takes more of the border the nearer the person.
TEST(TbdLikelihood, RowReferenceFitsPeopleOfEverySizeAlike) {
  const std::array<double, 3> heights = {80.0, 160.0, 320.0};
  cv::Mat y(600, 560, CV_32F, cv::Scalar(1.0f));
  std::array<double, 3> cxs = {60.0, 180.0, 400.0};
  for (int k = 0; k < 3; ++k) {
    people_scene::render_person(y, cxs[k], heights[k] / 0.8, 0.4 * heights[k], heights[k]);
  }
  std::vector<double> areas(static_cast<std::size_t>(y.rows));
  for (int r = 0; r < y.rows; ++r) {
    const double hr = 0.8 * std::max(r + 0.5, 1.0);
    areas[std::size_t(r)] = 0.4 * hr * hr;
  }
  // delta_B such that a person-sized box earns (1 - ybar) / 0.35 at the middle person's size.
  TbdLikelihoodParams image = printed();
  image.delta_b = 0.35 * 0.4 * 160 * 160 / double(y.total());
  TbdLikelihood printed_lik(image);
  printed_lik.set_image(y);
  TbdLikelihoodParams row = image;
  row.delta_b_reference = TbdLikelihoodParams::DeltaBReference::row;
  row.delta_b_row = 10.0;  // without row areas delta_b_no_line holds, not this
  row.delta_b_no_line = 0.9;
  TbdLikelihood by_row(row);
  by_row.set_person_size(0.4 * 160, 160);
  by_row.set_image(y);  // no row areas yet: every row's area is the prior's,
  // i.e. eq. (20) with m delta_B = 0.4 x 160 x 160 px x 0.9.
  TbdLikelihoodParams constant_area = printed();
  constant_area.delta_b = 0.9 * 0.4 * 160 * 160 / double(y.total());
  TbdLikelihood constant_lik(constant_area);
  constant_lik.set_image(y);
  for (const auto& b : std::vector<std::array<float, 4>>{{40, 60, 40, 90}, {150, 100, 70, 200}}) {
    EXPECT_NEAR(by_row.log_likelihood(b[0], b[1], b[2], b[3]),
                constant_lik.log_likelihood(b[0], b[1], b[2], b[3]), 1e-4);
  }
  // With row areas a person-sized box earns (1 - ybar) / delta_b_row: as the printed one here
  // at the middle person's size.
  row.delta_b_row = 0.35;
  TbdLikelihood weighted(row);
  weighted.set_person_size(0.4 * 160, 160);
  weighted.set_row_areas(areas);
  weighted.set_image(y);
  std::array<std::array<double, 3>, 3> fr_row{}, fr_image{};
  for (int k = 0; k < 3; ++k) {
    const double h = heights[k], w = 0.4 * h, cy = h / 0.8;
    fr_row[k] = best_box_fractions(weighted, cxs[k], cy, w, h);
    fr_image[k] = best_box_fractions(printed_lik, cxs[k], cy, w, h);
  }
  for (int k = 0; k < 3; ++k)
    for (int e = 0; e < 3; ++e) {
      // Pixel rounding of the smallest person's edges: 0.5 px of 16 (x) or 40 (y) px.
      EXPECT_NEAR(fr_row[k][e], fr_row[1][e], 0.05) << "person " << k << " edge " << e;
    }
  // (Measured: "row" 0.54-0.58 for every person and edge; "image" 0.48-0.50 far, 0.76 near.)
  for (int e = 0; e < 3; ++e) EXPECT_GT(fr_image[2][e], fr_image[0][e] + 0.15) << "edge " << e;
}

TEST(TbdLikelihood, RejectsBadImagesAndParameters) {
  TbdLikelihood lik;
  cv::Mat y(10, 10, CV_32F, cv::Scalar(0.5f));
  y.at<float>(3, 4) = std::numeric_limits<float>::quiet_NaN();
  try {
    lik.set_image(y);
    FAIL() << "NaN accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("row 3, column 4"), std::string::npos) << e.what();
  }
  y.at<float>(3, 4) = 1.5f;
  EXPECT_THROW(lik.set_image(y), InvalidArgument);
  EXPECT_THROW(lik.set_image(cv::Mat(10, 10, CV_8U, cv::Scalar(1))), InvalidArgument);
  EXPECT_THROW(lik.set_image(cv::Mat()), InvalidArgument);
  for (auto bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    TbdLikelihoodParams p;
    p.delta_f = bad;
    EXPECT_THROW(TbdLikelihood{p}, InvalidArgument);
    p = {};
    p.delta_b = bad;
    try {
      TbdLikelihood{p};
      FAIL();
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("delta_b"), std::string::npos);
    }
  }
  TbdLikelihoodParams p;
  p.closing_size = 4;
  EXPECT_THROW(TbdLikelihood{p}, InvalidArgument);
  p = {};
  p.closing_ratio = -0.5;
  EXPECT_THROW(TbdLikelihood{p}, InvalidArgument);
  // The defaults refer to the person size: an image before set_person_size is an error.
  TbdLikelihood unsized;
  try {
    unsized.set_image(cv::Mat(10, 10, CV_32F, cv::Scalar(0.5f)));
    FAIL() << "no person size accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("set_person_size"), std::string::npos) << e.what();
  }
  EXPECT_THROW(unsized.set_person_size(0.0, 10.0), InvalidArgument);
}
