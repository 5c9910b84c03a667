#include <gtest/gtest.h>
#include <algorithm>
#include <array>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <vector>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/image/color.hpp"
#include "vtrack/image/components.hpp"
#include "vtrack/image/integral_image.hpp"

using namespace vtrack::image;

namespace {

double brute_force_sum(const cv::Mat& image, const Rect& r) {
  double total = 0;
  for (int y = std::max(r.y, 0); y < std::min(r.y + r.height, image.rows); ++y) {
    for (int x = std::max(r.x, 0); x < std::min(r.x + r.width, image.cols); ++x) {
      total += image.at<float>(y, x);
    }
  }
  return total;
}

}  // namespace

TEST(IntegralImage, RectangleSumsMatchBruteForce) {
  vtrack::core::Rng rng(31);
  for (int trial = 0; trial < 20; ++trial) {
    const int rows = 1 + static_cast<int>(rng.below(60));
    const int cols = 1 + static_cast<int>(rng.below(80));
    cv::Mat image(rows, cols, CV_32F);
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < cols; ++x) image.at<float>(y, x) = static_cast<float>(rng.uniform());
    IntegralImage ii(image);
    ASSERT_EQ(ii.rows(), rows);
    ASSERT_EQ(ii.cols(), cols);
    for (int k = 0; k < 200; ++k) {
      // Corners from well outside the image on every side, sizes including 0 and negative.
      const Rect r{static_cast<int>(rng.below(cols + 40)) - 20,
                   static_cast<int>(rng.below(rows + 40)) - 20,
                   static_cast<int>(rng.below(cols + 10)) - 5,
                   static_cast<int>(rng.below(rows + 10)) - 5};
      EXPECT_NEAR(ii.sum(r), brute_force_sum(image, r), 1e-9)
          << "rect " << r.x << "," << r.y << "," << r.width << "," << r.height;
      const Rect c = ii.clip(r);
      EXPECT_EQ(ii.area(r), static_cast<long long>(c.width) * c.height);
    }
  }
}

TEST(IntegralImage, EdgeCases) {
  cv::Mat ones(10, 20, CV_32F, cv::Scalar(1.0f));
  IntegralImage ii(ones);
  EXPECT_EQ(ii.sum({0, 0, 20, 10}), 200.0);
  EXPECT_EQ(ii.sum({-100, -100, 1000, 1000}), 200.0);  // covers the image
  EXPECT_EQ(ii.sum({20, 0, 5, 5}), 0.0);               // just right of the image
  EXPECT_EQ(ii.area({20, 0, 5, 5}), 0);
  EXPECT_EQ(ii.sum({5, 5, 0, 3}), 0.0);                // empty
  EXPECT_EQ(ii.sum({5, 5, -3, 3}), 0.0);               // negative width
  EXPECT_EQ(ii.sum({18, 8, 5, 5}), 4.0);               // partly outside
  EXPECT_EQ(ii.sum({2147483600, 0, 2147483000, 5}), 0.0);  // no integer overflow
  cv::Mat bytes(4, 4, CV_8U, cv::Scalar(255));
  EXPECT_EQ(IntegralImage(bytes).sum({0, 0, 4, 4}), 16 * 255.0);
}

TEST(IntegralImage, RejectsBadImages) {
  EXPECT_THROW(IntegralImage(cv::Mat()), vtrack::InvalidArgument);
  EXPECT_THROW(IntegralImage(cv::Mat(3, 3, CV_32FC3)), vtrack::InvalidArgument);
  EXPECT_THROW(IntegralImage(cv::Mat(3, 3, CV_16S)), vtrack::InvalidArgument);
  EXPECT_THROW(IntegralImage().sum({0, 0, 1, 1}), vtrack::InvalidArgument);
}

TEST(Rgi, MatchesEquationsSixToEight) {
  cv::Mat bgr(2, 3, CV_8UC3);
  const cv::Vec3b pixels[] = {{10, 20, 30}, {0, 0, 0}, {255, 255, 255},
                              {0, 0, 1},    {7, 0, 0}, {100, 200, 50}};
  for (int i = 0; i < 6; ++i) bgr.at<cv::Vec3b>(i / 3, i % 3) = pixels[i];
  cv::Mat rgi;
  bgr_to_rgi(bgr, rgi);
  ASSERT_EQ(rgi.type(), CV_32FC3);
  for (int i = 0; i < 6; ++i) {
    const double b = pixels[i][0], g = pixels[i][1], r = pixels[i][2];
    const double s = r + g + b;
    const cv::Vec3f out = rgi.at<cv::Vec3f>(i / 3, i % 3);
    EXPECT_NEAR(out[0], s > 0 ? r / s : 1.0 / 3.0, 1e-6);
    EXPECT_NEAR(out[1], s > 0 ? g / s : 1.0 / 3.0, 1e-6);
    EXPECT_NEAR(out[2], s / 765.0, 1e-6);
  }
}

TEST(Rgi, RejectsBadFrames) {
  cv::Mat out;
  EXPECT_THROW(bgr_to_rgi(cv::Mat(), out), vtrack::InvalidArgument);
  EXPECT_THROW(bgr_to_rgi(cv::Mat(4, 4, CV_8UC1), out), vtrack::InvalidArgument);
  EXPECT_THROW(bgr_to_rgi(cv::Mat(4, 4, CV_32FC3), out), vtrack::InvalidArgument);
}

namespace {

// The rows 1..n-1 of a stats matrix as (top, left, width, height, area), sorted.
std::vector<std::array<int, 5>> components_in_order(const cv::Mat& stats) {
  std::vector<std::array<int, 5>> out;
  for (int i = 1; i < stats.rows; ++i) {
    const int* s = stats.ptr<int>(i);
    out.push_back({s[cv::CC_STAT_TOP], s[cv::CC_STAT_LEFT], s[cv::CC_STAT_WIDTH],
                   s[cv::CC_STAT_HEIGHT], s[cv::CC_STAT_AREA]});
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

// image::connected_components against cv::connectedComponentsWithStats on masks of blobs, noise
// and edge cases: the same number of components, numbered alike, each with the same box and area.
TEST(ConnectedComponents, MatchOpenCvStats) {
  cv::RNG rng(7);
  std::vector<cv::Mat> masks;
  for (int k = 0; k < 24; ++k) {
    // The last four are frame-sized, where OpenCV labels in parallel stripes.
    const bool large = k >= 20;
    cv::Mat m = cv::Mat::zeros(large ? 576 : rng.uniform(1, 90), large ? 768 : rng.uniform(1, 120),
                               CV_8U);
    if (k % 2 == 0) {
      rng.fill(m, cv::RNG::UNIFORM, 0, 256);
      m = m > rng.uniform(100, 250);  // speckle: many small components touching the borders
    } else {
      for (int e = 0; e < (large ? 40 : 6); ++e) {
        cv::ellipse(m, {rng.uniform(0, m.cols), rng.uniform(0, m.rows)},
                    {rng.uniform(1, 20), rng.uniform(1, 30)}, rng.uniform(0, 180), 0, 360, 255,
                    -1);
      }
    }
    masks.push_back(m);
  }
  masks.push_back(cv::Mat::zeros(5, 7, CV_8U));          // no component
  masks.push_back(cv::Mat(5, 7, CV_8U, cv::Scalar(1)));  // one component, the whole image
  cv::Mat diagonal = cv::Mat::eye(9, 9, CV_8U);           // touching at corners only (8-connected)
  diagonal.at<uchar>(0, 8) = diagonal.at<uchar>(1, 7) = 1;
  masks.push_back(diagonal);
  cv::Mat comb = cv::Mat::zeros(6, 11, CV_8U);  // teeth joined only by the last row
  for (int c = 0; c < comb.cols; c += 2) comb.col(c).setTo(1);
  comb.row(5).setTo(1);
  masks.push_back(comb);
  for (const cv::Mat& mask : masks) {
    cv::Mat stats, ref_labels, ref_stats, centroids;
    const int n = connected_components(mask, stats);
    const int ref_n =
        cv::connectedComponentsWithStats(mask, ref_labels, ref_stats, centroids, 8, CV_32S);
    ASSERT_EQ(n, ref_n);
    ASSERT_EQ(stats.rows, n);
    EXPECT_EQ(cv::countNonZero(stats.row(0)), 0);
    // OpenCV numbers components in the order of the 2 x 2 blocks its scan visits; ours are in
    // raster order of their first pixel (documented), so compare them ordered by their first row
    // and then their left edge (components are disjoint, so no two share both).
    EXPECT_EQ(components_in_order(stats), components_in_order(ref_stats));
    for (int i = 2; i < n; ++i) {
      EXPECT_LE(stats.at<int>(i - 1, cv::CC_STAT_TOP), stats.at<int>(i, cv::CC_STAT_TOP));
    }
  }
  cv::Mat stats;
  EXPECT_THROW(connected_components(cv::Mat(), stats), vtrack::InvalidArgument);
  EXPECT_THROW(connected_components(cv::Mat::zeros(3, 3, CV_32F), stats), vtrack::InvalidArgument);
}
