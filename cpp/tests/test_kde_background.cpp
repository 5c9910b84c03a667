// KdeBackground (eq. 10), its sample schedule, freeze/resume/reset, errors; close_square against
// cv::morphologyEx; foreground_mask.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/image/kde_background.hpp"
#include "vtrack/image/morphology.hpp"

using namespace vtrack::image;

namespace {

// A frame of one colour: B = G = 40, R = level.
cv::Mat flat(int level, int rows = 6, int cols = 9) {
  return cv::Mat(rows, cols, CV_8UC3, cv::Scalar(40, 40, level));
}

KdeBackgroundParams no_closing(int n_samples, int period) {
  KdeBackgroundParams p;
  p.n_samples = n_samples;
  p.period = period;
  p.closing = 0;
  p.threads = 1;
  p.update_threshold = 0.0;  // the paper's stack: every K0-th frame whole (eq. 10's schedule)
  return p;
}

// Eq. (10) for one pixel in double precision, written independently of the implementation.
double kernel_product(const cv::Vec3b& a, const cv::Vec3b& b, const KdeBackgroundParams& p) {
  auto rgi = [](const cv::Vec3b& v) {
    const double s = double(v[0]) + v[1] + v[2];
    return std::vector<double>{s > 0 ? v[2] / s : 1.0 / 3, s > 0 ? v[1] / s : 1.0 / 3, s / 765.0};
  };
  const auto x = rgi(a), m = rgi(b);
  const double sigma[3] = {p.bandwidth[0], p.bandwidth[1], p.bandwidth[2]};
  double e = 0;
  for (int d = 0; d < 3; ++d) e += (x[d] - m[d]) * (x[d] - m[d]) / (2 * sigma[d] * sigma[d]);
  return std::exp(-e);
}

double expected_y(const cv::Mat& frame, const std::vector<cv::Mat>& stack, int row, int col,
                  const KdeBackgroundParams& p) {
  double sum = 0;
  for (const auto& s : stack) sum += kernel_product(frame.at<cv::Vec3b>(row, col), s.at<cv::Vec3b>(row, col), p);
  return sum / stack.size();
}

}  // namespace

// The schedule of section 3.1, frame by frame: frames 0, K0, ..., (N0-1) K0 fill the stack; from
// N0 K0 on, the oldest is replaced every K0 frames.
TEST(KdeBackground, SampleScheduleFrameByFrame) {
  const int n0 = 3, k0 = 4;
  KdeBackground model(no_closing(n0, k0));
  cv::Mat y;
  for (int k = 0; k < 40; ++k) {
    model.apply(flat(k), y);
    std::vector<long long> expected;
    const long long newest = k0 * (k / k0);
    for (long long t = std::max(0LL, newest - (n0 - 1) * k0); t <= newest; t += k0) expected.push_back(t);
    ASSERT_EQ(model.sample_frames(), expected) << "frame " << k;
    ASSERT_EQ(model.frame_index(), k + 1);
  }
}

// The values of y follow the same schedule: each frame's colour identifies it, so y at frame k
// must equal eq. (10) against exactly the frames the schedule says are in the stack.
TEST(KdeBackground, ValuesMatchEquationTenOnTheSchedule) {
  KdeBackgroundParams p = no_closing(3, 2);
  p.bandwidth[0] = 0.01;  // consecutive levels differ by ~0.0025 in r: distinguishable kernels
  KdeBackground model(p);
  std::vector<cv::Mat> frames, stack;
  cv::Mat y;
  for (int k = 0; k < 12; ++k) {
    frames.push_back(flat(60 + 4 * k));
    if (k % 2 == 0) {
      stack.push_back(frames.back());
      if (stack.size() > 3) stack.erase(stack.begin());
    }
    model.apply(frames.back(), y);
    ASSERT_EQ(y.type(), CV_32FC1);
    EXPECT_NEAR(y.at<float>(2, 3), expected_y(frames.back(), stack, 2, 3, p), 1e-6) << "frame " << k;
  }
}

// A 16 x 12 frame of background colour A, with person B in the square (4, 3, 5, 4) if `person`.
// A and B are far apart in rgI, so each kernel between them is 0 (to 1e-30).
static cv::Mat square_scene(bool person) {
  const cv::Vec3b a(50, 100, 150), b(200, 30, 60);
  cv::Mat f(12, 16, CV_8UC3, cv::Scalar(a[0], a[1], a[2]));
  if (person) f(cv::Rect(4, 3, 5, 4)).setTo(cv::Scalar(b[0], b[1], b[2]));
  return f;
}

// Selective update (beyond the paper): a person present on one sample frame leaves no ghost, and
// one present on every sample frame is absorbed after update_max_skips skips. Background A and
// person B are far apart in rgI, so each kernel is 0 or 1 (to 1e-30) and y inside the square is
// the fraction of samples equal to the current pixel.
TEST(KdeBackground, SelectiveUpdateSkipsForegroundPixelsAtMostMaxSkipsTimes) {
  auto at = [](const cv::Mat& y) { return double(y.at<float>(5, 6)); };  // inside the square
  KdeBackgroundParams p = no_closing(4, 2);
  // Ghost: the person stands in the square on sample frame 2 only.
  for (const double threshold : {0.0, 0.5}) {
    p.update_threshold = threshold;
    KdeBackground model(p);
    cv::Mat y;
    model.apply(square_scene(false), y);  // frame 0: sample
    model.apply(square_scene(false), y);
    model.apply(square_scene(true), y);   // frame 2: sample
    if (threshold > 0) EXPECT_NEAR(at(y), 0.0, 1e-6);  // y from the stack before the sample
    else EXPECT_NEAR(at(y), 0.5, 1e-6);                // eq. (10): the l = 0 term is frame 2
    model.apply(square_scene(false), y);  // frame 3: the person has gone
    EXPECT_NEAR(at(y), threshold > 0 ? 1.0 : 0.5, 1e-6) << threshold;  // ghost only without
    EXPECT_NEAR(y.at<float>(0, 0), 1.0, 1e-6);
  }
  // The person stays from frame 2 on: skipped on sample frames 2 and 4 (max_skips 2), taken on 6.
  p.update_threshold = 0.5;
  p.update_max_skips = 2;
  KdeBackground model(p);
  cv::Mat y;
  const double expected[] = {1, 1, 0, 0, 0, 0, 0, 0.25, 0.25, 0.5};  // frames 0..9
  for (int k = 0; k < 10; ++k) {
    model.apply(square_scene(k >= 2), y);
    EXPECT_NEAR(at(y), expected[k], 1e-6) << "frame " << k;
  }
}

// update_static: a person in the first sample (stored whole) who leaves at frame 1 uncovers
// background A, which stays unchanged from sample frame 2 on. Without it the uncovered pixels are
// skipped twice (max_skips 2) and the ghost lasts to frame 8; with it they are taken from sample
// frame 4 on (the same as on sample frame 2), so y rises two sample periods earlier. Once the
// stack is full the rule is off: a person who then stands still is skipped as before. Kernels
// are 0 or 1 as above; y inside the square is the fraction of samples equal to A.
TEST(KdeBackground, UpdateStaticTakesStartUpGhostsIntoTheStackWhileItFills) {
  KdeBackgroundParams p = no_closing(4, 2);
  p.update_threshold = 0.5;
  p.update_max_skips = 2;
  const double off[] = {1, 0, 0, 0, 0, 0, 0, 0.25, 0.25, 0.5};
  const double on[] = {1, 0, 0, 0, 0, 1.0 / 3, 1.0 / 3, 0.5, 0.5, 0.75};
  for (const bool update_static : {false, true}) {
    p.update_static = update_static;
    KdeBackground model(p);
    cv::Mat y;
    for (int k = 0; k < 10; ++k) {
      model.apply(square_scene(k == 0), y);
      EXPECT_NEAR(y.at<float>(5, 6), update_static ? on[k] : off[k], 1e-6)
          << "frame " << k << " update_static " << update_static;
    }
  }
  // The stack is full (frames 2 (a repeat of B), 4, 6, 8): a person arriving at frame 10 and
  // standing still is skipped on sample frames 10 and 12, not taken as static.
  KdeBackground model(p);
  cv::Mat y;
  for (int k = 0; k < 14; ++k) model.apply(square_scene(k == 0 || k >= 10), y);
  EXPECT_NEAR(y.at<float>(5, 6), 0.0, 1e-6);
}

// y of frame `after` against a model that has seen `before` only (2 samples, no closing).
static cv::Mat y_after(const cv::Mat& before, const cv::Mat& after, bool compensate) {
  KdeBackgroundParams p = no_closing(2, 100);
  p.illumination_compensation = compensate;
  KdeBackground model(p);
  cv::Mat y;
  model.apply(before, y);
  model.apply(after, y);
  return y;
}

// Illumination compensation: a frame that is the sample under 1.3 x the light has the same r, g
// and 1.3 x the intensity. Eq. (10) sees foreground (the intensity kernel alone, computed here
// independently); compensated, the intensity is scaled back and y = 1.
TEST(KdeBackground, IlluminationCompensationCancelsAGlobalGain) {
  const cv::Mat dim(10, 12, CV_8UC3, cv::Scalar(60, 90, 120));
  const cv::Mat bright(10, 12, CV_8UC3, cv::Scalar(78, 117, 156));  // x 1.3 exactly
  for (const bool compensate : {false, true}) {
    const cv::Mat y = y_after(dim, bright, compensate);
    const double expected = compensate ? 1.0 : kernel_product(bright.at<cv::Vec3b>(0, 0),
                                                              dim.at<cv::Vec3b>(0, 0),
                                                              no_closing(2, 100));
    EXPECT_NEAR(y.at<float>(4, 5), expected, 1e-5) << compensate;
  }
  EXPECT_LT(kernel_product(cv::Vec3b(78, 117, 156), cv::Vec3b(60, 90, 120), no_closing(2, 100)), 0.3);
}

// The gain is a median over the pixels, so a person in view does not bias it: the same 1.3 x
// light with a dark person over a third of the frame still gives y = 1 on the background (the
// ratio of the images' means, the former gain, would be 1.10 instead of 1 / 1.3 here).
TEST(KdeBackground, IlluminationGainIgnoresThePeopleInView) {
  const cv::Mat dim(10, 12, CV_8UC3, cv::Scalar(60, 90, 120));
  cv::Mat bright(10, 12, CV_8UC3, cv::Scalar(78, 117, 156));
  bright(cv::Rect(0, 0, 4, 10)).setTo(cv::Scalar(20, 20, 20));  // the person: 40 of 120 pixels
  const cv::Mat y = y_after(dim, bright, true);
  for (int x = 4; x < 12; ++x) EXPECT_NEAR(y.at<float>(5, x), 1.0, 1e-5) << x;
  EXPECT_LT(y.at<float>(5, 1), 0.01);  // the person stays foreground
}

TEST(KdeBackground, FirstFrameIsItsOwnBackground) {
  KdeBackground model(no_closing(5, 3));
  cv::Mat frame(20, 30, CV_8UC3), y;
  cv::randu(frame, 0, 256);
  model.apply(frame, y);
  EXPECT_EQ(cv::countNonZero(y != 1.0f), 0);
}

TEST(KdeBackground, RandomImagesMatchEquationTen) {
  KdeBackgroundParams p = no_closing(4, 1);
  p.bandwidth[0] = 0.05;
  p.bandwidth[1] = 0.04;
  p.bandwidth[2] = 0.1;
  cv::RNG rng(7);
  std::vector<cv::Mat> frames;
  KdeBackground model(p);
  cv::Mat base(17, 41, CV_8UC3), y;  // odd width: exercises the vector loop's scalar tail
  rng.fill(base, cv::RNG::UNIFORM, 0, 256);
  base(cv::Rect(0, 0, 3, 3)).setTo(cv::Scalar(0, 0, 0));  // black pixels: r = g = 1/3
  for (int k = 0; k < 6; ++k) {
    cv::Mat noise(base.size(), CV_16SC3), frame;
    rng.fill(noise, cv::RNG::UNIFORM, -12, 13);
    cv::add(base, noise, frame, cv::noArray(), CV_8UC3);
    frames.push_back(frame);
    model.apply(frame, y);
  }
  const std::vector<cv::Mat> stack(frames.end() - 4, frames.end());
  double worst = 0;
  for (int r = 0; r < y.rows; ++r) {
    for (int c = 0; c < y.cols; ++c) {
      worst = std::max(worst, std::abs(y.at<float>(r, c) - expected_y(frames.back(), stack, r, c, p)));
    }
  }
  EXPECT_LT(worst, 1e-5);
}

TEST(KdeBackground, ResultDoesNotDependOnThreads) {
  cv::RNG rng(3);
  std::vector<cv::Mat> ys;
  for (int threads : {1, 0, 3}) {
    KdeBackgroundParams p;
    p.period = 1;
    p.threads = threads;
    KdeBackground model(p);
    rng = cv::RNG(3);
    cv::Mat frame(123, 77, CV_8UC3), y;
    for (int k = 0; k < 5; ++k) {
      rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
      model.apply(frame, y);
    }
    ys.push_back(y.clone());
  }
  EXPECT_EQ(cv::norm(ys[0], ys[1], cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(ys[0], ys[2], cv::NORM_INF), 0.0);
}

TEST(KdeBackground, FreezeKeepsTheStackAndResumeFollowsTheSchedule) {
  KdeBackground model(no_closing(3, 2));
  cv::Mat y;
  for (int k = 0; k < 3; ++k) model.apply(flat(50), y);  // samples 0, 2
  model.freeze();
  EXPECT_FALSE(model.learning());
  for (int k = 3; k < 9; ++k) model.apply(flat(200), y);  // no sample at 4, 6, 8
  EXPECT_EQ(model.sample_frames(), (std::vector<long long>{0, 2}));
  // The frozen model still judges the new colour against the old background.
  EXPECT_LT(y.at<float>(0, 0), 1e-3);
  model.resume();
  model.apply(flat(200), y);  // frame 9: not a sample time
  model.apply(flat(200), y);  // frame 10: sampled
  EXPECT_EQ(model.sample_frames(), (std::vector<long long>{0, 2, 10}));
  EXPECT_NEAR(y.at<float>(0, 0), 1.0 / 3.0, 1e-6);  // one of three samples matches
}

TEST(KdeBackground, FrozenBeforeAnySampleGivesAllBackground) {
  KdeBackground model(no_closing(3, 2));
  model.freeze();
  cv::Mat y;
  model.apply(flat(90), y);
  EXPECT_EQ(model.sample_count(), 0);
  EXPECT_EQ(cv::countNonZero(y != 1.0f), 0);
}

TEST(KdeBackground, ResetForgetsSamplesAndFrameSize) {
  KdeBackground model(no_closing(3, 1));
  cv::Mat y;
  model.apply(flat(50), y);
  model.apply(flat(60), y);
  model.freeze();
  model.reset();
  EXPECT_TRUE(model.learning());
  EXPECT_EQ(model.frame_index(), 0);
  EXPECT_TRUE(model.sample_frames().empty());
  model.apply(flat(200, 10, 12), y);  // a new size is fine after reset
  EXPECT_EQ(y.size(), cv::Size(12, 10));
  EXPECT_EQ(model.sample_frames(), (std::vector<long long>{0}));
  EXPECT_EQ(cv::countNonZero(y != 1.0f), 0);
}

TEST(KdeBackground, ClosingIsAppliedToY) {
  // A one-pixel foreground speck disappears with a 3x3 closing, a 5x5 foreground block stays.
  KdeBackgroundParams p = no_closing(1, 1000);
  KdeBackground plain(p);
  p.closing = 3;
  KdeBackground closed(p);
  cv::Mat bg = flat(100, 20, 20), fg = bg.clone(), y_plain, y_closed, expected;
  fg.at<cv::Vec3b>(3, 3) = cv::Vec3b(200, 10, 10);
  fg(cv::Rect(10, 10, 5, 5)).setTo(cv::Scalar(200, 10, 10));
  for (const cv::Mat* f : {&bg, &fg}) {
    plain.apply(*f, y_plain);
    closed.apply(*f, y_closed);
  }
  EXPECT_LT(y_plain.at<float>(3, 3), 1e-3);
  EXPECT_GT(y_closed.at<float>(3, 3), 0.999);
  EXPECT_LT(y_closed.at<float>(12, 12), 1e-3);
  cv::morphologyEx(y_plain, expected, cv::MORPH_CLOSE, cv::Mat::ones(3, 3, CV_8U));
  EXPECT_EQ(cv::norm(y_closed, expected, cv::NORM_INF), 0.0);
}

TEST(KdeBackground, RejectsBadFrames) {
  KdeBackground model(no_closing(2, 1));
  cv::Mat y;
  EXPECT_THROW(model.apply(cv::Mat(), y), vtrack::InvalidArgument);
  EXPECT_THROW(model.apply(cv::Mat(4, 4, CV_8UC1, cv::Scalar(1)), y), vtrack::InvalidArgument);
  EXPECT_THROW(model.apply(cv::Mat(4, 4, CV_8UC4, cv::Scalar(1)), y), vtrack::InvalidArgument);
  EXPECT_THROW(model.apply(cv::Mat(4, 4, CV_32FC3, cv::Scalar(1)), y), vtrack::InvalidArgument);
  model.apply(flat(10, 4, 4), y);
  try {
    model.apply(flat(10, 5, 4), y);
    FAIL() << "size change accepted";
  } catch (const vtrack::InvalidArgument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("frame 1"), std::string::npos) << what;
    EXPECT_NE(what.find("4x5"), std::string::npos) << what;
    EXPECT_NE(what.find("4x4"), std::string::npos) << what;
  }
  EXPECT_EQ(model.frame_index(), 1);  // the rejected frame did not count
}

TEST(KdeBackground, RejectsBadParameters) {
  const auto rejects = [](auto change, const char* name) {
    KdeBackgroundParams p;
    change(p);
    try {
      KdeBackground model(p);
      ADD_FAILURE() << name << " accepted";
    } catch (const vtrack::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  rejects([](KdeBackgroundParams& p) { p.n_samples = 0; }, "n_samples");
  rejects([](KdeBackgroundParams& p) { p.n_samples = -3; }, "n_samples");
  rejects([](KdeBackgroundParams& p) { p.period = 0; }, "period");
  rejects([](KdeBackgroundParams& p) { p.bandwidth[0] = 0; }, "sigma_r");
  rejects([](KdeBackgroundParams& p) { p.bandwidth[1] = -0.1; }, "sigma_g");
  rejects([](KdeBackgroundParams& p) { p.bandwidth[2] = NAN; }, "sigma_I");
  rejects([](KdeBackgroundParams& p) { p.bandwidth[2] = INFINITY; }, "sigma_I");
  rejects([](KdeBackgroundParams& p) { p.closing = 4; }, "closing");
  rejects([](KdeBackgroundParams& p) { p.closing = -1; }, "closing");
  rejects([](KdeBackgroundParams& p) { p.threads = -1; }, "threads");
  rejects([](KdeBackgroundParams& p) { p.update_threshold = 1.5; }, "update_threshold");
  rejects([](KdeBackgroundParams& p) { p.update_threshold = NAN; }, "update_threshold");
  rejects([](KdeBackgroundParams& p) { p.update_max_skips = 0; }, "update_max_skips");
}

TEST(CloseSquare, EqualsOpenCvClosing) {
  cv::RNG rng(11);
  // Radii 1-5 take the unrolled passes, 6 and 7 the general ones; images smaller than the window,
  // one as wide as it, and one large enough for several row stripes on 2 threads.
  for (int size : {3, 5, 7, 9, 11, 13, 15}) {
    for (cv::Size s : {cv::Size(1, 1), cv::Size(2, 9), cv::Size(37, 23), cv::Size(64, 3),
                       cv::Size(size, size), cv::Size(160, 120)}) {
      cv::Mat src(s, CV_32FC1), ours, theirs, two_threads;
      rng.fill(src, cv::RNG::UNIFORM, 0.0f, 1.0f);
      close_square(src, ours, size, 1);
      close_square(src, two_threads, size, 2);
      EXPECT_EQ(cv::norm(ours, two_threads, cv::NORM_INF), 0.0) << size << " on " << s;
      cv::morphologyEx(src, theirs, cv::MORPH_CLOSE, cv::Mat::ones(size, size, CV_8U));
      EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_INF), 0.0) << size << " on " << s;
      cv::Mat in_place = src.clone();
      close_square(in_place, in_place, size, 0);
      EXPECT_EQ(cv::norm(in_place, theirs, cv::NORM_INF), 0.0) << "in place " << size << " on " << s;
    }
  }
  cv::Mat out;
  EXPECT_THROW(close_square(cv::Mat(3, 3, CV_8UC1), out, 3), vtrack::InvalidArgument);
  EXPECT_THROW(close_square(cv::Mat(3, 3, CV_32FC1), out, 2), vtrack::InvalidArgument);
}

TEST(ForegroundMask, ThresholdsBelow) {
  cv::Mat y = (cv::Mat_<float>(1, 4) << 0.0f, 0.49f, 0.5f, 1.0f), mask;
  foreground_mask(y, 0.5, mask);
  EXPECT_EQ(mask.type(), CV_8UC1);
  EXPECT_EQ(mask.at<unsigned char>(0, 0), 255);
  EXPECT_EQ(mask.at<unsigned char>(0, 1), 255);
  EXPECT_EQ(mask.at<unsigned char>(0, 2), 0);
  EXPECT_EQ(mask.at<unsigned char>(0, 3), 0);
  EXPECT_THROW(foreground_mask(y, 1.5, mask), vtrack::InvalidArgument);
  EXPECT_THROW(foreground_mask(y, NAN, mask), vtrack::InvalidArgument);
  EXPECT_THROW(foreground_mask(cv::Mat(2, 2, CV_8UC1), 0.5, mask), vtrack::InvalidArgument);
}
