// The colour and part-based particle filters (part-based-graphical-model-pf.txt sections 2-4)
// against exact synthetic truth, hand computations of eqs. 13 and 21, a transcription of eqs.
// 24-29 from independently computed Bhattacharyya coefficients, the draw frequencies of eqs.
// 27-30, determinism and the bad-input conventions.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/filters/color_particle.hpp"

using namespace vtrack;
using filters::Box;

namespace {

// A scene with exact truth: a textured grey background and a figure of two coloured halves
// (red-ish over blue-ish, each with per-pixel noise) of size w x h whose top-left corner moves
// by (vx, vy) per frame; optionally a green occluder over a fixed rectangle.
struct Scene {
  int cols = 320, rows = 240;
  double x0 = 40, y0 = 80, w = 24, h = 64, vx = 2.0, vy = 0.5;
  cv::Rect occluder{0, 0, 0, 0};
  cv::Mat background;

  explicit Scene(std::uint64_t seed = 1) {
    core::Rng rng(seed, 0);
    cv::Mat small(rows / 8, cols / 8, CV_8UC3);
    for (int i = 0; i < small.rows * small.cols * 3; ++i) {
      small.data[i] = static_cast<uchar>(90 + rng.below(60));
    }
    cv::resize(small, background, cv::Size(cols, rows), 0, 0, cv::INTER_LINEAR);
  }
  Box truth(int k) const { return Box{x0 + vx * k, y0 + vy * k, w, h}; }
  Box part_truth(int k, int part) const {
    const Box b = truth(k);
    return Box{b.x, b.y + part * h / 2, w, h / 2};
  }
  cv::Mat frame(int k) const {
    cv::Mat f = background.clone();
    core::Rng rng(1000 + static_cast<std::uint64_t>(k), 0);
    const Box b = truth(k);
    const int bx = static_cast<int>(std::lround(b.x)), by = static_cast<int>(std::lround(b.y));
    for (int r = 0; r < h; ++r) {
      for (int c = 0; c < w; ++c) {
        const int x = bx + c, y = by + r;
        if (x < 0 || y < 0 || x >= cols || y >= rows) continue;
        const int n = static_cast<int>(rng.below(30));
        f.at<cv::Vec3b>(y, x) = r < h / 2 ? cv::Vec3b(30 + n, 40 + n, 200 + n / 2)
                                          : cv::Vec3b(190 + n / 2, 60 + n, 30 + n);
      }
    }
    if (occluder.area() > 0) f(occluder).setTo(cv::Scalar(40, 180, 60));
    return f;
  }
};

double centre_error(const Box& a, const Box& b) {
  return std::hypot(a.x + a.w / 2 - b.x - b.w / 2, a.y + a.h / 2 - b.y - b.h / 2);
}

// Bhattacharyya coefficient of box b against the template of box t (both on their frames),
// computed from scratch with the image layer's single-box histogram.
double rho_of(const cv::Mat& frame, const Box& b, const std::vector<double>& q) {
  image::HsvBinImage bins;
  bins.assign(frame);
  std::vector<double> hist(q.size());
  const double total = image::box_histogram(bins, b.x, b.y, b.w, b.h, false, hist.data());
  if (total <= 0) return 0.0;
  double rho = 0.0;
  for (std::size_t u = 0; u < q.size(); ++u) rho += std::sqrt(hist[u] / total * q[u]);
  return rho;
}

std::vector<double> template_of(const cv::Mat& frame, const Box& b) {
  return image::ColorModel::from_box(frame, b.x, b.y, b.w, b.h).reference();
}

}  // namespace

TEST(BoxMotion, SecondOrderAutoRegressiveByHand) {
  // Eq. 13 without noise: X_k = 2 X_{k-1} - X_{k-2}, and the previous half is X_{k-1}.
  models::BoxMotionParams p;
  p.noise = {0.0, 0.0, 0.0, 0.0};
  p.min_scale = 0.5;
  p.max_scale = 2.0;
  const models::BoxMotion motion(p, 50.0, 20.0);
  Eigen::MatrixXd prev(1, 8), eps = Eigen::MatrixXd::Zero(1, 4), next(1, 8);
  prev << 100, 60, 52, 21, 97, 61, 50, 20;
  motion.propagate(prev, eps, next);
  Eigen::MatrixXd expected(1, 8);
  expected << 103, 59, 54, 22, 100, 60, 52, 21;
  EXPECT_TRUE(next.isApprox(expected, 1e-12)) << next;
  // The size guard: at most max_scale (2) times the reference size, at least min_scale (0.5).
  prev << 0, 0, 99, 39, 0, 0, 80, 30;
  motion.propagate(prev, eps, next);
  EXPECT_DOUBLE_EQ(next(0, 2), 100.0);
  EXPECT_DOUBLE_EQ(next(0, 3), 40.0);
  prev << 0, 0, 30, 12, 0, 0, 40, 14;
  motion.propagate(prev, eps, next);
  EXPECT_DOUBLE_EQ(next(0, 2), 25.0);
  EXPECT_DOUBLE_EQ(next(0, 3), 10.0);
}

TEST(BoxMotion, NoiseScalesWithTheBox) {
  // U = (noise[0] w, noise[1] h, noise[2] h, noise[3] w) eps: the sample standard deviation of
  // the step of n = 20000 particles against it, two box sizes (tolerance 3%: ~4 standard errors).
  models::BoxMotionParams p;
  p.noise = {0.1, 0.05, 0.02, 0.01};
  p.min_scale = 0.1;  // far from the size guard
  p.max_scale = 10.0;
  const models::BoxMotion motion(p, 100.0, 40.0);
  core::Rng rng(7, 0);
  const int n = 20000;
  for (double scale : {1.0, 1.5}) {
    Eigen::MatrixXd prev(n, 8), eps(n, 4), next(n, 8);
    for (int i = 0; i < n; ++i) {
      prev.row(i) << 10, 20, 100 * scale, 40 * scale, 10, 20, 100 * scale, 40 * scale;
      for (int c = 0; c < 4; ++c) eps(i, c) = rng.normal();
    }
    motion.propagate(prev, eps, next);
    const double expected[4] = {0.1 * 40 * scale, 0.05 * 100 * scale, 0.02 * 100 * scale,
                                0.01 * 40 * scale};
    for (int c = 0; c < 4; ++c) {
      const Eigen::ArrayXd d = next.col(c).array() - prev(0, c);
      const double sd = std::sqrt((d - d.mean()).square().mean());
      EXPECT_NEAR(sd / expected[c], 1.0, 0.03) << "component " << c << " scale " << scale;
    }
  }
}

TEST(MessageMap, GeometryByHand) {
  // Upper half (10, 20, 30, 40) to lower half (10, 60, 30, 40) of a 30 x 80 box: the lower
  // half's centre is 40 px (one upper-half height) below; when the upper half doubles in size the
  // offset doubles (eq. 21 following the scale).
  const Box upper{10, 20, 30, 40}, lower{10, 60, 30, 40};
  const filters::MessageMap m = filters::MessageMap::between(upper, lower);
  const Eigen::Vector4d same = m.A * Eigen::Vector4d(25, 40, 40, 30) + m.b;
  EXPECT_TRUE(same.isApprox(Eigen::Vector4d(25, 80, 40, 30), 1e-12)) << same.transpose();
  const Eigen::Vector4d doubled = m.A * Eigen::Vector4d(25, 40, 80, 60) + m.b;
  EXPECT_TRUE(doubled.isApprox(Eigen::Vector4d(25, 120, 80, 60), 1e-12)) << doubled.transpose();
  // A part of another size and a horizontal offset: from (0, 0, 20, 10) to (30, 5, 10, 40),
  // centres (10, 5) -> (35, 25): A(0, 3) = 25 / 20, A(1, 2) = 20 / 10, sizes 4x and 0.5x.
  const filters::MessageMap k = filters::MessageMap::between({0, 0, 20, 10}, {30, 5, 10, 40});
  const Eigen::Vector4d moved = k.A * Eigen::Vector4d(110, 105, 20, 40) + k.b;  // twice the size
  EXPECT_TRUE(moved.isApprox(Eigen::Vector4d(110 + 2 * 25, 105 + 2 * 20, 80, 20), 1e-12))
      << moved.transpose();
  // Both halves of the AR state move together.
  Eigen::MatrixXd states(1, 8), out;
  states << 25, 40, 40, 30, 24, 39, 40, 30;
  m.apply(states, out);
  EXPECT_NEAR(out(0, 1), 80, 1e-12);
  EXPECT_NEAR(out(0, 5), 79, 1e-12);
}

TEST(ColorParticleFilter, FollowsAMovingFigureToExactTruth) {
  const Scene scene;
  filters::ColorParticleParams p;
  p.seed = 3;
  filters::ColorParticleFilter pf(p);
  pf.init(scene.frame(0), scene.truth(0));
  double worst = 0.0;
  for (int k = 1; k <= 50; ++k) {
    ASSERT_TRUE(pf.update(scene.frame(k)));
    worst = std::max(worst, centre_error(pf.box(), scene.truth(k)));
    const Eigen::VectorXd w = pf.weights();
    ASSERT_TRUE(w.allFinite());
    ASSERT_NEAR(w.sum(), 1.0, 1e-9);
  }
  // The figure moves 100 px; the colour histogram pins its centre to a few pixels (the figure is
  // 24 x 64).
  EXPECT_LT(worst, 8.0);
  EXPECT_GT(pf.coefficient(), 0.9);
}

TEST(ColorParticleFilter, SameSeedSameTrack) {
  const Scene scene;
  auto run = [&](std::uint64_t seed) {
    filters::ColorParticleParams p;
    p.seed = seed;
    filters::ColorParticleFilter pf(p);
    pf.init(scene.frame(0), scene.truth(0));
    std::vector<double> xs;
    for (int k = 1; k <= 10; ++k) {
      pf.update(scene.frame(k));
      xs.push_back(pf.box().x);
    }
    return xs;
  };
  EXPECT_EQ(run(5), run(5));
  EXPECT_NE(run(5), run(6));
}

TEST(PartParticleFilter, WeightsAreEqs24To29FromIndependentCoefficients) {
  // Two halves, eq. 26 message weights: in part 0's joint set, row 2i is part 0's predicted
  // particle i weighted by p(z_0 | x) (eq. 24) and row 2i + 1 is part 1's predicted particle i
  // mapped by eq. 21 and weighted by part 1's own p(z_1 | x_1) (eq. 26), all normalised together.
  const Scene scene;
  filters::PartParticleParams p;
  p.n_particles = 12;
  p.seed = 2;
  p.color.histogram.kernel = false;  // as template_of and rho_of count
  filters::PartParticleFilter pf(p);
  const cv::Mat f0 = scene.frame(0);
  pf.init(f0, scene.truth(0));
  const std::vector<double> q0 = template_of(f0, scene.part_truth(0, 0));
  const std::vector<double> q1 = template_of(f0, scene.part_truth(0, 1));
  pf.update(scene.frame(1));
  const cv::Mat f1 = scene.frame(1);
  const Eigen::MatrixXd b0 = pf.particle_boxes(0), b1 = pf.particle_boxes(1);
  const Eigen::VectorXd w0 = pf.weights(0);
  ASSERT_EQ(b0.rows(), 24);
  const double sigma = p.color.sigma;
  auto lik = [&](double rho) { return std::exp(-(1 - rho) / (2 * sigma * sigma)); };
  Eigen::VectorXd expected(24);
  const filters::MessageMap& m = pf.message(1, 0);
  for (int i = 0; i < 12; ++i) {
    const Box own{b0(2 * i, 0), b0(2 * i, 1), b0(2 * i, 2), b0(2 * i, 3)};
    const Box sender{b1(2 * i, 0), b1(2 * i, 1), b1(2 * i, 2), b1(2 * i, 3)};  // x-hat_1(i)
    expected[2 * i] = lik(rho_of(f1, own, q0));
    expected[2 * i + 1] = lik(rho_of(f1, sender, q1));
    // The message particle's box is eq. 21 applied to the sender's state.
    const Eigen::Vector4d xs(sender.x + sender.w / 2, sender.y + sender.h / 2, sender.h, sender.w);
    const Eigen::Vector4d xm = m.A * xs + m.b;
    EXPECT_NEAR(b0(2 * i + 1, 0), xm[0] - xm[3] / 2, 1e-9);
    EXPECT_NEAR(b0(2 * i + 1, 1), xm[1] - xm[2] / 2, 1e-9);
    EXPECT_NEAR(b0(2 * i + 1, 3), xm[2], 1e-9);
  }
  expected /= expected.sum();
  EXPECT_TRUE(w0.isApprox(expected, 1e-6)) << w0.transpose() << "\n" << expected.transpose();
  // Eq. 22: the part's estimate is the weighted mean of the joint set.
  const Eigen::VectorXd cx = b0.col(0) + b0.col(2) / 2;
  EXPECT_NEAR(pf.part_box(0).x + pf.part_box(0).w / 2, cx.dot(w0), 1e-9);
}

TEST(PartParticleFilter, JointDrawFrequenciesFollowTheCumulativeWeights) {
  // Step 5 draws N rows of the joint set with probabilities c'(j) - c'(j - 1) (eqs. 27-30).
  // With N = 4000 per node: every drawn particle is a row of the joint set, and the fraction drawn
  // from the node's own rows matches their total weight (binomial, 4 standard errors), at several
  // seeds.
  const Scene scene;
  for (std::uint64_t seed : {0u, 1u, 2u}) {
    filters::PartParticleParams p;
    p.n_particles = 4000;
    p.seed = seed;
    filters::PartParticleFilter pf(p);
    pf.init(scene.frame(0), scene.truth(0));
    pf.update(scene.frame(1));
    const Eigen::MatrixXd joint = pf.particle_boxes(0), drawn = pf.drawn_boxes(0);
    const Eigen::VectorXd w = pf.weights(0);
    double own_weight = 0.0;
    for (Eigen::Index j = 0; j < w.size(); j += 2) own_weight += w[j];
    int own = 0;
    for (Eigen::Index i = 0; i < drawn.rows(); ++i) {
      Eigen::Index found = -1;
      for (Eigen::Index j = 0; j < joint.rows() && found < 0; ++j) {
        if ((joint.row(j) - drawn.row(i)).cwiseAbs().maxCoeff() < 1e-9) found = j;
      }
      ASSERT_GE(found, 0) << "drawn particle " << i << " is not in the joint set";
      ASSERT_GT(w[found], 0.0);
      own += found % 2 == 0;
    }
    const double n = static_cast<double>(drawn.rows());
    const double se = std::sqrt(own_weight * (1 - own_weight) / n);
    EXPECT_NEAR(own / n, own_weight, 4 * se + 1e-12) << "seed " << seed;
  }
}

TEST(PartParticleFilter, InfersTheOccludedHalfFromItsNeighbour) {
  // The lower half walks behind a green occluder for 29 frames: it is judged occluded there and
  // its estimate, inferred from the upper half's messages (eq. 21), stays on its exact truth.
  // Sizes are held fixed (no size noise), so that the message geometry is under test rather than
  // the scale ambiguity of a uniformly coloured half (any sub-box of it scores rho = 1).
  Scene scene;
  scene.vy = 0.0;
  scene.occluder = cv::Rect(100, 112, 80, 128);  // hides rows >= 112: the lower half
  filters::PartParticleParams p;
  p.seed = 4;
  p.color.motion.noise[2] = p.color.motion.noise[3] = 0.0;
  filters::PartParticleFilter pf(p);
  pf.init(scene.frame(0), scene.truth(0));
  int occluded_frames = 0;
  double worst_hidden = 0.0, worst_object = 0.0;
  for (int k = 1; k <= 80; ++k) {
    ASSERT_TRUE(pf.update(scene.frame(k)));
    const Box t = scene.truth(k);
    const bool hidden = t.x >= 100 && t.x + t.w <= 180;  // the lower half wholly behind it
    if (hidden) {
      occluded_frames += pf.occluded(1);
      worst_hidden = std::max(worst_hidden, centre_error(pf.part_box(1), scene.part_truth(k, 1)));
    }
    worst_object = std::max(worst_object, centre_error(pf.box(), t));
    for (int part = 0; part < 2; ++part) ASSERT_TRUE(pf.weights(part).allFinite());
  }
  EXPECT_GT(occluded_frames, 15);
  EXPECT_LT(worst_hidden, 8.0);
  EXPECT_LT(worst_object, 8.0);
}

TEST(PartParticleFilter, SameSeedSameTrackAndLayouts) {
  const Scene scene;
  auto run = [&](std::uint64_t seed, int parts) {
    filters::PartParticleParams p;
    p.seed = seed;
    p.parts = parts;
    filters::PartParticleFilter pf(p);
    pf.init(scene.frame(0), scene.truth(0));
    std::vector<double> xs;
    for (int k = 1; k <= 8; ++k) {
      pf.update(scene.frame(k));
      for (int q = 0; q < parts; ++q) xs.push_back(pf.part_box(q).y);
    }
    return xs;
  };
  EXPECT_EQ(run(1, 2), run(1, 2));
  EXPECT_NE(run(1, 2), run(2, 2));
  EXPECT_EQ(run(1, 3).size(), 24u);
  // A layout from the API: a chain of three stripes (no edge 0-2).
  filters::PartLayout chain = filters::PartLayout::stripes(3);
  chain.edges = {{0, 1}, {1, 2}};
  filters::PartParticleFilter pf({}, chain);
  pf.init(scene.frame(0), scene.truth(0));
  pf.update(scene.frame(1));
  EXPECT_EQ(pf.particle_boxes(0).rows(), 2 * 15);
  EXPECT_EQ(pf.particle_boxes(1).rows(), 3 * 15);
  EXPECT_THROW(pf.message(0, 2), InvalidArgument);
}

TEST(ColorTrackers, BadInput) {
  const Scene scene;
  const cv::Mat f = scene.frame(0);
  filters::ColorParticleFilter pf;
  filters::PartParticleFilter parts;
  EXPECT_THROW(pf.update(f), InvalidArgument);     // before init
  EXPECT_THROW(parts.update(f), InvalidArgument);
  EXPECT_THROW(pf.init(f, {10, 10, 0, 20}), InvalidArgument);      // zero width
  EXPECT_THROW(pf.init(f, {10, 10, 20, -5}), InvalidArgument);     // negative height
  EXPECT_THROW(pf.init(f, {400, 10, 20, 20}), InvalidArgument);    // no pixel in the frame
  EXPECT_THROW(pf.init(f, {std::nan(""), 10, 20, 20}), InvalidArgument);
  cv::Mat black = f.clone();
  black(cv::Rect(10, 10, 20, 20)).setTo(cv::Scalar(0, 0, 0));
  EXPECT_THROW(pf.init(black, {10, 10, 20, 20}), InvalidArgument);  // all black
  EXPECT_THROW(parts.init(black, {10, 10, 20, 20}), InvalidArgument);
  pf.init(f, scene.truth(0));
  parts.init(f, scene.truth(0));
  cv::Mat small(100, 100, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_THROW(pf.update(small), InvalidArgument);  // another size than init saw
  EXPECT_THROW(parts.update(small), InvalidArgument);
  filters::ColorParticleParams bad;
  bad.color.sigma = std::nan("");
  EXPECT_THROW(filters::ColorParticleFilter{bad}, InvalidArgument);
  filters::PartParticleParams bad_parts;
  bad_parts.color.motion.noise[1] = std::nan("");
  EXPECT_THROW(filters::PartParticleFilter{bad_parts}, InvalidArgument);
  filters::PartLayout loop = filters::PartLayout::stripes(2);
  loop.edges.push_back({1, 1});
  EXPECT_THROW(filters::PartParticleFilter({}, loop), InvalidArgument);
}

TEST(ColorTrackers, TargetLeavingTheImageIsNotOk) {
  // The figure walks out of the right border at 4 px/frame: the trackers follow it out and report
  // ok = false (no crash, finite weights) once the estimate's centre has left.
  Scene scene;
  scene.x0 = 250;
  scene.vx = 4.0;
  scene.vy = 0.0;
  filters::ColorParticleFilter pf;
  filters::PartParticleFilter parts;
  pf.init(scene.frame(0), scene.truth(0));
  parts.init(scene.frame(0), scene.truth(0));
  bool pf_lost = false, parts_lost = false;
  for (int k = 1; k <= 40; ++k) {
    const cv::Mat f = scene.frame(k);
    pf_lost = pf_lost || !pf.update(f);
    parts_lost = parts_lost || !parts.update(f);
    ASSERT_TRUE(pf.weights().allFinite());
    ASSERT_TRUE(parts.weights(0).allFinite());
  }
  EXPECT_TRUE(pf_lost);
  EXPECT_TRUE(parts_lost);
}
