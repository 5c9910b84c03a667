// smc::Sir against the Kalman filter (the exact posterior of a linear-Gaussian model) and against
// the definitions of selective resampling, determinism and the failure conventions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/models/linear_gaussian.hpp"
#include "vtrack/models/linear_gaussian_likelihood.hpp"
#include "vtrack/models/motion.hpp"
#include "vtrack/smc/sir.hpp"

using namespace vtrack;
using models::StatesView;

namespace {

using vtrack::core::kInf;

// A 2-D constant-velocity target seen in position with noise R = 4 I.
struct Scenario {
  models::ConstantVelocity motion{{2, 1.0, 0.5, models::AccelerationNoise::Continuous}};
  models::LinearGaussianObservation observation =
      models::LinearGaussianObservation::position_of_constant_velocity(2, 4.0 * Eigen::Matrix2d::Identity());
  Eigen::Vector4d m0{0.0, 1.0, 0.0, -0.5};
  Eigen::Matrix4d P0 = Eigen::Vector4d(10.0, 1.0, 10.0, 1.0).asDiagonal();
  std::vector<Eigen::VectorXd> z;

  explicit Scenario(std::uint64_t seed, int steps = 10) {
    core::Rng rng(seed);
    Eigen::VectorXd x = core::Gaussian(m0, P0).sample(rng);
    const core::Gaussian noise(Eigen::Vector2d::Zero(), observation.R);
    for (int k = 0; k < steps; ++k) {
      Eigen::VectorXd e(4);
      rng.fill_normal(e.data(), 4);
      x = motion.F() * x + motion.noise_factor() * e;
      z.push_back(observation.H * x + noise.sample(rng));
    }
  }
  core::Gaussian prior() const { return core::Gaussian(m0, P0); }
};

struct KalmanStep {
  models::GaussianDensity posterior;
  double log_likelihood;  // log p(z_k | z_1:k-1)
};

std::vector<KalmanStep> kalman(const Scenario& s) {
  const models::LinearGaussianMotion motion{s.motion.F(), s.motion.Q()};
  models::GaussianDensity d{s.m0, s.P0};
  std::vector<KalmanStep> out;
  for (const auto& z : s.z) {
    const models::KalmanInnovation innovation(models::kalman_predict(d, motion), s.observation);
    d = innovation.posterior(z);
    out.push_back({d, innovation.log_likelihood(z)});
  }
  return out;
}

// Over `runs` seeded runs on the same measurements, the mean of the SIR estimates is within 5
// standard errors (the runs' own spread / sqrt(runs)) of the Kalman mean at every step, the spread
// itself is at most 10 sqrt(P_ii / N_eff), N_eff the smallest mean ESS so far (resampling noise
// accumulates after a degenerate update: measured up to 6), the particles' covariance averages
// to P within 15% (a finite resampled cloud underestimates it after a degenerate update: measured
// up to 12% at N = 4000), and the log evidence averages to the Kalman marginal likelihood within
// 4 standard errors.
template <class MakeFilter>
void expect_matches_kalman(MakeFilter make_filter, const std::vector<Eigen::VectorXd>& zs,
                           const std::vector<KalmanStep>& exact, int runs, const std::string& what) {
  const std::size_t steps = zs.size();
  const Eigen::Index d = exact[0].posterior.mean.size();
  std::vector<Eigen::MatrixXd> means(steps, Eigen::MatrixXd(runs, d));
  std::vector<Eigen::MatrixXd> covs(steps, Eigen::MatrixXd::Zero(d, d));
  Eigen::VectorXd evidence(runs);
  Eigen::VectorXd ess = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(steps));
  for (int r = 0; r < runs; ++r) {
    auto filter = make_filter(static_cast<std::uint64_t>(1000 + r));
    for (std::size_t k = 0; k < steps; ++k) {
      means[k].row(r) = filter.step(zs[k]).transpose();
      ess[static_cast<Eigen::Index>(k)] += filter.ess() / runs;
      covs[k] += filter.particles().covariance() / runs;
    }
    evidence[r] = filter.log_evidence();
  }
  double n_eff = ess[0];
  for (std::size_t k = 0; k < steps; ++k) {
    n_eff = std::min(n_eff, ess[static_cast<Eigen::Index>(k)]);
    const auto& P = exact[k].posterior.cov;
    for (Eigen::Index i = 0; i < d; ++i) {
      const Eigen::VectorXd c = means[k].col(i);
      const double sd = std::sqrt((c.array() - c.mean()).square().sum() / (runs - 1));
      EXPECT_NEAR(c.mean(), exact[k].posterior.mean[i], 5 * sd / std::sqrt(runs) + 1e-9)
          << what << " step " << k << " component " << i;
      EXPECT_LT(sd, 10 * std::sqrt(P(i, i) / n_eff)) << what << " step " << k << " component " << i;
      EXPECT_NEAR(covs[k](i, i), P(i, i), 0.15 * P(i, i)) << what << " step " << k;
    }
  }
  double total = 0;
  for (const auto& e : exact) total += e.log_likelihood;
  const double sd = std::sqrt((evidence.array() - evidence.mean()).square().sum() / (runs - 1));
  EXPECT_NEAR(evidence.mean(), total, 4 * sd / std::sqrt(runs)) << what << " log evidence";
  EXPECT_LT(sd, 0.5) << what;
}

using CvSir = smc::Sir<models::ConstantVelocity, models::LinearGaussianLikelihood>;

smc::SirParams params(int n, std::uint64_t seed, double ess_threshold = 1.0, int moves = 0) {
  smc::SirParams p;
  p.n_particles = n;
  p.seed = seed;
  p.ess_threshold = ess_threshold;
  p.resample_move_steps = moves;
  return p;
}

// p(z | x) = 1 when x_0 >= z_0, else 0.
struct HalfPlane {
  int min_state_dim() const { return 1; }
  void check(const Eigen::VectorXd& z) const {
    if (z.size() != 1) throw InvalidArgument("z must have one value");
  }
  void log_likelihood(const StatesView<double>& x, const Eigen::VectorXd& z, double* out) const {
    for (Eigen::Index i = 0; i < x.rows(); ++i) out[i] = x(i, 0) >= z[0] ? 0.0 : -kInf;
  }
};

// log N(rows of r; 0, L L^T) for a lower Cholesky factor L.
Eigen::VectorXd log_normal_rows(Eigen::MatrixXd r, const Eigen::MatrixXd& L) {
  L.transpose().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(r);
  return (-0.5 * r.cols() * core::kLog2Pi - L.diagonal().array().log().sum() -
          0.5 * r.rowwise().squaredNorm().array()).matrix();
}

// The optimal proposal of a linear-Gaussian model, p(x_k | x_k-1, z_k) = N(m, Sigma) with
// Sigma = (Q^-1 + H^T R^-1 H)^-1, m = Sigma (Q^-1 F x_k-1 + H^T R^-1 z) (Doucet et al. 2000).
struct OptimalProposal {
  Eigen::MatrixXd F, H, Rinv, Sigma, L_sigma, L_q, gain_prev, gain_z;
  OptimalProposal(const Scenario& s) : F(s.motion.F()), H(s.observation.H) {
    const Eigen::MatrixXd Qinv = s.motion.Q().inverse();
    Rinv = s.observation.R.inverse();
    Sigma = (Qinv + H.transpose() * Rinv * H).inverse();
    L_sigma = Sigma.llt().matrixL();
    L_q = s.motion.Q().llt().matrixL();
    gain_prev = Sigma * Qinv * F;
    gain_z = Sigma * H.transpose() * Rinv;
  }
  int noise_dim() const { return static_cast<int>(F.rows()); }
  Eigen::MatrixXd mean(const StatesView<double>& prev, const Eigen::VectorXd& z) const {
    Eigen::MatrixXd m = prev * gain_prev.transpose();
    m.rowwise() += (gain_z * z).transpose();
    return m;
  }
  void propagate(const StatesView<double>& prev, const StatesView<double>& eps,
                 const Eigen::VectorXd& z, models::MutableStatesView<double> next) const {
    next = mean(prev, z) + eps * L_sigma.transpose();
  }
  void log_weight(const StatesView<double>& prev, const StatesView<double>& next,
                  const Eigen::VectorXd& z, double* out) const {
    const Eigen::MatrixXd x = next;
    Eigen::Map<Eigen::VectorXd>(out, x.rows()) =
        log_normal_rows(x - prev * F.transpose(), L_q) - log_normal_rows(x - mean(prev, z), L_sigma);
  }
};

}  // namespace

TEST(SmcSir, MatchesTheKalmanFilterOnALinearGaussianModel) {
  for (std::uint64_t data = 1; data <= 2; ++data) {
    const Scenario s(data);
    expect_matches_kalman(
        [&](std::uint64_t seed) {
          return CvSir(s.motion, models::LinearGaussianLikelihood(s.observation), s.prior(),
                       params(5000, seed));
        },
        s.z, kalman(s), 30, "data " + std::to_string(data));
  }
}

TEST(SmcSir, SelectiveResamplingMatchesTheKalmanFilterToo) {
  const Scenario s(11);
  expect_matches_kalman(
      [&](std::uint64_t seed) {
        return CvSir(s.motion, models::LinearGaussianLikelihood(s.observation), s.prior(),
                     params(5000, seed, 0.3));
      },
      s.z, kalman(s), 30, "ess_threshold 0.3");
}

TEST(SmcSir, ResamplesExactlyWhenTheEffectiveSampleSizeIsAtMostTheThreshold) {
  const Scenario s(12, 30);
  for (const double threshold : {0.0, 0.3, 0.5, 1.0}) {
    CvSir filter(s.motion, models::LinearGaussianLikelihood(s.observation), s.prior(),
                 params(2000, 12, threshold));
    int resampled = 0;
    for (const auto& z : s.z) {
      filter.step(z);
      EXPECT_EQ(filter.resampled(), filter.ess() <= threshold * 2000) << threshold;
      resampled += filter.resampled();
      if (filter.resampled()) {
        EXPECT_EQ(filter.particles().ess(), 2000.0);
      }
    }
    if (threshold == 0.0) {
      EXPECT_EQ(resampled, 0);
    }
    if (threshold == 1.0) {
      EXPECT_EQ(resampled, 30);
    }
    // The intermediate thresholds see both cases, or the test would not test them.
    if (threshold == 0.3 || threshold == 0.5) {
      EXPECT_GT(resampled, 0) << threshold;
      EXPECT_LT(resampled, 30) << threshold;
    }
  }
}

TEST(SmcSir, ZeroWeightParticlesNeverSurviveResampling) {
  models::RandomWalkParams rw;
  rw.dims = 1;
  for (const auto scheme : {core::ResamplingScheme::Multinomial, core::ResamplingScheme::Stratified,
                            core::ResamplingScheme::Systematic, core::ResamplingScheme::Residual}) {
    smc::SirParams p = params(3000, 4);
    p.resampling = scheme;
    smc::Sir<models::RandomWalk, HalfPlane> filter(
        models::RandomWalk(rw), HalfPlane{}, core::Gaussian(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Identity(1, 1)), p);
    filter.step(Eigen::VectorXd::Constant(1, 0.5));
    ASSERT_TRUE(filter.resampled());
    EXPECT_GE(filter.particles().states().col(0).minCoeff(), 0.5) << core::to_string(scheme);
  }
}

TEST(SmcSir, AllLikelihoodsZeroSkipsTheUpdateWithoutNan) {
  models::RandomWalkParams rw;
  rw.dims = 1;
  smc::Sir<models::RandomWalk, HalfPlane> filter(
      models::RandomWalk(rw), HalfPlane{},
      core::Gaussian(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Identity(1, 1)), params(500, 5, 0.5));
  const Eigen::VectorXd mean = filter.step(Eigen::VectorXd::Constant(1, 1e9));  // nothing there
  EXPECT_EQ(filter.last_log_normaliser(), -kInf);
  EXPECT_EQ(filter.log_evidence(), -kInf);
  EXPECT_TRUE(mean.allFinite());
  EXPECT_NEAR(filter.particles().weights().minCoeff(), 1.0 / 500, 1e-15);  // the previous ones
  // The filter carries on.
  filter.step(Eigen::VectorXd::Constant(1, -1e9));
  EXPECT_TRUE(filter.mean().allFinite());
  EXPECT_EQ(filter.log_evidence(), -kInf);
}

TEST(SmcSir, NanMeasurementIsAnErrorAndLeavesTheFilterUnchanged) {
  const Scenario s(6);
  CvSir filter(s.motion, models::LinearGaussianLikelihood(s.observation), s.prior(), params(1000, 6));
  filter.step(s.z[0]);
  const Eigen::MatrixXd before = filter.particles().states();
  const Eigen::VectorXd nan = (Eigen::VectorXd(2) << 1.0, std::nan("")).finished();
  EXPECT_THROW(filter.step(nan), InvalidArgument);
  EXPECT_THROW(filter.step(Eigen::VectorXd::Ones(3)), InvalidArgument);
  EXPECT_EQ(filter.particles().states(), before);
  EXPECT_EQ(filter.steps(), 1);
}

TEST(SmcSir, RejectsBadParameters) {
  const Scenario s(7);
  const models::LinearGaussianLikelihood obs(s.observation);
  EXPECT_THROW(CvSir(s.motion, obs, s.prior(), params(0, 1)), InvalidArgument);
  EXPECT_THROW(CvSir(s.motion, obs, s.prior(), params(10, 1, 1.5)), InvalidArgument);
  EXPECT_THROW(CvSir(s.motion, obs, s.prior(), params(10, 1, 1.0, -1)), InvalidArgument);
  EXPECT_THROW(CvSir(s.motion, obs, core::Gaussian(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity()),
                     params(10, 1)),
               InvalidArgument);
  EXPECT_THROW(CvSir(s.motion, obs, Eigen::MatrixXd::Constant(5, 4, std::nan("")), params(10, 1)),
               InvalidArgument);
}

// Same seed, same particles, for any thread count (the per-block streams and reductions).
template <class Filter>
void expect_same_for_any_thread_count(const Scenario& s, const char* what) {
  const models::LinearGaussianLikelihood obs(s.observation);
  for (const int moves : {0, 1}) {
    smc::SirParams p = params(10000, 8, 0.6, moves);
    std::vector<std::decay_t<decltype(Filter(s.motion, obs, s.prior(), p).particles().states())>>
        finals;
    std::vector<double> evidences;
    for (const int threads : {1, 2, 0, 1}) {
      p.threads = threads;
      Filter filter(s.motion, obs, s.prior(), p);
      for (const auto& z : s.z) filter.step(z);
      finals.push_back(filter.particles().states());
      evidences.push_back(filter.log_evidence());
    }
    for (std::size_t i = 1; i < finals.size(); ++i) {
      EXPECT_EQ(finals[i], finals[0]) << what << ", moves " << moves << " run " << i;
      EXPECT_EQ(evidences[i], evidences[0]) << what;
    }
    p.seed = 9;
    Filter other(s.motion, obs, s.prior(), p);
    for (const auto& z : s.z) other.step(z);
    EXPECT_NE(other.particles().states(), finals[0]) << what;
  }
}

using FloatCvSir = smc::Sir<models::ConstantVelocity, models::LinearGaussianLikelihood,
                            smc::Bootstrap, float>;

TEST(SmcSir, SameSeedSameParticlesAndAnyThreadCountTheSame) {
  const Scenario s(8);
  expect_same_for_any_thread_count<CvSir>(s, "double states");
  expect_same_for_any_thread_count<FloatCvSir>(s, "float states");
}

using OptimalSir =
    smc::Sir<models::ConstantVelocity, models::LinearGaussianLikelihood, OptimalProposal>;

TEST(SmcSir, OptimalProposalMatchesKalmanWithLessWeightDegeneracy) {
  const Scenario s(13);
  const models::LinearGaussianLikelihood obs(s.observation);
  expect_matches_kalman(
      [&](std::uint64_t seed) {
        return OptimalSir(s.motion, obs, s.prior(), params(5000, seed), OptimalProposal(s));
      },
      s.z, kalman(s), 30, "optimal proposal");
  OptimalSir optimal(s.motion, obs, s.prior(), params(5000, 13), OptimalProposal(s));
  CvSir bootstrap(s.motion, obs, s.prior(), params(5000, 13));
  // The optimal proposal's weights p(z_k | x_k-1) vary less than the bootstrap's p(z_k | x_k)
  // (Doucet et al. 2000, Prop. 2): a larger effective sample size on average over the steps.
  double ess_optimal = 0, ess_bootstrap = 0;
  for (const auto& z : s.z) {
    optimal.step(z);
    bootstrap.step(z);
    ess_optimal += optimal.ess();
    ess_bootstrap += bootstrap.ess();
  }
  EXPECT_GT(ess_optimal, ess_bootstrap);
}

TEST(SmcSir, ResampleMoveKeepsThePosterior) {
  const Scenario s(14);
  expect_matches_kalman(
      [&](std::uint64_t seed) {
        return CvSir(s.motion, models::LinearGaussianLikelihood(s.observation), s.prior(),
                     params(5000, seed, 1.0, 2));
      },
      s.z, kalman(s), 30, "resample-move");
  CvSir filter(s.motion, models::LinearGaussianLikelihood(s.observation), s.prior(),
               params(5000, 14, 1.0, 2));
  for (const auto& z : s.z) filter.step(z);
  EXPECT_GT(filter.acceptance_rate(), 0.05);
  EXPECT_LT(filter.acceptance_rate(), 0.95);
}

TEST(SmcSir, FloatStatesMatchTheKalmanFilterWithAndWithoutMoves) {
  for (const int moves : {0, 1}) {
    const Scenario s(15 + static_cast<std::uint64_t>(moves));
    expect_matches_kalman(
        [&](std::uint64_t seed) {
          return FloatCvSir(s.motion, models::LinearGaussianLikelihood(s.observation), s.prior(),
                            params(5000, seed, 0.6, moves));
        },
        s.z, kalman(s), 30, "float states, moves " + std::to_string(moves));
  }
}

// Float and double filters draw the same random numbers: the prior sample and the first update
// agree to float round-off (the states are ~10, float's relative precision 6e-8); resampling then
// takes the same ancestors except where a float-rounded weight moves a particle across a point.
TEST(SmcSir, FloatStatesDrawTheSameParticlesAsDouble) {
  const Scenario s(17);
  const models::LinearGaussianLikelihood obs(s.observation);
  for (const int threads : {1, 2}) {
    smc::SirParams p = params(4000, 17);
    p.threads = threads;
    CvSir twin(s.motion, obs, s.prior(), p);
    FloatCvSir filter(s.motion, obs, s.prior(), p);
    EXPECT_LT((filter.particles().states().cast<double>() - twin.particles().states())
                  .cwiseAbs().maxCoeff(), 1e-5);
    const Eigen::VectorXd expected = twin.step(s.z[0]);
    EXPECT_LT((filter.step(s.z[0]) - expected).cwiseAbs().maxCoeff(), 1e-5);
    EXPECT_NEAR(filter.log_evidence(), twin.log_evidence(), 1e-5);
    const Eigen::MatrixXd a = filter.particles().states().cast<double>();
    const Eigen::MatrixXd& b = twin.particles().states();
    Eigen::Index same = 0;
    for (Eigen::Index i = 0; i < a.rows(); ++i) same += (a.row(i) - b.row(i)).cwiseAbs().maxCoeff() < 1e-4;
    EXPECT_GT(same, a.rows() * 99 / 100) << "threads " << threads;
  }
}

TEST(SmcSir, ResampleMoveWorksWithSingularProcessNoise) {
  // The second-order auto-regressive model's copied half has no noise: a state-space random walk
  // could never be accepted there; the moves on eps can. Kalman handles the singular Q.
  models::SecondOrderAutoRegressiveParams ar;
  ar.sigma = {0.5};
  ar.dims = 2;
  const models::SecondOrderAutoRegressive motion(ar);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, 4);
  H(0, 0) = H(1, 1) = 1.0;
  const models::LinearGaussianObservation observation{H, Eigen::Matrix2d::Identity()};
  const Eigen::Vector4d m0(0.0, 0.0, -1.0, 0.5);
  const Eigen::Matrix4d P0 = Eigen::Matrix4d::Identity();
  core::Rng rng(15);
  std::vector<Eigen::VectorXd> zs;
  Eigen::VectorXd x = m0;
  for (int k = 0; k < 8; ++k) {
    Eigen::VectorXd e(2);
    rng.fill_normal(e.data(), 2);
    x = motion.F() * x + motion.noise_factor() * e;
    Eigen::Vector2d w;
    rng.fill_normal(w.data(), 2);
    zs.push_back(H * x + w);
  }
  using ArSir = smc::Sir<models::SecondOrderAutoRegressive, models::LinearGaussianLikelihood>;
  std::vector<KalmanStep> exact;
  models::GaussianDensity d{m0, P0};
  const models::LinearGaussianMotion kalman_motion{motion.F(), motion.Q()};
  for (const auto& z : zs) {
    const models::KalmanInnovation innovation(models::kalman_predict(d, kalman_motion), observation);
    d = innovation.posterior(z);
    exact.push_back({d, innovation.log_likelihood(z)});
  }
  expect_matches_kalman(
      [&](std::uint64_t seed) {
        return ArSir(motion, models::LinearGaussianLikelihood(observation), core::Gaussian(m0, P0),
                     params(5000, seed, 1.0, 2));
      },
      zs, exact, 30, "AR2 resample-move");
  ArSir filter(motion, models::LinearGaussianLikelihood(observation), core::Gaussian(m0, P0),
               params(5000, 15, 1.0, 2));
  for (const auto& z : zs) filter.step(z);
  EXPECT_GT(filter.acceptance_rate(), 0.05);
}

TEST(SmcSir, PredictPropagatesLikeTheKalmanPrediction) {
  const Scenario s(16);
  CvSir filter(s.motion, models::LinearGaussianLikelihood(s.observation), s.prior(), params(40000, 16));
  const models::GaussianDensity predicted =
      models::kalman_predict({s.m0, s.P0}, models::LinearGaussianMotion{s.motion.F(), s.motion.Q()});
  const Eigen::VectorXd mean = filter.predict();
  // i.i.d. prior samples propagated: standard error sqrt(P_ii / N).
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(mean[i], predicted.mean[i], 5 * std::sqrt(predicted.cov(i, i) / 40000));
    EXPECT_NEAR(filter.particles().covariance()(i, i), predicted.cov(i, i),
                5 * predicted.cov(i, i) * std::sqrt(2.0 / 40000));
  }
  EXPECT_FALSE(filter.resampled());
  EXPECT_EQ(filter.log_evidence(), 0.0);
}
