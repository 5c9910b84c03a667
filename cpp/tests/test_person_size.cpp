#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <opencv2/core.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/models/person_size.hpp"

using vtrack::InvalidArgument;
using vtrack::models::ForegroundSizeEstimator;

namespace {

// A background image (y = 1) with dark rectangles (y = 0.1) of the given (x, y, w, h).
cv::Mat with_blobs(const std::vector<cv::Rect>& blobs, int width = 320, int height = 240) {
  cv::Mat y(height, width, CV_32F, cv::Scalar(1.0f));
  for (const auto& r : blobs) y(r).setTo(0.1f);
  return y;
}

}  // namespace

// Area-weighted median of the component heights: blobs of heights 40 (area 400), 60 (area 1200)
// and 80 (area 800) have total area 2400, so the median falls in the 60 px component; specks
// below the area floor are ignored and do not pull it down.
TEST(ForegroundSizeEstimator, AreaWeightedMedianHeight) {
  ForegroundSizeEstimator est(std::numeric_limits<double>::infinity(), 1e-3);  // floor 76.8 px
  EXPECT_EQ(est.median_height(), 0.0);
  std::vector<cv::Rect> blobs = {{10, 10, 10, 40}, {50, 10, 20, 60}, {100, 10, 10, 80}};
  for (int k = 0; k < 30; ++k) blobs.push_back({150 + 5 * (k % 20), 150 + 4 * (k / 20), 2, 2});
  est.observe(with_blobs(blobs));
  // Within the bin (1/32 octave, 2.2 %) holding 60.
  EXPECT_NEAR(est.median_height(), 60.0, 60.0 * 0.022);
  EXPECT_DOUBLE_EQ(est.weight(), 2400.0);
  EXPECT_EQ(est.frames(), 1);
}

// With a half-life of 5 frames, after 40 frames of 100 px people the 50 px people seen before
// weigh 2^-8 as much: the median follows the scene.
TEST(ForegroundSizeEstimator, ForgetsWithTheHalfLife) {
  ForegroundSizeEstimator est(5.0, 0.0);
  for (int k = 0; k < 40; ++k) est.observe(with_blobs({{10, 10, 20, 50}, {60, 10, 20, 50}}));
  EXPECT_NEAR(est.median_height(), 50.0, 50.0 * 0.022);
  for (int k = 0; k < 40; ++k) est.observe(with_blobs({{10, 10, 40, 100}}));
  EXPECT_NEAR(est.median_height(), 100.0, 100.0 * 0.022);
  // Decayed total: each frame's 4000 px, a geometric sum with ratio 2^(-1/5).
  const double q = std::exp2(-1.0 / 5.0);
  EXPECT_NEAR(est.weight(), 4000.0 * (1 - std::pow(q, 40)) / (1 - q) +
                                2000.0 * std::pow(q, 40) * (1 - std::pow(q, 40)) / (1 - q),
              1e-6 * est.weight());
  est.reset();
  EXPECT_EQ(est.median_height(), 0.0);
}

TEST(ForegroundSizeEstimator, RejectsBadArguments) {
  EXPECT_THROW(ForegroundSizeEstimator(0.0), InvalidArgument);
  EXPECT_THROW(ForegroundSizeEstimator(10.0, 1.0), InvalidArgument);
  ForegroundSizeEstimator est;
  EXPECT_THROW(est.observe(cv::Mat()), InvalidArgument);
  EXPECT_THROW(est.observe(cv::Mat(10, 10, CV_8U, cv::Scalar(0))), InvalidArgument);
  est.observe(cv::Mat(10, 10, CV_32F, cv::Scalar(1.0f)));  // no foreground: nothing learnt
  EXPECT_EQ(est.median_height(), 0.0);
  EXPECT_EQ(est.weight(), 0.0);
}
