#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/filters/detector_learning.hpp"
#include "vtrack/filters/glmb.hpp"
#include "distributions.hpp"

using namespace vtrack;
using filters::ClutterRate;
using filters::DetectionProbability;
using filters::Forgetting;
using filters::ScoreModel;
using filters::WeightedGaussian;

using vtrack::test_reference::normal_cdf;

namespace {

}  // namespace

TEST(NormalQuantile, InvertsTheNormalCdf) {
  // Reference values (Abramowitz & Stegun 26.2) and the round trip through erfc.
  EXPECT_NEAR(core::normal_quantile(0.975), 1.959963984540054, 1e-12);
  EXPECT_NEAR(core::normal_quantile(0.5), 0.0, 1e-15);
  EXPECT_NEAR(core::normal_quantile(0.001), -3.090232306167814, 1e-11);
  for (double p : {1e-300, 1e-12, 0.01, 0.02425, 0.3, 0.7, 0.97575, 0.999, 1.0 - 1e-12}) {
    EXPECT_NEAR(normal_cdf(core::normal_quantile(p)), p, 1e-12 * std::max(p, 1e-3)) << p;
  }
  EXPECT_THROW(core::normal_quantile(0.0), InvalidArgument);
  EXPECT_THROW(core::normal_quantile(1.0), InvalidArgument);
}

TEST(DetectorLearning, ClutterRateIsTheGammaPoissonPosteriorWithForgetting) {
  // estimate = (n0 lambda0 + sum_i f^(k-i) c_i) / (n0 + sum_i f^(k-i) e_i), f = 1 - 1/memory.
  const Forgetting forgetting{20.0, 5.0};
  ClutterRate rate(2.0, forgetting);
  EXPECT_DOUBLE_EQ(rate.rate(), 2.0);
  const std::vector<double> counts{3.0, 0.5, 7.25, 4.0}, exposure{1.0, 2.0, 1.0, 0.5};
  for (std::size_t i = 0; i < counts.size(); ++i) rate.update(counts[i], exposure[i]);
  const double f = 1.0 - 1.0 / 20.0;
  double num = 5.0 * 2.0, den = 5.0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double decay = std::pow(f, static_cast<double>(counts.size() - 1 - i));
    num += decay * counts[i];
    den += decay * exposure[i];
  }
  EXPECT_NEAR(rate.rate(), num / den, 1e-12);
  EXPECT_THROW(ClutterRate(0.0, forgetting), InvalidArgument);
  EXPECT_THROW(ClutterRate(1.0, Forgetting{0.5, 1.0}), InvalidArgument);
}

TEST(DetectorLearning, DetectionProbabilityIsTheBetaPosteriorWithinItsBounds) {
  DetectionProbability p_d(0.8, 0.3, 0.98, Forgetting{1e9, 10.0});
  p_d.update(6.0, 4.0);
  p_d.update(3.5, 0.5);
  // (10 * 0.8 + 9.5) / (10 + 9.5 + 4.5), forgetting negligible.
  EXPECT_NEAR(p_d.probability(), 17.5 / 24.0, 1e-7);
  for (int k = 0; k < 100; ++k) p_d.update(0.0, 10.0);
  EXPECT_DOUBLE_EQ(p_d.probability(), 0.3);  // clamped at the lower bound
  EXPECT_THROW(DetectionProbability(0.2, 0.3, 0.98, {}), InvalidArgument);
}

TEST(DetectorLearning, WeightedGaussianPoolsThePriorAndTheWeightedData) {
  const Eigen::Vector2d m0(1.0, -1.0);
  Eigen::Matrix2d c0;
  c0 << 2.0, 0.3, 0.3, 1.0;
  WeightedGaussian g(m0, c0, 4.0, 1e12);
  Eigen::MatrixXd y(2, 3);
  y << 0.0, 2.0, 5.0, 1.0, -3.0, 0.5;
  const Eigen::Vector3d w(0.5, 1.0, 2.5);
  g.update(y, w);
  // The prior is 4 points with covariance c0 about m0; the data add weighted points.
  const Eigen::Vector2d mean = (4.0 * m0 + y * w) / (4.0 + w.sum());
  Eigen::Matrix2d second = 4.0 * (c0 + (m0 - mean) * (m0 - mean).transpose());
  for (int j = 0; j < 3; ++j) second += w[j] * (y.col(j) - mean) * (y.col(j) - mean).transpose();
  const Eigen::Matrix2d cov = second / (4.0 + w.sum());
  EXPECT_TRUE(g.mean().isApprox(mean, 1e-9));
  EXPECT_TRUE(g.covariance().isApprox(cov, 1e-9));
  const Eigen::VectorXd log_p = g.log_density(y);
  const core::Gaussian reference(mean, cov);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(log_p[j], reference.log_density(y.col(j)), 1e-9);
}

TEST(DetectorLearning, ScoreModelRatioIsOneWhenScoresCarryNoInformation) {
  // All scores equal: every u is 0, both class means stay 0, the log ratio is exactly 0.
  ScoreModel model(100, 10.0, 50.0);
  const Eigen::VectorXd scores = Eigen::VectorXd::Constant(8, 0.7);
  Eigen::VectorXd p_target(8);
  p_target << 1, 1, 1, 1, 0, 0, 0, 0.5;
  for (int k = 0; k < 20; ++k) {
    const Eigen::VectorXd u = model.transform(scores);
    EXPECT_TRUE((u.array() == 0.0).all());
    model.update(scores, u, p_target);
  }
  EXPECT_TRUE((model.log_ratio(model.transform(scores)).array() == 0.0).all());
}

TEST(DetectorLearning, ScoreModelWindowKeepsTheLastScoresOnceFull) {
  // A window of 50 fed scans of 7 scores (repeated values, ties included) wraps around many
  // times: u must be the mid-rank quantile among exactly the last 50 scores, counted directly.
  const int window = 50;
  ScoreModel model(window, 10.0, 100.0);
  core::Rng rng(5);
  std::vector<double> seen;
  const Eigen::VectorXd probe = (Eigen::VectorXd(5) << 0.0, 0.25, 0.5, 0.55, 1.0).finished();
  for (int k = 0; k < 40; ++k) {
    Eigen::VectorXd scores(7);
    for (auto& s : scores) s = std::round(20.0 * rng.uniform()) / 20.0;
    model.update(scores, Eigen::VectorXd::Zero(7), Eigen::VectorXd::Zero(7));
    seen.insert(seen.end(), scores.begin(), scores.end());
    const std::size_t n = std::min<std::size_t>(seen.size(), window);
    const Eigen::VectorXd u = model.transform(probe);
    for (Eigen::Index j = 0; j < probe.size(); ++j) {
      double below = 0.0, equal = 0.0;
      for (std::size_t i = seen.size() - n; i < seen.size(); ++i) {
        below += seen[i] < probe[j];
        equal += seen[i] == probe[j];
      }
      const double F = std::clamp((below + 0.5 * equal) / n, 0.5 / n, 1.0 - 0.5 / n);
      EXPECT_EQ(u[j], F == 0.5 ? 0.0 : core::normal_quantile(F)) << "scan " << k << " probe " << j;
    }
  }
}

TEST(DetectorLearning, ScoreModelLearnsWhichScoresBelongToTargets) {
  // Targets score high, clutter low: the learnt log ratio increases with the score and its sign
  // separates the classes; u is the normal quantile of the score's mid-rank among those seen.
  ScoreModel model(1000, 10.0, 100.0);
  Eigen::VectorXd scores(10), p_target(10);
  for (int j = 0; j < 10; ++j) {
    scores[j] = 0.05 + 0.1 * j;
    p_target[j] = j >= 5 ? 1.0 : 0.0;
  }
  for (int k = 0; k < 30; ++k) model.update(scores, model.transform(scores), p_target);
  const Eigen::VectorXd u = model.transform(scores);
  // Every score seen 30 times among 300: the mid-rank of the j-th value is (30 j + 15) / 300.
  for (int j = 0; j < 10; ++j) {
    EXPECT_NEAR(u[j], core::normal_quantile((30.0 * j + 15.0) / 300.0), 1e-12);
  }
  EXPECT_GT(model.target_mean(), 0.5);
  EXPECT_LT(model.clutter_mean(), -0.5);
  const Eigen::VectorXd r = model.log_ratio(u);
  for (int j = 1; j < 10; ++j) EXPECT_GT(r[j], r[j - 1]);
  EXPECT_LT(r[0], 0.0);
  EXPECT_GT(r[9], 0.0);
}

namespace {

// One target moving at (10, 5) per scan from the origin, detected at every scan except `gap`;
// returns the reported labels' birth times per scan (-1: nothing reported).
struct GapRun {
  std::vector<int> labels;        // the reported label's birth time per scan, -1: none
  std::vector<double> existence;  // P(at least one track) per scan
};

GapRun run_through_a_gap(double occlusion_rate, int first_missed, int last_missed,
                         filters::EstimatorParams estimator = {filters::LabelEstimator::map}) {
  const auto motion = models::LinearGaussianMotion::constant_velocity(2, 1.0, 1.0);
  const auto obs = models::LinearGaussianObservation::position_of_constant_velocity(
      2, Eigen::Matrix2d::Identity() * 4.0);
  filters::GlmbParams params;
  params.detection_probability = 0.9;
  params.survival_probability = 0.99;
  params.clutter_intensity = 1e-6;
  params.occlusion.rate = occlusion_rate;
  params.occlusion.length = 10.0;
  params.estimator = estimator;
  params.adaptive_birth.enabled = true;
  params.adaptive_birth.cov = Eigen::Vector4d(4.0, 400.0, 4.0, 400.0).asDiagonal();
  filters::GaussianGlmbFilter glmb(motion, obs, {}, params);
  GapRun run;
  for (int k = 1; k <= 30; ++k) {
    const Eigen::Vector2d z(10.0 * k, 5.0 * k);
    glmb.step(k >= first_missed && k <= last_missed ? Eigen::MatrixXd(2, 0) : Eigen::MatrixXd(z));
    const auto& est = glmb.estimates();
    run.labels.push_back(est.empty() ? -1 : est[0].label.birth_time);
    run.existence.push_back(1.0 - glmb.cardinality_distribution()[0]);
  }
  return run;
}

std::vector<int> labels_through_a_gap(double occlusion_rate, int first_missed, int last_missed) {
  return run_through_a_gap(occlusion_rate, first_missed, last_missed).labels;
}

}  // namespace

TEST(GlmbOcclusion, ARunOfMissesKeepsTheTrackInTheEstimate) {
  // Missed at scans 12-19. With constant p_D a miss costs -log(p_S (1 - p_D)) = 2.3 nats against
  // -log(1 - p_S) = 4.6 for dying once, so after two misses the MAP estimate holds no track
  // (the label lingers in light hypotheses and returns with the detections). With runs of misses
  // (rate 0.05, mean length 10) the visibility mode turns undetectable after a few misses and
  // further misses cost about -log(1 - 1/10) = 0.1 nats each: the track is reported through the
  // whole run under its label.
  const auto constant = labels_through_a_gap(0.0, 12, 19);
  const auto occluded = labels_through_a_gap(0.05, 12, 19);
  const int first = occluded[10];  // scan 11, before the gap
  ASSERT_GE(first, 1);
  EXPECT_EQ(constant[10], first);
  for (int k = 11; k <= 30; ++k) EXPECT_EQ(occluded[k - 1], first) << "scan " << k;
  for (int k = 14; k <= 20; ++k) EXPECT_EQ(constant[k - 1], -1) << "scan " << k;
  for (int k = 22; k <= 30; ++k) EXPECT_EQ(constant[k - 1], first) << "scan " << k;
}

TEST(GlmbEstimator, ConsistentEstimatorIsHysteresisOnTheExistence) {
  // One label at a time (negligible clutter and births): the consistent estimator maximises
  // log w(I) + keep_bonus |I & R| - entry_penalty |I \ R|, so with existence r a reported label
  // stays while r > 1 / (1 + e^keep_bonus) and a new one enters once r > 1 / (1 + e^-entry).
  // The filtering is the same as the MAP estimator's run; only the report differs.
  filters::EstimatorParams consistent;
  consistent.estimator = filters::LabelEstimator::consistent;
  consistent.keep_bonus = 2.0;
  consistent.entry_penalty = 1.0;
  const GapRun run = run_through_a_gap(0.0, 12, 25, consistent);
  const double stay = 1.0 / (1.0 + std::exp(2.0)), enter = 1.0 / (1.0 + std::exp(-1.0));
  bool reported = false;
  int checked = 0;
  for (std::size_t k = 0; k < run.labels.size(); ++k) {
    const double r = run.existence[k];
    const double threshold = reported ? stay : enter;
    if (std::abs(r - threshold) > 0.01) {
      EXPECT_EQ(run.labels[k] >= 0, r > threshold) << "scan " << k + 1 << ", r = " << r;
      ++checked;
    }
    reported = run.labels[k] >= 0;
  }
  EXPECT_GE(checked, 25);
  // The hysteresis held the label below r = 0.5 during the run of misses, and dropped it later.
  const auto map = run_through_a_gap(0.0, 12, 25).labels;
  int held = 0;
  for (std::size_t k = 11; k < 25; ++k) held += run.labels[k] >= 0 && map[k] < 0;
  EXPECT_GE(held, 1);
  EXPECT_EQ(run.labels[24], -1);
}

TEST(GlmbEstimator, DuplicateGateReportsOneLabelPerTarget) {
  // Two birth components at each of two places, existence 0.9, p_D 0.5, one detection at each
  // place. Per place, the hypothesis with both labels (one takes the detection, the other is
  // missed) has weight 0.9 * 0.9 (1 - p_D) = 0.405 against 0.9 * 0.1 = 0.09 with one of them
  // absent, so the best hypothesis holds two labels on each target, at the same mean. With the
  // gate (chi-square 0.99 quantile for 2-D detections) one label per target is reported: the
  // older (lower birth index at equal birth time); the two targets, 100 sigma apart, both stay.
  const auto motion = models::LinearGaussianMotion::constant_velocity(2, 1.0, 1.0);
  const auto obs = models::LinearGaussianObservation::position_of_constant_velocity(
      2, Eigen::Matrix2d::Identity() * 4.0);
  const Eigen::Vector4d a(0.0, 0.0, 0.0, 0.0), b(200.0, 0.0, 0.0, 0.0);
  const Eigen::Matrix4d cov = Eigen::Vector4d(4.0, 1.0, 4.0, 1.0).asDiagonal();
  const std::vector<filters::GaussianBirth> births = {
      {0.9, {a, cov}}, {0.9, {a, cov}}, {0.9, {b, cov}}, {0.9, {b, cov}}};
  Eigen::MatrixXd z(2, 2);
  z << 1.0, 201.0, -1.0, 1.0;
  filters::GlmbParams params;
  params.detection_probability = 0.5;
  params.clutter_intensity = 1e-6;
  auto report = [&](double gate) {
    params.estimator.duplicate_gate = gate;
    filters::GaussianGlmbFilter glmb(motion, obs, births, params);
    glmb.step(z);
    std::vector<int> indices;
    for (const auto& e : glmb.estimates()) indices.push_back(e.label.birth_index);
    std::sort(indices.begin(), indices.end());
    return indices;
  };
  EXPECT_EQ(report(0.0), (std::vector<int>{0, 1, 2, 3}));  // two labels on each target
  EXPECT_EQ(report(9.21), (std::vector<int>{0, 2}));
  filters::EstimatorParams bad;
  bad.duplicate_gate = -1.0;
  EXPECT_THROW(filters::validate(bad), InvalidArgument);
}

TEST(GlmbOcclusion, RejectsBadParameters) {
  filters::OcclusionParams p;
  p.rate = 1.0;
  EXPECT_THROW(filters::validate(p), InvalidArgument);
  p = {};
  p.length = 0.5;
  EXPECT_THROW(filters::validate(p), InvalidArgument);
  p = {};
  p.max_length = 0;
  EXPECT_THROW(filters::validate(p), InvalidArgument);
}

TEST(GlmbGate, AtMostGateMaxDetectionsEnterATrackAssociation) {
  // A thousand detections inside one track's gate: with gate_max_detections = 5 the posterior
  // can only have assigned the track to one of the 5 most likely (closest) detections.
  const auto motion = models::LinearGaussianMotion::constant_velocity(2, 1.0, 1.0);
  const auto obs = models::LinearGaussianObservation::position_of_constant_velocity(
      2, Eigen::Matrix2d::Identity() * 100.0);
  filters::GlmbParams params;
  params.gate_max_detections = 5;
  params.gate_threshold = std::numeric_limits<double>::infinity();
  filters::GaussianBirth birth{0.99, {Eigen::Vector4d::Zero(), Eigen::Matrix4d::Identity()}};
  filters::GaussianGlmbFilter glmb(motion, obs, {birth}, params);
  Eigen::MatrixXd z(2, 1000);
  z.row(0) = Eigen::RowVectorXd::LinSpaced(1000, 0.01, 10.0);
  z.row(1).setZero();
  glmb.step(z);
  const auto& to_track = glmb.summary().to_birth;
  EXPECT_GT(to_track.head(5).sum(), 0.9);
  EXPECT_DOUBLE_EQ(to_track.tail(995).sum(), 0.0);
}
