// Metropolis-Hastings chains (smc/mh.hpp) against known targets, and the MCMC particle filter
// (smc/mcmc.hpp) against the closed-form targets of a linear-Gaussian model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/models/linear_gaussian.hpp"
#include "vtrack/models/linear_gaussian_likelihood.hpp"
#include "vtrack/models/motion.hpp"
#include "vtrack/smc/mcmc.hpp"
#include "distributions.hpp"

using namespace vtrack;

using vtrack::test_reference::ks_statistic;
using vtrack::test_reference::normal_cdf;

namespace {

std::vector<double> column(const Eigen::MatrixXd& m, int c) {
  return std::vector<double>(m.col(c).data(), m.col(c).data() + m.rows());
}

// The chains below are thinned until successive kept samples are nearly independent, so the
// i.i.d. KS critical value applies: 1.63 / sqrt(n) at alpha = 0.01.
double ks_critical(Eigen::Index n) { return 1.63 / std::sqrt(static_cast<double>(n)); }

// An independence proposal x' ~ N(0, s^2), whose q ratio is not 1: log q(x) - log q(x').
struct IndependenceProposal {
  double s;
  double propose(const Eigen::VectorXd& from, Eigen::VectorXd& to, core::Rng& rng) {
    to.resize(from.size());
    for (Eigen::Index i = 0; i < from.size(); ++i) to[i] = s * rng.normal();
    return -0.5 * (from.squaredNorm() - to.squaredNorm()) / (s * s);
  }
};

// Always moves +1 with q ratio 1: on a flat target every proposal is accepted, so after j
// proposals the chain is at x_0 + j.
struct StepProposal {
  double propose(const Eigen::VectorXd& from, Eigen::VectorXd& to, core::Rng&) {
    to = from.array() + 1.0;
    return 0.0;
  }
};

}  // namespace

TEST(SmcMh, OneDimensionalGaussianByMomentsAndKs) {
  core::Rng rng(1);
  auto target = [](const Eigen::VectorXd& x) { return -0.5 * std::pow((x[0] - 2.0) / 3.0, 2); };
  smc::RandomWalkProposal proposal(Eigen::MatrixXd::Constant(1, 1, 7.0));
  const auto r = smc::metropolis_hastings(target, Eigen::VectorXd::Zero(1), {4000, 500, 10}, proposal, rng);
  const auto x = column(r.samples, 0);
  EXPECT_LT(ks_statistic(x, [](double v) { return normal_cdf((v - 2.0) / 3.0); }), ks_critical(4000));
  const Eigen::VectorXd c = r.samples.col(0);
  // Standard errors (near-independent samples): 3/sqrt(4000) = 0.047, 9 sqrt(2/4000) = 0.2.
  EXPECT_NEAR(c.mean(), 2.0, 0.25);
  EXPECT_NEAR((c.array() - c.mean()).square().mean(), 9.0, 1.0);
  EXPECT_GT(r.acceptance_rate(), 0.2);
  EXPECT_LT(r.acceptance_rate(), 0.6);
}

TEST(SmcMh, CorrelatedTwoDimensionalGaussian) {
  core::Rng rng(2);
  Eigen::Matrix2d cov;
  cov << 4.0, 1.8, 1.8, 1.0;  // correlation 0.9
  const core::Gaussian g(Eigen::Vector2d(1.0, -1.0), cov);
  auto target = [&](const Eigen::VectorXd& x) { return g.log_density(x); };
  smc::RandomWalkProposal proposal(1.5 * g.cholesky());
  const auto r = smc::metropolis_hastings(target, Eigen::VectorXd::Zero(2), {5000, 500, 8}, proposal, rng);
  const Eigen::Vector2d mean = r.samples.colwise().mean();
  const Eigen::MatrixXd centred = r.samples.rowwise() - mean.transpose();
  const Eigen::Matrix2d sample_cov = centred.transpose() * centred / 5000.0;
  EXPECT_NEAR(mean[0], 1.0, 0.15);
  EXPECT_NEAR(mean[1], -1.0, 0.075);
  EXPECT_LT((sample_cov - cov).cwiseAbs().maxCoeff(), 0.35);
  // The marginals by KS.
  EXPECT_LT(ks_statistic(column(r.samples, 0), [](double v) { return normal_cdf((v - 1.0) / 2.0); }),
            ks_critical(5000));
  EXPECT_LT(ks_statistic(column(r.samples, 1), [](double v) { return normal_cdf(v + 1.0); }),
            ks_critical(5000));
}

TEST(SmcMh, BimodalMixtureVisitsBothModesInProportion) {
  // 0.3 N(-3, 1) + 0.7 N(3, 1); the random walk's step (4) crosses between the modes.
  core::Rng rng(3);
  auto target = [](const Eigen::VectorXd& x) {
    const double a = 0.3 * std::exp(-0.5 * std::pow(x[0] + 3.0, 2));
    const double b = 0.7 * std::exp(-0.5 * std::pow(x[0] - 3.0, 2));
    return std::log(a + b);
  };
  auto cdf = [](double v) { return 0.3 * normal_cdf(v + 3.0) + 0.7 * normal_cdf(v - 3.0); };
  smc::RandomWalkProposal proposal(Eigen::MatrixXd::Constant(1, 1, 4.0));
  const auto r = smc::metropolis_hastings(target, Eigen::VectorXd::Zero(1), {5000, 1000, 20}, proposal, rng);
  const auto x = column(r.samples, 0);
  const double left = static_cast<double>(std::count_if(x.begin(), x.end(), [](double v) { return v < 0; })) / 5000.0;
  EXPECT_NEAR(left, 0.3, 0.04);  // sd of a proportion: sqrt(0.21 / 5000) = 0.0065, with autocorrelation
  EXPECT_LT(ks_statistic(x, cdf), ks_critical(5000));
}

TEST(SmcMh, AsymmetricProposalUsesTheHastingsRatio) {
  // Target N(1, 1) sampled with an independence proposal N(0, 2^2): without the q ratio the chain
  // would sample a different distribution.
  core::Rng rng(4);
  auto target = [](const Eigen::VectorXd& x) { return -0.5 * std::pow(x[0] - 1.0, 2); };
  IndependenceProposal proposal{2.0};
  const auto r = smc::metropolis_hastings(target, Eigen::VectorXd::Zero(1), {5000, 200, 5}, proposal, rng);
  const Eigen::VectorXd c = r.samples.col(0);
  EXPECT_NEAR(c.mean(), 1.0, 0.08);
  EXPECT_NEAR((c.array() - c.mean()).square().mean(), 1.0, 0.1);
  EXPECT_LT(ks_statistic(column(r.samples, 0), [](double v) { return normal_cdf(v - 1.0); }),
            ks_critical(5000));
}

TEST(SmcMh, BurnInAndThinningBookkeepingIsExact) {
  core::Rng rng(5);
  auto flat = [](const Eigen::VectorXd&) { return 0.0; };
  for (const auto& [samples, burn_in, thinning] :
       {std::tuple{7, 0, 1}, std::tuple{5, 3, 4}, std::tuple{10, 100, 3}}) {
    StepProposal proposal;
    const auto r = smc::metropolis_hastings(flat, Eigen::VectorXd::Zero(1),
                                            {samples, burn_in, thinning}, proposal, rng);
    EXPECT_EQ(r.proposals, burn_in + thinning * samples);
    EXPECT_EQ(r.accepted, r.proposals);
    ASSERT_EQ(r.samples.rows(), samples);
    for (int k = 0; k < samples; ++k) {
      EXPECT_EQ(r.samples(k, 0), burn_in + thinning * (k + 1));  // x_{B + c k}, k = 1..N_s
    }
  }
  StepProposal proposal;
  EXPECT_THROW(smc::metropolis_hastings(flat, Eigen::VectorXd::Zero(1), {0, 1, 1}, proposal, rng),
               InvalidArgument);
  EXPECT_THROW(smc::metropolis_hastings(flat, Eigen::VectorXd::Zero(1), {1, -1, 1}, proposal, rng),
               InvalidArgument);
  EXPECT_THROW(smc::metropolis_hastings(flat, Eigen::VectorXd::Zero(1), {1, 1, 0}, proposal, rng),
               InvalidArgument);
}

namespace {

// A 2-D constant-velocity model seen in position; the MCMC filter's targets have closed forms.
struct Model {
  models::ConstantVelocity motion{{2, 1.0, 0.5, models::AccelerationNoise::Continuous}};
  models::LinearGaussianObservation observation =
      models::LinearGaussianObservation::position_of_constant_velocity(2, 4.0 * Eigen::Matrix2d::Identity());
  core::Gaussian prior{Eigen::Vector4d(0.0, 1.0, 0.0, -0.5),
                       Eigen::Matrix4d(Eigen::Vector4d(10.0, 1.0, 10.0, 1.0).asDiagonal())};
  Eigen::Vector2d z{1.5, -2.0};
};

using Filter = smc::McmcFilter<models::ConstantVelocity, models::LinearGaussianLikelihood>;

smc::McmcParams mcmc_params(smc::McmcReference reference, int n, std::uint64_t seed) {
  smc::McmcParams p;
  p.reference = reference;
  p.n_particles = n;
  p.burn_in = 1000;
  p.thinning = 5;
  p.proposal_scale = 1.0;
  p.seed = seed;
  return p;
}

// The posterior of x given x* exactly: the Kalman update of N(F x*, Q) by z.
models::GaussianDensity given_reference(const Model& m, const Eigen::VectorXd& x_star) {
  const models::KalmanInnovation innovation({m.motion.F() * x_star, m.motion.Q()}, m.observation);
  return innovation.posterior(m.z);
}

void expect_samples_follow(const Eigen::MatrixXd& samples, const Eigen::VectorXd& mean,
                           const Eigen::MatrixXd& cov, const std::string& what) {
  const Eigen::VectorXd sample_mean = samples.colwise().mean();
  const Eigen::MatrixXd centred = samples.rowwise() - sample_mean.transpose();
  const Eigen::MatrixXd sample_cov = centred.transpose() * centred / static_cast<double>(samples.rows());
  const double n_eff = samples.rows() / 4.0;  // the thinned chain's autocorrelation, measured < 4
  for (int i = 0; i < mean.size(); ++i) {
    EXPECT_NEAR(sample_mean[i], mean[i], 5 * std::sqrt(cov(i, i) / n_eff)) << what << " " << i;
    EXPECT_NEAR(sample_cov(i, i), cov(i, i), 5 * cov(i, i) * std::sqrt(2 / n_eff)) << what << " " << i;
  }
}

}  // namespace

TEST(SmcMcmcFilter, ReferenceVariantsSampleTheirClosedFormTargets) {
  const Model m;
  const models::LinearGaussianLikelihood obs(m.observation);
  for (const auto reference : {smc::McmcReference::Random, smc::McmcReference::Map, smc::McmcReference::Mean}) {
    Filter filter(m.motion, obs, m.prior, mcmc_params(reference, 4000, 7));
    const Eigen::MatrixXd previous = filter.particles();
    const Eigen::VectorXd previous_mean = filter.mean();
    const Eigen::VectorXd previous_target = filter.log_target();
    filter.step(m.z);
    EXPECT_EQ(filter.proposals(), 1000 + 5 * 4000);
    const Eigen::VectorXd x_star = filter.reference().transpose();
    // x* is chosen by the rule of the variant (§3.3).
    if (reference == smc::McmcReference::Mean) {
      EXPECT_EQ(x_star, previous_mean);
    }
    if (reference == smc::McmcReference::Map) {
      Eigen::Index best;
      previous_target.maxCoeff(&best);
      EXPECT_EQ(x_star, previous.row(best).transpose());
    }
    if (reference == smc::McmcReference::Random) {
      EXPECT_TRUE(((previous.rowwise() - x_star.transpose()).rowwise().norm().array() == 0).any());
    }
    const auto exact = given_reference(m, x_star);
    expect_samples_follow(filter.particles(), exact.mean, exact.cov, smc::to_string(reference));
    EXPECT_TRUE(filter.mean().allFinite());
  }
}

TEST(SmcMcmcFilter, AllReferenceSamplesTheMixturePosterior) {
  // pi(x) ∝ p(z|x) sum_i N(x; F x_i, Q): a mixture whose component i has weight
  // ∝ N(z; H F x_i, H Q H^T + R) and the Kalman posterior of N(F x_i, Q) as its density.
  const Model m;
  Filter filter(m.motion, models::LinearGaussianLikelihood(m.observation), m.prior,
                mcmc_params(smc::McmcReference::All, 3000, 8));
  const Eigen::MatrixXd previous = filter.particles();
  filter.step(m.z);
  Eigen::VectorXd log_w(previous.rows());
  Eigen::MatrixXd means(previous.rows(), 4);
  std::vector<models::GaussianDensity> parts;
  for (Eigen::Index i = 0; i < previous.rows(); ++i) {
    const models::KalmanInnovation innovation({m.motion.F() * previous.row(i).transpose(), m.motion.Q()},
                                              m.observation);
    log_w[i] = innovation.log_likelihood(m.z);
    parts.push_back(innovation.posterior(m.z));
  }
  const Eigen::VectorXd w = (log_w.array() - log_w.maxCoeff()).exp();
  const double total = w.sum();
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(4);
  for (std::size_t i = 0; i < parts.size(); ++i) mean += w[i] / total * parts[i].mean;
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(4, 4);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const Eigen::VectorXd d = parts[i].mean - mean;
    cov += w[i] / total * (parts[i].cov + d * d.transpose());
  }
  expect_samples_follow(filter.particles(), mean, cov, "all");
}

TEST(SmcMcmcFilter, MapEstimateIsTheMostLikelyKeptSample) {
  const Model m;
  Filter filter(m.motion, models::LinearGaussianLikelihood(m.observation), m.prior,
                mcmc_params(smc::McmcReference::Map, 500, 9));
  filter.step(m.z);
  Eigen::Index best;
  filter.log_target().maxCoeff(&best);
  EXPECT_EQ(filter.map_estimate(), filter.particles().row(best).transpose());
  EXPECT_EQ(filter.mean(), Eigen::VectorXd(filter.particles().colwise().mean()));
}

TEST(SmcMcmcFilter, RefusesAllWithSingularNoiseAndNanMeasurements) {
  const Model m;
  const models::ConstantVelocity discrete({2, 1.0, 0.5, models::AccelerationNoise::Discrete});
  const models::LinearGaussianLikelihood obs(m.observation);
  EXPECT_THROW(Filter(discrete, obs, m.prior, mcmc_params(smc::McmcReference::All, 10, 1)),
               InvalidArgument);
  // The x* variants run on the noise and accept it.
  Filter ok(discrete, obs, m.prior, mcmc_params(smc::McmcReference::Mean, 10, 1));
  EXPECT_TRUE(ok.step(m.z).allFinite());
  EXPECT_THROW(ok.step(Eigen::Vector2d(std::nan(""), 0.0)), InvalidArgument);
  smc::McmcParams bad = mcmc_params(smc::McmcReference::Mean, 10, 1);
  bad.thinning = 0;
  EXPECT_THROW(Filter(m.motion, obs, m.prior, bad), InvalidArgument);
  EXPECT_THROW(smc::parse_mcmc_reference("best"), InvalidArgument);
}

TEST(SmcMcmcFilter, SameSeedSameSamples) {
  const Model m;
  const models::LinearGaussianLikelihood obs(m.observation);
  Filter a(m.motion, obs, m.prior, mcmc_params(smc::McmcReference::Random, 200, 3));
  Filter b(m.motion, obs, m.prior, mcmc_params(smc::McmcReference::Random, 200, 3));
  a.step(m.z);
  b.step(m.z);
  EXPECT_EQ(a.particles(), b.particles());
}
