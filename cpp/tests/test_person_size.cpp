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

// Counted once each, big enough to be a person: three people of heights 40, 60 and 80 and a
// group three people high (half the area counted: area-weighting would favour it);
// specks below the area floor, fragments below a person of half the height (a 4 x 8 piece), and
// a tall component cut by the top border are not counted. The count median of 40, 60, 80, 230
// lies between 60 and 80 (the median of four, interpolated in log2 within the bins).
TEST(ForegroundSizeEstimator, CountsPeopleNotGroupsSpecksOrTheBorder) {
  ForegroundSizeEstimator est(std::numeric_limits<double>::infinity(), 1e-4, 0.25);  // floor 7.7 px
  EXPECT_EQ(est.person_height(), 0.0);
  std::vector<cv::Rect> blobs = {{10, 10, 10, 40}, {30, 10, 15, 60}, {60, 10, 20, 80},
                                 {90, 0, 10, 240},    // cut by the top border
                                 {110, 5, 12, 230}};  // a group of three
  for (int k = 0; k < 30; ++k) blobs.push_back({150 + 5 * (k % 20), 150 + 4 * (k / 20), 2, 2});
  for (int k = 0; k < 6; ++k) blobs.push_back({150 + 8 * k, 200, 4, 8});  // fragments
  est.observe(with_blobs(blobs));
  EXPECT_GE(est.person_height(), 60.0 / 1.045);
  EXPECT_LE(est.person_height(), 80.0 * 1.045);
  // Counted: 400 + 900 + 1600 + 2760 + 6 x 32; the specks are under the floor, the column is on
  // the top border.
  EXPECT_DOUBLE_EQ(est.weight(), 400.0 + 900.0 + 1600.0 + 12.0 * 230.0 + 6 * 32.0);
  EXPECT_EQ(est.frames(), 1);
  // With many single people the group is one count among many: the estimate is a person's.
  for (int k = 0; k < 5; ++k) est.observe(with_blobs({{10, 10, 20, 60}, {40, 10, 20, 60},
                                                      {70, 10, 20, 60}, {110, 5, 30, 180}}));
  EXPECT_NEAR(est.person_height(), 60.0, 60.0 * 0.045);
}

// With a half-life of 5 frames, after 40 frames of 100 px people the 50 px people seen before
// weigh 2^-8 as much: the median follows the scene.
TEST(ForegroundSizeEstimator, ForgetsWithTheHalfLife) {
  ForegroundSizeEstimator est(5.0, 0.0);
  for (int k = 0; k < 40; ++k) est.observe(with_blobs({{10, 10, 20, 50}, {60, 10, 20, 50}}));
  EXPECT_NEAR(est.person_height(), 50.0, 50.0 * 0.045);
  for (int k = 0; k < 40; ++k) est.observe(with_blobs({{10, 10, 40, 100}}));
  EXPECT_NEAR(est.person_height(), 100.0, 100.0 * 0.045);
  // Decayed total: each frame's 4000 px, a geometric sum with ratio 2^(-1/5).
  const double q = std::exp2(-1.0 / 5.0);
  EXPECT_NEAR(est.weight(), 4000.0 * (1 - std::pow(q, 40)) / (1 - q) +
                                2000.0 * std::pow(q, 40) * (1 - std::pow(q, 40)) / (1 - q),
              1e-6 * est.weight());
  est.reset();
  EXPECT_EQ(est.person_height(), 0.0);
}

TEST(ForegroundSizeEstimator, RejectsBadArguments) {
  EXPECT_THROW(ForegroundSizeEstimator(0.0), InvalidArgument);
  EXPECT_THROW(ForegroundSizeEstimator(10.0, 1.0), InvalidArgument);
  EXPECT_THROW(ForegroundSizeEstimator(10.0, 0.0, 0.0), InvalidArgument);
  ForegroundSizeEstimator est;
  EXPECT_THROW(est.observe(cv::Mat()), InvalidArgument);
  EXPECT_THROW(est.observe(cv::Mat(10, 10, CV_8U, cv::Scalar(0))), InvalidArgument);
  est.observe(cv::Mat(10, 10, CV_32F, cv::Scalar(1.0f)));  // no foreground: nothing learnt
  EXPECT_EQ(est.person_height(), 0.0);
  EXPECT_EQ(est.weight(), 0.0);
}
