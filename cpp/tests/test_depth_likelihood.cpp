#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/core.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/models/depth_likelihood.hpp"

using namespace vtrack;
using models::DepthLikelihood;
using models::DepthLikelihoodParams;

namespace {

DepthLikelihoodParams small_camera() {
  DepthLikelihoodParams p;
  p.camera = {60.0, 55.0, 19.5, 14.5, 40, 30};
  p.person_width = 0.5;
  p.person_height = 1.7;
  p.sigma_target = 0.3;
  p.sigma_background = 0.8;
  p.tempering = 0.37;
  return p;
}

// Eq. (4)'s log ratio by a loop over the footprint's pixels, the footprint computed here from
// the pinhole formulas (round to the nearest pixel edge, clip), independently of the model.
// Pixels inside an occluder that hides the state (D > hides_beyond) are skipped.
double brute_force_log_ratio(const DepthLikelihoodParams& p, const cv::Mat& d, double X, double Y,
                             double D, const std::vector<models::Occluder>& occluders = {}) {
  if (D <= p.min_depth) return 0.0;
  const auto& c = p.camera;
  const double u = c.cx + c.fx * X / D, v = c.cy + c.fy * Y / D;
  const double a = c.fx * p.person_width / (2 * D), b = c.fy * p.person_height / (2 * D);
  const int x0 = std::max(0, static_cast<int>(std::floor(u - a + 0.5)));
  const int x1 = std::min(c.width, static_cast<int>(std::floor(u + a + 0.5)));
  const int y0 = std::max(0, static_cast<int>(std::floor(v - b + 0.5)));
  const int y1 = std::min(c.height, static_cast<int>(std::floor(v + b + 0.5)));
  const double log2pi = std::log(2 * M_PI);
  double total = 0.0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      bool hidden = false;
      for (const auto& o : occluders) {
        hidden = hidden || (D > o.hides_beyond && x >= o.rect.x && x < o.rect.x + o.rect.width &&
                            y >= o.rect.y && y < o.rect.y + o.rect.height);
      }
      if (hidden) continue;
      const double di = d.at<float>(y, x);
      const double log_phi = -0.5 * log2pi - std::log(p.sigma_target) -
                             (di - D) * (di - D) / (2 * p.sigma_target * p.sigma_target);
      const double log_varphi = -0.5 * log2pi - std::log(p.sigma_background) -
                                di * di / (2 * p.sigma_background * p.sigma_background);
      total += log_phi - log_varphi;
    }
  }
  return p.tempering * total;
}

}  // namespace

TEST(Kinect, RawToDepthIsEquation3) {
  // T = 8 B F_x / (W_max - w) = 8 * 0.075 * 525 / (1084 - 1000) = 315 / 84.
  EXPECT_DOUBLE_EQ(models::kinect_raw_to_depth(1000.0, 525.0), 315.0 / 84.0);
  EXPECT_DOUBLE_EQ(models::kinect_raw_to_depth(0.0, 600.0), 8 * 0.075 * 600 / 1084.0);
  // No reading: at or beyond W_max, negative, NaN.
  EXPECT_EQ(models::kinect_raw_to_depth(1084.0, 525.0), 0.0);
  EXPECT_EQ(models::kinect_raw_to_depth(2047.0, 525.0), 0.0);
  EXPECT_EQ(models::kinect_raw_to_depth(-1.0, 525.0), 0.0);
  EXPECT_EQ(models::kinect_raw_to_depth(std::nan(""), 525.0), 0.0);
}

TEST(Kinect, DepthToRawInvertsEquation3) {
  for (double T = 0.3; T < 20.0; T *= 1.17) {
    const double raw = models::kinect_depth_to_raw(T, 525.0);
    ASSERT_GE(raw, 0.0);
    ASSERT_LT(raw, 1084.0);
    EXPECT_NEAR(models::kinect_raw_to_depth(raw, 525.0), T, 1e-12 * T) << T;
  }
  // Nearer than the sensor's minimum 315 / 1084 m, zero, negative: no reading (-> 0 again).
  for (double T : {0.2, 0.0, -1.0, std::nan("")}) {
    EXPECT_EQ(models::kinect_depth_to_raw(T, 525.0), models::kKinectNoReading) << T;
    EXPECT_EQ(models::kinect_raw_to_depth(models::kinect_depth_to_raw(T, 525.0), 525.0), 0.0);
  }
}

TEST(DepthLikelihood, IntegralImagesMatchABruteForcePixelSum) {
  const auto p = small_camera();
  const DepthLikelihood model(p);
  core::Rng rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    cv::Mat d(30, 40, CV_32F);
    for (int y = 0; y < d.rows; ++y) {
      for (int x = 0; x < d.cols; ++x) {
        // Background zeros and people-like depths, as a background-subtracted image.
        d.at<float>(y, x) = rng.uniform() < 0.4 ? 0.0f : static_cast<float>(rng.uniform(1.0, 6.0));
      }
    }
    const auto frame = model.frame(d);
    Eigen::Matrix3Xd x(3, 200);
    for (int i = 0; i < x.cols(); ++i) {
      // Positions that put footprints inside, across the border and wholly outside the image,
      // and a few at or behind the camera.
      const double D = i % 50 == 0 ? -1.0 : rng.uniform(0.5, 7.0);
      x.col(i) << rng.uniform(-4.0, 4.0), rng.uniform(-3.0, 3.0), D;
    }
    Eigen::VectorXd out(x.cols());
    model.log_ratio(frame, x, out);
    int clipped = 0;
    for (int i = 0; i < x.cols(); ++i) {
      const double expected = brute_force_log_ratio(p, d, x(0, i), x(1, i), x(2, i));
      EXPECT_NEAR(out[i], expected, 1e-9 * (1.0 + std::abs(expected))) << "trial " << trial;
      const auto r = model.footprint(x(0, i), x(1, i), x(2, i));
      EXPECT_GE(r.x, 0);
      EXPECT_GE(r.y, 0);
      EXPECT_LE(r.x + r.width, 40);
      EXPECT_LE(r.y + r.height, 30);
      if (r.width > 0 && (r.x == 0 || r.y == 0 || r.x + r.width == 40 || r.y + r.height == 30)) {
        ++clipped;
      }
    }
    EXPECT_GT(clipped, 10);  // the border case was exercised
  }
}

TEST(DepthLikelihood, OccludedPixelsAreLeftOutOfTheProduct) {
  const auto p = small_camera();
  const DepthLikelihood model(p);
  core::Rng rng(5);
  cv::Mat d(30, 40, CV_32F);
  for (int y = 0; y < d.rows; ++y) {
    for (int x = 0; x < d.cols; ++x) {
      d.at<float>(y, x) = rng.uniform() < 0.4 ? 0.0f : static_cast<float>(rng.uniform(1.0, 6.0));
    }
  }
  auto frame = model.frame(d);
  // Two disjoint occluders at different depths: each hides only the states behind it.
  frame.occluders = {{{5, 2, 12, 20}, 2.5}, {{22, 8, 10, 15}, 4.0}};
  Eigen::Matrix3Xd x(3, 300);
  for (int i = 0; i < x.cols(); ++i) {
    x.col(i) << rng.uniform(-2.0, 2.0), rng.uniform(-1.5, 1.5), rng.uniform(0.5, 7.0);
  }
  Eigen::VectorXd out(x.cols());
  model.log_ratio(frame, x, out);
  int hidden_states = 0;
  for (int i = 0; i < x.cols(); ++i) {
    const double expected = brute_force_log_ratio(p, d, x(0, i), x(1, i), x(2, i), frame.occluders);
    EXPECT_NEAR(out[i], expected, 1e-9 * (1.0 + std::abs(expected))) << i;
    hidden_states += std::abs(expected - brute_force_log_ratio(p, d, x(0, i), x(1, i), x(2, i))) > 1e-9;
  }
  EXPECT_GT(hidden_states, 50);  // occlusion changed many scores
}

TEST(DepthLikelihood, PrefersTheTrueDepthAndPosition) {
  auto p = small_camera();
  p.tempering = 1.0;
  const DepthLikelihood model(p);
  cv::Mat d = cv::Mat::zeros(30, 40, CV_32F);
  const auto r = model.footprint(0.0, 0.0, 4.0);
  d(cv::Rect(r.x, r.y, r.width, r.height)).setTo(4.0f);
  Eigen::Matrix3Xd x(3, 4);
  x << 0.0, 0.0, 1.0, 0.0,  //
      0.0, 0.0, 0.0, 0.0,   //
      4.0, 5.0, 4.0, 4.0;
  Eigen::VectorXd out(4);
  model.log_ratio(model.frame(d), x, out);
  EXPECT_GT(out[0], 0.0);  // the target's footprint on the target: evidence for it
  EXPECT_GT(out[0], out[1]);
  EXPECT_GT(out[0], out[2]);
  EXPECT_DOUBLE_EQ(out[0], out[3]);
}

TEST(DepthLikelihood, RejectsBadImagesAndParameters) {
  const DepthLikelihood model(small_camera());
  EXPECT_THROW(model.frame(cv::Mat::zeros(31, 40, CV_32F)), InvalidArgument);
  EXPECT_THROW(model.frame(cv::Mat::zeros(30, 40, CV_8U)), InvalidArgument);
  cv::Mat nan = cv::Mat::zeros(30, 40, CV_32F);
  nan.at<float>(3, 4) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(model.frame(nan), InvalidArgument);
  cv::Mat negative = cv::Mat::zeros(30, 40, CV_64F);
  negative.at<double>(0, 0) = -1.0;
  EXPECT_THROW(model.frame(negative), InvalidArgument);
  auto bad = small_camera();
  bad.tempering = 0.0;
  EXPECT_THROW(DepthLikelihood{bad}, InvalidArgument);
  bad = small_camera();
  bad.sigma_target = -1.0;
  EXPECT_THROW(DepthLikelihood{bad}, InvalidArgument);
  bad = small_camera();
  bad.camera.width = 0;
  EXPECT_THROW(DepthLikelihood{bad}, InvalidArgument);
}
