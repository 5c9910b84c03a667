#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <opencv2/core.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/filters/particle_glmb.hpp"

using namespace vtrack;
using filters::GaussianBirth;
using filters::GaussianGlmbFilter;
using filters::GlmbParams;
using filters::ParticleGlmbFilter;
using filters::ParticleParams;
using models::LinearGaussianMotion;
using models::LinearGaussianObservation;

namespace {

// The paper's 3-D model at 30 Hz (eq. 7) and eq. (2)'s position detections.
LinearGaussianMotion motion3() { return LinearGaussianMotion::constant_velocity(3, 1.0 / 30, 1.0); }
LinearGaussianObservation observation3() {
  return LinearGaussianObservation::position_of_constant_velocity(
      3, Eigen::Vector3d(0.05, 0.05, 0.1).cwiseAbs2().asDiagonal());
}
GaussianBirth birth3() {
  Eigen::VectorXd m(6);
  m << 0.0, 0.5, 0.6, 0.0, 3.0, -0.3;
  Eigen::VectorXd sd(6);
  sd << 0.2, 0.5, 0.2, 0.2, 0.3, 0.5;
  return {0.5, {m, sd.cwiseAbs2().asDiagonal()}};
}
GlmbParams certain() {
  GlmbParams p;
  p.survival_probability = 1.0;
  p.detection_probability = 1.0;
  p.clutter_intensity = 1e-30;
  return p;
}

models::DepthLikelihood depth_model() {
  models::DepthLikelihoodParams p;
  p.camera = {131.25, 131.25, 79.5, 59.5, 160, 120};
  return models::DepthLikelihood(p);
}

}  // namespace

TEST(ParticleGlmb, OneCertainTargetMatchesTheKalmanFilter) {
  // p_S = p_D = 1, no clutter: both filters must keep the one track and take every detection, so
  // the Gaussian GLMB is the Kalman filter and the particle GLMB is a bootstrap particle filter of
  // the same model: its weighted mean converges to the Kalman mean. The 2-D standard model (T = 1,
  // sigma_v = 5, R = 100 I) keeps a bootstrap filter well mixed (the process noise refreshes the
  // velocities each scan). Tolerance: 5 Monte Carlo standard errors sqrt(P_ii / N_eff) with
  // N_eff >= N/4 (resampling at N/2), and the covariance within 40 %.
  const auto motion = LinearGaussianMotion::constant_velocity(2, 1.0, 5.0);
  const auto obs = LinearGaussianObservation::position_of_constant_velocity(
      2, Eigen::Matrix2d::Identity() * 100.0);
  const GaussianBirth birth{0.5, {Eigen::Vector4d(0, 1, 0, 1), Eigen::Matrix4d::Identity() * 400.0}};
  ParticleParams pp;
  pp.n_particles = 4000;
  GlmbParams seeded = certain();
  seeded.seed = 5;
  GaussianGlmbFilter kalman(motion, obs, {birth}, certain());
  ParticleGlmbFilter particles(motion, obs, {birth}, seeded, pp);
  core::Rng rng(8);
  Eigen::Vector4d truth(0, 1, 0, 1);
  for (int k = 1; k <= 20; ++k) {
    truth = motion.F * truth;
    const Eigen::Vector2d z = obs.H * truth + Eigen::Vector2d(rng.normal(), rng.normal()) * 10.0;
    kalman.step(z);
    particles.step(z);
    const auto a = kalman.estimates(), b = particles.estimates();
    ASSERT_EQ(a.size(), 1u);
    ASSERT_EQ(b.size(), 1u) << "scan " << k;
    EXPECT_TRUE(a[0].label == b[0].label);
    for (int i = 0; i < 4; ++i) {
      const double se = std::sqrt(a[0].cov(i, i) / (pp.n_particles / 4.0));
      EXPECT_NEAR(b[0].mean[i], a[0].mean[i], 5.0 * se) << "scan " << k << " component " << i;
      EXPECT_NEAR(b[0].cov(i, i), a[0].cov(i, i), 0.4 * a[0].cov(i, i)) << "scan " << k;
    }
  }
}

TEST(ParticleGlmb, SameSeedSameTracksOtherSeedOtherParticles) {
  auto run = [](std::uint64_t seed) {
    ParticleParams pp;
    pp.n_particles = 200;
    GlmbParams p;
    p.seed = seed;
    ParticleGlmbFilter f(motion3(), observation3(), {birth3()}, p, pp, depth_model());
    cv::Mat depth = cv::Mat::zeros(120, 160, CV_32F);
    depth(cv::Rect(70, 40, 25, 60)).setTo(3.0f);
    std::vector<double> out;
    for (int k = 0; k < 10; ++k) {
      Eigen::MatrixXd z(3, 1);
      z << 0.01 * k, 0.6, 3.0;
      f.step(k % 3 == 2 ? Eigen::MatrixXd(3, 0) : z, &depth);
      for (const auto& e : f.estimates()) out.insert(out.end(), e.mean.data(), e.mean.data() + 6);
    }
    return out;
  };
  const auto a = run(3), b = run(3), c = run(4);
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(ParticleGlmb, RejectsBadInput) {
  ParticleParams pp;
  pp.n_particles = 1;
  EXPECT_THROW(ParticleGlmbFilter(motion3(), observation3(), {birth3()}, GlmbParams{}, pp),
               InvalidArgument);
  ParticleParams negative_margin;
  negative_margin.mask_depth_margin = -0.1;
  EXPECT_THROW(ParticleGlmbFilter(motion3(), observation3(), {birth3()}, GlmbParams{},
                                  negative_margin),
               InvalidArgument);
  auto bad_birth = birth3();
  bad_birth.density.cov(0, 0) = -1.0;  // not positive definite
  EXPECT_THROW(ParticleGlmbFilter(motion3(), observation3(), {bad_birth}), InvalidArgument);
  GlmbParams no_hypotheses;
  no_hypotheses.max_hypotheses = 0;
  EXPECT_THROW(ParticleGlmbFilter(motion3(), observation3(), {birth3()}, no_hypotheses),
               InvalidArgument);
  auto obs2 = LinearGaussianObservation::position_of_constant_velocity(2, Eigen::Matrix2d::Identity());
  EXPECT_THROW(ParticleGlmbFilter(LinearGaussianMotion::constant_velocity(2, 1.0, 1.0), obs2, {},
                                  GlmbParams{}, ParticleParams{}, depth_model()),
               InvalidArgument);  // the depth model needs (X, Y, D) detections

  ParticleGlmbFilter without(motion3(), observation3(), {birth3()});
  cv::Mat depth = cv::Mat::zeros(120, 160, CV_32F);
  EXPECT_THROW(without.step(Eigen::MatrixXd(3, 0), &depth), InvalidArgument);  // no depth model
  ParticleGlmbFilter with(motion3(), observation3(), {birth3()}, GlmbParams{}, ParticleParams{},
                          depth_model());
  cv::Mat wrong = cv::Mat::zeros(100, 160, CV_32F);
  EXPECT_THROW(with.step(Eigen::MatrixXd(3, 0), &wrong), InvalidArgument);
  Eigen::MatrixXd nan = Eigen::MatrixXd::Zero(3, 1);
  nan(1, 0) = std::nan("");
  EXPECT_THROW(with.step(nan, &depth), InvalidArgument);
  EXPECT_EQ(with.time(), 0);
}

TEST(ParticleGlmb, VanishingLikelihoodsNeverProduceNaN) {
  // No gate and detections absurdly far from every particle: every g1(z|x_p) underflows (log
  // -inf or ~-1e300), and a depth image full of far values makes every depth ratio tiny. The
  // filter must stay finite and normalised.
  GlmbParams p;
  p.gate_threshold = std::numeric_limits<double>::infinity();
  ParticleParams pp;
  pp.n_particles = 100;
  ParticleGlmbFilter f(motion3(), observation3(), {birth3()}, p, pp, depth_model());
  cv::Mat depth(120, 160, CV_32F, cv::Scalar(1e6f));
  for (int k = 0; k < 5; ++k) {
    Eigen::MatrixXd z(3, 2);
    z << 1e150, -1e150, 1e150, 3.0, 1e151, 1e3;
    f.step(z, &depth);
    const Eigen::VectorXd card = f.cardinality_distribution();
    ASSERT_TRUE(card.allFinite());
    EXPECT_NEAR(card.sum(), 1.0, 1e-9);
    for (const auto& e : f.estimates()) {
      EXPECT_TRUE(e.mean.allFinite());
      EXPECT_TRUE(e.cov.allFinite());
    }
  }
}

TEST(ParticleGlmb, DetectionMaskKeepsTheSurfaceInFrontOfTheDetection) {
  // A missed person A at D = 2 m stands in front of a detected person B at D = 3 m, 0.2 m to the
  // side: A hides most of B's rectangle. The detection's footprint T(z_B) covers part of A's
  // pixels. With mask_depth_margin 0.3 only the pixels of T(z_B) at depth >= 2.7 are blanked, so A
  // keeps every pixel of its own; with +inf the whole T(z_B) is blanked (A loses the overlap, which
  // then votes "background"). Expected scores: DepthLikelihood::log_ratio on the image masked here
  // independently (cv::compare on the raw image), with the detection's occluder.
  const auto model = depth_model();
  const Eigen::Vector3d a(0.0, 0.6, 2.0), b(0.2, 0.6, 3.0);
  cv::Mat depth = cv::Mat::zeros(120, 160, CV_32F);
  const image::Rect ra = model.footprint(a.x(), a.y(), a.z());
  const image::Rect rb = model.footprint(b.x(), b.y(), b.z());
  const cv::Rect rect_a(ra.x, ra.y, ra.width, ra.height), rect_b(rb.x, rb.y, rb.width, rb.height);
  depth(rect_b).setTo(3.0f);
  depth(rect_a).setTo(2.0f);  // nearer: drawn last
  ASSERT_GT((rect_a & rect_b).area(), 0);

  Eigen::VectorXd mean(6);
  mean << a.x(), 0.0, a.y(), 0.0, a.z(), 0.0;
  const Eigen::MatrixXd cov = Eigen::VectorXd::Constant(6, 1e-4).asDiagonal();
  const models::GaussianDensity at_a{mean, cov};
  auto scores = [&](double margin, Eigen::VectorXd& expected) {
    ParticleParams pp;
    pp.n_particles = 200;
    pp.mask_depth_margin = margin;
    filters::ParticleTracks tracks(pp, 7, motion3(), observation3(), model);
    tracks.set_depth(&depth, b);
    auto c = tracks.candidate(tracks.birth(at_a), observation3(), filters::TrackLabel{1, 0},
                              false);
    cv::Mat masked = depth.clone();
    cv::Mat blank;
    cv::compare(masked(rect_b), b.z() - margin, blank, cv::CMP_GE);
    masked(rect_b).setTo(0.0f, blank);
    auto frame = model.frame(masked);
    frame.occluders.push_back({rb, b.z() + pp.occlusion_margin});
    expected.resize(c.predicted_z.cols());
    model.log_ratio(frame, c.predicted_z, expected);
    return c.depth_log_ratio;
  };
  Eigen::VectorXd expected_kept, expected_blanked;
  const Eigen::VectorXd kept = scores(0.3, expected_kept);
  const Eigen::VectorXd blanked = scores(std::numeric_limits<double>::infinity(), expected_blanked);
  ASSERT_EQ(kept.size(), 200);
  EXPECT_LT((kept - expected_kept).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((blanked - expected_blanked).cwiseAbs().maxCoeff(), 1e-9);
  // A's own pixels are evidence for A only when they are kept.
  EXPECT_GT(kept.mean(), blanked.mean() + 1.0);
  EXPECT_GT(kept.mean(), 0.0);
}

TEST(ParticleGlmb, ReportedTracksHideWhatIsBehindThemFromUnreportedTracks) {
  // A person A at D = 2 m, missed (no detection), is a reported track. A candidate 0.5 m behind
  // A, on A's pixels, scores them as its own under eq. (4) (each pixel votes for any state less
  // than twice its depth away). With track_occluders a birth there (outside the report) finds
  // its whole footprint hidden by A's and scores 0, while the reported track itself keeps eq. (4)
  // as without the option. Expected scores: DepthLikelihood::log_ratio on the image without any
  // occluder, at the same particles.
  const auto model = depth_model();
  const Eigen::Vector3d a(0.0, 0.6, 2.0);
  cv::Mat depth = cv::Mat::zeros(120, 160, CV_32F);
  const image::Rect ra = model.footprint(a.x(), a.y(), a.z());
  depth(cv::Rect(ra.x, ra.y, ra.width, ra.height)).setTo(2.0f);
  Eigen::VectorXd mean(6);
  mean << a.x(), 0.0, a.y(), 0.0, a.z() + 0.5, 0.0;
  const models::GaussianDensity behind{mean, Eigen::VectorXd::Constant(6, 1e-6).asDiagonal()};
  const filters::TrackLabel label_a{1, 0}, newborn{5, 0};
  const std::vector<filters::ParticleTracks::ReportedTrack> reported{{label_a, a}};
  auto score = [&](bool track_occluders, const filters::TrackLabel& label, bool is_birth,
                   Eigen::VectorXd& expected) {
    ParticleParams pp;
    pp.n_particles = 100;
    pp.track_occluders = track_occluders;
    filters::ParticleTracks tracks(pp, 3, motion3(), observation3(), model);
    tracks.set_depth(&depth, Eigen::MatrixXd(3, 0), reported);
    auto c = tracks.candidate(tracks.birth(behind), observation3(), label, is_birth);
    expected.resize(c.predicted_z.cols());
    model.log_ratio(model.frame(depth), c.predicted_z, expected);
    return c.depth_log_ratio;
  };
  Eigen::VectorXd unhidden;
  const Eigen::VectorXd birth_before = score(false, newborn, true, unhidden);
  EXPECT_LT((birth_before - unhidden).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT(birth_before.minCoeff(), 1.0);  // A's pixels support the state behind A
  const Eigen::VectorXd birth_after = score(true, newborn, true, unhidden);
  EXPECT_LT(birth_after.cwiseAbs().maxCoeff(), 1e-12);  // all hidden: no evidence either way
  const Eigen::VectorXd track_after = score(true, label_a, false, unhidden);
  EXPECT_LT((track_after - unhidden).cwiseAbs().maxCoeff(), 1e-9);
}
