// Color histograms, Bhattacharyya coefficient and color likelihood (part-based paper eqs. 9-11)
// against brute force: OpenCV's HSV_FULL per pixel binned by the documented formula, kernel
// weights evaluated pixel by pixel, closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/image/color_histogram.hpp"

using namespace vtrack::image;
using vtrack::InvalidArgument;
using vtrack::core::Rng;

namespace {

cv::Mat random_frame(Rng& rng, int rows, int cols) {
  // Smooth-ish blocks (so neighbouring pixels share bins, as in real images) plus noise.
  cv::Mat small(rows / 8 + 1, cols / 8 + 1, CV_8UC3);
  for (int i = 0; i < small.rows * small.cols * 3; ++i) {
    small.data[i] = static_cast<uchar>(rng.below(256));
  }
  cv::Mat frame;
  cv::resize(small, frame, cv::Size(cols, rows), 0, 0, cv::INTER_NEAREST);
  for (int i = 0; i < rows * cols * 3; ++i) {
    if (rng.below(4) == 0) frame.data[i] = static_cast<uchar>(rng.below(256));
  }
  return frame;
}

// Bin of each pixel, from OpenCV's HSV_FULL and the header's formula floor(c * n / 256).
std::vector<int> brute_force_bins(const cv::Mat& bgr, const ColorHistogramParams& p) {
  cv::Mat hsv;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV_FULL);
  std::vector<int> bins(static_cast<std::size_t>(bgr.rows * bgr.cols));
  for (int r = 0; r < bgr.rows; ++r) {
    for (int c = 0; c < bgr.cols; ++c) {
      const cv::Vec3b v = hsv.at<cv::Vec3b>(r, c);
      const int h = v[0] * p.bins_h / 256, s = v[1] * p.bins_s / 256, b = v[2] * p.bins_v / 256;
      bins[static_cast<std::size_t>(r * bgr.cols + c)] = (h * p.bins_s + s) * p.bins_v + b;
    }
  }
  return bins;
}

// Histogram of a box by visiting every frame pixel and testing whether it is in the box's pixel
// rect (the header's rounding), optionally with the kernel weight evaluated from its definition.
std::vector<double> brute_force_histogram(const cv::Mat& bgr, const ColorHistogramParams& p,
                                          const double* box, double* total) {
  const std::vector<int> bins = brute_force_bins(bgr, p);
  std::vector<double> hist(static_cast<std::size_t>(bin_count(p)), 0.0);
  const double x0 = std::floor(box[0] + 0.5), x1 = std::floor(box[0] + box[2] + 0.5);
  const double y0 = std::floor(box[1] + 0.5), y1 = std::floor(box[1] + box[3] + 0.5);
  const double cx = box[0] + box[2] / 2, cy = box[1] + box[3] / 2;
  const double a2 = (box[2] * box[2] + box[3] * box[3]) / 4;
  *total = 0;
  for (int r = 0; r < bgr.rows; ++r) {
    for (int c = 0; c < bgr.cols; ++c) {
      if (c < x0 || c >= x1 || r < y0 || r >= y1) continue;
      const double dx = c + 0.5 - cx, dy = r + 0.5 - cy;
      const double k = p.kernel ? std::max(0.0, 1.0 - (dx * dx + dy * dy) / a2) : 1.0;
      hist[static_cast<std::size_t>(bins[static_cast<std::size_t>(r * bgr.cols + c)])] += k;
      *total += k;
    }
  }
  return hist;
}

double brute_force_rho(const std::vector<double>& p, double p_total, const std::vector<double>& q) {
  if (p_total <= 0) return 0.0;
  double q_total = 0, s = 0;
  for (double v : q) q_total += v;
  for (std::size_t u = 0; u < p.size(); ++u) s += std::sqrt(p[u] / p_total * q[u] / q_total);
  return s;
}

// Every histogram method's coefficients of `boxes` (x, y, w, h each) against `model` equal the
// brute-force histogram's.
void expect_every_method_matches_brute_force(const ColorModel& model, const cv::Mat& frame,
                                             const ColorHistogramParams& p, const std::vector<double>& boxes) {
  const std::size_t n = boxes.size() / 4;
  HsvBinImage bins(p);
  for (const auto method :
       {HistogramMethod::automatic, HistogramMethod::direct, HistogramMethod::incremental}) {
    std::vector<double> rho(n, -1.0);
    model.coefficients(frame, boxes.data(), n, 4, rho.data(), bins, method);
    for (std::size_t i = 0; i < n; ++i) {
      double total = 0;
      const auto hist = brute_force_histogram(frame, p, &boxes[4 * i], &total);
      ASSERT_NEAR(rho[i], brute_force_rho(hist, total, model.reference()), 2e-6)
          << "method " << static_cast<int>(method) << " box " << i;
    }
  }
}

std::vector<double> random_boxes(Rng& rng, int n, int cols, int rows) {
  std::vector<double> boxes;
  for (int i = 0; i < n; ++i) {
    boxes.push_back(rng.uniform(-20.0, cols + 5.0));
    boxes.push_back(rng.uniform(-20.0, rows + 5.0));
    boxes.push_back(rng.uniform(0.0, 40.0));
    boxes.push_back(rng.uniform(0.0, 60.0));
  }
  return boxes;
}

}  // namespace

TEST(ColorHistogram, PureColorsFallInTheirHueBins) {
  // HSV_FULL: H = round(256 * hue / 360); 16 hue bins of 22.5 degrees; S, V in 4 bins of 64.
  const ColorHistogramParams p;  // 16 x 4 x 4
  struct Case {
    cv::Vec3b bgr;
    int h, s, v;
  };
  const Case cases[] = {
      {{0, 0, 255}, 0, 3, 3},       // red, hue 0
      {{0, 255, 255}, 2, 3, 3},     // yellow, 60 deg -> H 43
      {{0, 255, 0}, 5, 3, 3},       // green, 120 deg -> H 85
      {{255, 255, 0}, 8, 3, 3},     // cyan, 180 deg -> H 128
      {{255, 0, 0}, 10, 3, 3},      // blue, 240 deg -> H 171
      {{255, 0, 255}, 13, 3, 3},    // magenta, 300 deg -> H 213
      {{128, 128, 128}, 0, 0, 2},   // grey: H = S = 0 by OpenCV's convention, V = 128
      {{0, 0, 0}, 0, 0, 0},         // black
      {{20, 20, 100}, 0, 3, 1},     // dark red: S = 255 * 80 / 100 = 204, V = 100
  };
  cv::Mat frame(1, static_cast<int>(std::size(cases)), CV_8UC3);
  for (int i = 0; i < frame.cols; ++i) frame.at<cv::Vec3b>(0, i) = cases[i].bgr;
  HsvBinImage bins(p);
  bins.assign(frame);
  for (int i = 0; i < frame.cols; ++i) {
    EXPECT_EQ(bins.at(0, i), (cases[i].h * 4 + cases[i].s) * 4 + cases[i].v) << "case " << i;
  }
}

TEST(ColorHistogram, BinsAgreeWithFloatHsvAwayFromBinEdges) {
  // Independent of OpenCV: hue in degrees, S = (max - min) / max, V = max, binned in floating
  // point.
  // OpenCV rounds H and S to integer codes, so a pixel within one code of a bin edge may land in
  // the neighbouring bin; every other pixel must agree exactly.
  Rng rng(5);
  const ColorHistogramParams p{16, 4, 4, false};
  cv::Mat frame = random_frame(rng, 64, 96);
  HsvBinImage bins(p);
  bins.assign(frame);
  int checked = 0;
  for (int r = 0; r < frame.rows; ++r) {
    for (int c = 0; c < frame.cols; ++c) {
      const cv::Vec3b px = frame.at<cv::Vec3b>(r, c);
      const double b = px[0], g = px[1], rd = px[2];
      const double mx = std::max({b, g, rd}), mn = std::min({b, g, rd}), d = mx - mn;
      double hue = 0;
      if (d > 0) {
        if (mx == rd) hue = 60 * (g - b) / d;
        else if (mx == g) hue = 120 + 60 * (b - rd) / d;
        else hue = 240 + 60 * (rd - g) / d;
        if (hue < 0) hue += 360;
      }
      const double s = mx > 0 ? 255 * d / mx : 0;
      const double h_code = 256 * hue / 360, h_pos = h_code / 16, s_pos = s / 64;
      const bool near_edge = std::abs(h_pos - std::round(h_pos)) * 16 < 1.0 ||
                             std::abs(s_pos - std::round(s_pos)) * 64 < 1.0 || h_code > 255;
      if (near_edge) continue;
      const int expected = (static_cast<int>(h_pos) * 4 + static_cast<int>(s_pos)) * 4 +
                           static_cast<int>(mx) / 64;
      ASSERT_EQ(bins.at(r, c), expected) << "pixel " << r << "," << c;
      ++checked;
    }
  }
  EXPECT_GT(checked, frame.rows * frame.cols * 3 / 4);
}

TEST(ColorHistogram, BoxHistogramsMatchBruteForce) {
  Rng rng(11);
  const ColorHistogramParams params[] = {{16, 4, 4, false}, {16, 4, 4, true}, {8, 3, 5, false},
                                          {7, 1, 2, true}};
  for (const auto& p : params) {
    const cv::Mat frame = random_frame(rng, 50, 70);
    HsvBinImage bins(p);
    bins.assign(frame);
    const std::vector<double> boxes = random_boxes(rng, 60, frame.cols, frame.rows);
    std::vector<double> hist(static_cast<std::size_t>(bin_count(p)));
    for (std::size_t i = 0; i < boxes.size(); i += 4) {
      double expected_total = 0;
      const auto expected = brute_force_histogram(frame, p, &boxes[i], &expected_total);
      const double total = box_histogram(bins, boxes[i], boxes[i + 1], boxes[i + 2], boxes[i + 3],
                                         p.kernel, hist.data());
      ASSERT_NEAR(total, expected_total, 1e-9 * (1 + expected_total));
      for (std::size_t u = 0; u < hist.size(); ++u) ASSERT_NEAR(hist[u], expected[u], 1e-9) << u;
    }
  }
}

TEST(ColorHistogram, KernelIsNummiaroEpanechnikov) {
  // A one-bin histogram sums the weights: compare the weight of single-pixel boxes' neighbourhoods
  // with k(r) = 1 - r^2 / (Hx^2 + Hy^2) at a few known pixels of a 10 x 4 box at (0, 0).
  cv::Mat frame(4, 10, CV_8UC3, cv::Scalar(0, 0, 0));
  const ColorHistogramParams p{1, 1, 1, true};
  HsvBinImage bins(p);
  bins.assign(frame);
  double hist = 0;
  const double total = box_histogram(bins, 0, 0, 10, 4, true, &hist);
  // Centre (5, 2); a^2 = 25 + 4 = 29. Sum over pixel centres (c + 0.5, r + 0.5).
  double expected = 0;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 10; ++c)
      expected += 1 - ((c + 0.5 - 5) * (c + 0.5 - 5) + (r + 0.5 - 2) * (r + 0.5 - 2)) / 29.0;
  EXPECT_NEAR(total, expected, 1e-12);
  EXPECT_NEAR(hist, expected, 1e-12);
  EXPECT_LT(total, 40.0);  // weighted: less than the pixel count
  EXPECT_GT(total, 0.6 * 40.0);
}

TEST(ColorHistogram, PixelRectRoundsBothEdges) {
  const Rect r = pixel_rect(0.49, 1.5, 10.0, 2.4);
  EXPECT_EQ(r.x, 0);
  EXPECT_EQ(r.width, 10);  // [0, round(10.49) = 10)
  EXPECT_EQ(r.y, 2);
  EXPECT_EQ(r.height, 2);  // [2, round(3.9) = 4)
  EXPECT_EQ(pixel_rect(5, 5, -3, 4).width, 0);
  EXPECT_EQ(pixel_rect(std::nan(""), 0, 4, 4).width, 0);
  EXPECT_EQ(pixel_rect(1e300, 0, 4, 4).width, 0);
  // Edges are pinned to +-2^29, so even the widest box's width fits an int.
  EXPECT_EQ(pixel_rect(-1e300, 0, 2e300, 4).width, 2 * 536870912);
}

TEST(Bhattacharyya, ClosedForms) {
  const double p[] = {1, 0, 0, 0}, q[] = {0.5, 0.5, 0, 0}, r[] = {0, 0, 3, 1};
  EXPECT_NEAR(bhattacharyya_coefficient(p, q, 4), std::sqrt(0.5), 1e-15);
  EXPECT_DOUBLE_EQ(bhattacharyya_coefficient(p, r, 4), 0.0);
  EXPECT_DOUBLE_EQ(bhattacharyya_coefficient(r, r, 4), 1.0);
  // Scale-free: counts and their normalised histogram give the same coefficient.
  const double counts[] = {2, 6, 0, 8}, dist[] = {0.125, 0.375, 0, 0.5};
  const double expected = std::sqrt(0.125 * 0.5) + std::sqrt(0.375 * 0.5) + 0 + 0;  // vs q
  EXPECT_NEAR(bhattacharyya_coefficient(counts, q, 4), expected, 1e-15);
  EXPECT_NEAR(bhattacharyya_coefficient(dist, q, 4), expected, 1e-15);
  EXPECT_NEAR(bhattacharyya_distance(std::sqrt(0.5)), std::sqrt(1 - std::sqrt(0.5)), 1e-15);
  EXPECT_EQ(bhattacharyya_distance(1.0 + 1e-16), 0.0);
  const double zeros[] = {0, 0, 0, 0}, negative[] = {1, -1, 0, 0}, nan[] = {1, std::nan(""), 0, 0};
  EXPECT_THROW(bhattacharyya_coefficient(zeros, q, 4), InvalidArgument);
  EXPECT_THROW(bhattacharyya_coefficient(q, negative, 4), InvalidArgument);
  EXPECT_THROW(bhattacharyya_coefficient(nan, q, 4), InvalidArgument);
}

TEST(ColorLikelihood, IsEquationElevenInLogs) {
  for (const double sigma : {0.2, std::sqrt(0.2), 1.0}) {
    for (const double rho : {0.0, 0.3, 0.95, 1.0}) {
      const double p = 1 / std::sqrt(2 * M_PI * sigma * sigma) *
                       std::exp(-(1 - rho) / (2 * sigma * sigma));
      EXPECT_NEAR(color_log_likelihood(rho, sigma), std::log(p), 1e-12);
    }
  }
  EXPECT_DOUBLE_EQ(kDefaultColorSigma * kDefaultColorSigma, 0.2);
  const double rho[] = {0.1, 0.9};
  double out[2];
  color_log_likelihood(rho, 2, 0.2, out);
  EXPECT_NEAR(out[1] - out[0], 0.8 / (2 * 0.04), 1e-12);
  EXPECT_THROW(color_log_likelihood(0.5, 0.0), InvalidArgument);
  EXPECT_THROW(color_log_likelihood(rho, 2, std::nan(""), out), InvalidArgument);
}

TEST(ColorModel, EveryMethodMatchesBruteForce) {
  Rng rng(23);
  for (int trial = 0; trial < 6; ++trial) {
    const ColorHistogramParams p{trial % 2 ? 16 : 6, 4, trial % 3 ? 4 : 2, false};
    const cv::Mat frame = random_frame(rng, 60, 80);
    const ColorModel model = ColorModel::from_box(frame, 10, 10, 20, 30, p);
    // Clustered boxes (as particles are: the incremental method's differences are small) and
    // scattered ones, some partly or wholly outside the frame, some empty.
    std::vector<double> boxes = random_boxes(rng, 40, frame.cols, frame.rows);
    for (int i = 0; i < 40; ++i) {
      for (const double v : {12 + 3 * rng.normal(), 9 + 3 * rng.normal(), 20 + rng.normal(),
                             30 + rng.normal()}) {
        boxes.push_back(v);
      }
    }
    expect_every_method_matches_brute_force(model, frame, p, boxes);
  }
}

TEST(ColorModel, KernelWeightedCoefficientsMatchBruteForce) {
  Rng rng(29);
  const ColorHistogramParams p{16, 4, 4, true};
  const cv::Mat frame = random_frame(rng, 60, 80);
  const ColorModel model = ColorModel::from_box(frame, 30.3, 12.7, 21.5, 33.2, p);
  // The template itself: rho = 1.
  const double same[] = {30.3, 12.7, 21.5, 33.2};
  double rho1 = 0;
  HsvBinImage bins(p);
  model.coefficients(frame, same, 1, 4, &rho1, bins);
  EXPECT_NEAR(rho1, 1.0, 2e-6);  // sqrt(q) is held in float: rho to ~1e-7
  // Scattered boxes (partly outside, empty) and clustered ones with half-pixel edges (the kernel's
  // corner pixels then sit on the box's edge, weight 0), so the incremental method's moments are
  // updated by small differences as well as counted afresh.
  std::vector<double> boxes = random_boxes(rng, 50, frame.cols, frame.rows);
  for (int i = 0; i < 50; ++i) {
    for (const double v : {30 + 3 * rng.normal(), 12 + 3 * rng.normal(), 21.5 + rng.normal(),
                           33 + rng.normal()}) {
      boxes.push_back(i % 5 == 0 ? std::floor(v) + 0.5 : v);
    }
  }
  expect_every_method_matches_brute_force(model, frame, p, boxes);
}

TEST(ColorModel, StridedBoxesAndSharedBinImage) {
  // Two models with the same bins score against one quantised region (the part-based filter's
  // use), with boxes read from rows of 8 doubles (a state with extra components).
  Rng rng(31);
  const cv::Mat frame = random_frame(rng, 40, 60);
  const ColorModel upper = ColorModel::from_box(frame, 10, 5, 12, 10);
  const ColorModel lower = ColorModel::from_box(frame, 10, 15, 12, 10);
  const double rows[16] = {10, 5, 12, 10, 9, 9, 9, 9, 10, 15, 12, 10, 9, 9, 9, 9};
  HsvBinImage bins;
  bins.assign(frame, boxes_roi(rows, 2, 8, frame.cols, frame.rows));
  EXPECT_EQ(bins.roi().y, 5);
  EXPECT_EQ(bins.roi().height, 20);
  double a[2], b[2];
  upper.coefficients(bins, rows, 2, 8, a);
  lower.coefficients(bins, rows, 2, 8, b);
  EXPECT_NEAR(a[0], 1.0, 1e-6);
  EXPECT_NEAR(b[1], 1.0, 1e-6);
  EXPECT_LT(a[1], 1.0 - 1e-3);
}

TEST(ColorModel, BadInput) {
  const cv::Mat frame(20, 30, CV_8UC3, cv::Scalar(10, 200, 30));
  EXPECT_THROW(ColorModel::from_box(frame, 40, 0, 5, 5), InvalidArgument);   // outside
  EXPECT_THROW(ColorModel::from_box(frame, 5, 5, 0, 5), InvalidArgument);    // empty
  EXPECT_THROW(ColorModel::from_box(cv::Mat(), 5, 5, 5, 5), InvalidArgument);
  EXPECT_THROW(ColorModel::from_box(cv::Mat(20, 30, CV_8UC1), 5, 5, 5, 5), InvalidArgument);
  try {
    validate(ColorHistogramParams{0, 4, 4, false});
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("bins_h"), std::string::npos);
  }
  EXPECT_THROW(validate(ColorHistogramParams{16, 257, 4, false}), InvalidArgument);
  EXPECT_THROW(validate(ColorHistogramParams{256, 256, 2, false}), InvalidArgument);
  EXPECT_THROW(ColorModel(ColorHistogramParams{}, std::vector<double>(10, 1.0)), InvalidArgument);
  EXPECT_THROW(ColorModel(ColorHistogramParams{}, std::vector<double>(256, 0.0)),
               InvalidArgument);
  // A box outside the quantised region (but inside the frame) is refused, not silently clipped.
  const ColorModel model = ColorModel::from_box(frame, 5, 5, 5, 5);
  HsvBinImage bins;
  bins.assign(frame, Rect{0, 0, 10, 10});
  const double box[] = {8, 8, 5, 5};
  double rho = 0;
  EXPECT_THROW(model.coefficients(bins, box, 1, 4, &rho), InvalidArgument);
  // Bins of another shape than the model's.
  HsvBinImage other(ColorHistogramParams{8, 4, 4, false});
  other.assign(frame);
  EXPECT_THROW(model.coefficients(other, box, 1, 4, &rho), InvalidArgument);
  // A box wholly outside the frame scores 0, no error.
  const double away[] = {100, 100, 5, 5};
  model.coefficients(frame, away, 1, 4, &rho, bins);
  EXPECT_EQ(rho, 0.0);
}

TEST(ColorHistogram, EveryRegionWidthAndOffsetMatchesOpenCv) {
  // The quantiser works on 16 pixels at a time and treats each row's last 1-15 pixels apart (two
  // ways: rows shorter or longer than 64 bytes), so every width from 1 to 50 px at several
  // offsets, regions ending at the frame's right edge included, against OpenCV's bins.
  Rng rng(17);
  const ColorHistogramParams p{16, 4, 4, false};
  const cv::Mat frame = random_frame(rng, 12, 60);
  const std::vector<int> expected = brute_force_bins(frame, p);
  HsvBinImage bins(p);
  for (int width = 1; width <= 50; ++width) {
    for (const int x : {0, 1, 5, 60 - width}) {
      bins.assign(frame, Rect{x, 2, width, 7});
      for (int r = 2; r < 9; ++r) {
        for (int c = x; c < x + width; ++c) {
          ASSERT_EQ(bins.at(r, c), expected[static_cast<std::size_t>(r * frame.cols + c)])
              << "width " << width << " x " << x << " pixel " << r << "," << c;
        }
      }
    }
  }
}

TEST(ColorHistogram, HsvIsOpenCvsForEveryColor) {
  // HsvBinImage computes OpenCV's integer HSV_FULL itself: with 256 bins per channel its bin
  // indices are the H, S, V bytes, which must equal cv::cvtColor's for all 2^24 BGR colors.
  cv::Mat all(4096, 4096, CV_8UC3);
  for (int i = 0; i < 4096 * 4096; ++i) {
    all.data[3 * i] = static_cast<uchar>(i & 255);
    all.data[3 * i + 1] = static_cast<uchar>((i >> 8) & 255);
    all.data[3 * i + 2] = static_cast<uchar>(i >> 16);
  }
  cv::Mat hsv;
  cv::cvtColor(all, hsv, cv::COLOR_BGR2HSV_FULL);
  // (256, 256, 1) bins: u = H * 256 + S, so H and S are checked; V by (1, 1, 256): u = V.
  for (const ColorHistogramParams p : {ColorHistogramParams{256, 256, 1, false},
                                        ColorHistogramParams{1, 1, 256, false}}) {
    HsvBinImage bins(p);
    bins.assign(all);
    long long mismatches = 0;
    for (int r = 0; r < all.rows; ++r) {
      const std::uint16_t* u = bins.row_ptr(r);
      const cv::Vec3b* ref = hsv.ptr<cv::Vec3b>(r);
      for (int c = 0; c < all.cols; ++c) {
        const int expected = p.bins_v == 256 ? ref[c][2] : ref[c][0] * 256 + ref[c][1];
        mismatches += u[c] != expected;
      }
    }
    EXPECT_EQ(mismatches, 0) << "bins " << p.bins_h << " x " << p.bins_s << " x " << p.bins_v;
  }
}
