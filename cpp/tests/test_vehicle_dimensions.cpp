#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Dense>

#include "road_scene.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/filters/vehicle_dimensions.hpp"

using namespace vtrack;
using filters::VehicleEstimatorParams;
using filters::VehiclePosterior;
using filters::VehicleSampler;
using models::Camera;
using models::VehicleObservation;

namespace {

Camera mast_camera() { return Camera(road_scene::look({-3.0, 0.0, 8.0}, 12.0, 12.0)); }

Eigen::Matrix<double, 3, 8> corners_at(const Camera& cam, double lateral, double along, double W, double H,
                                       double L) {
  const Eigen::Vector3d origin = lateral * cam.lateral_axis() + along * cam.road_axis();
  return road_scene::cuboid(origin, cam.lateral_axis(), cam.road_axis(), W, H, L);
}

// The exact silhouette without distortion: the convex hull of the projected corners (OpenCV).
Eigen::Matrix2Xd silhouette(const Camera& cam, const Eigen::Matrix<double, 3, 8>& corners) {
  const Eigen::Matrix2Xd px = road_scene::opencv_project(cam.calibration(), corners);
  std::vector<cv::Point2f> pts, hull;
  for (int i = 0; i < 8; ++i) pts.emplace_back(static_cast<float>(px(0, i)), static_cast<float>(px(1, i)));
  cv::convexHull(pts, hull);
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(hull.size()));
  for (std::size_t i = 0; i < hull.size(); ++i) out.col(static_cast<Eigen::Index>(i)) << hull[i].x, hull[i].y;
  return out;
}

VehicleObservation view(const Camera& cam, double lateral, double along, double W, double H, double L) {
  return models::observe_silhouette(cam, silhouette(cam, corners_at(cam, lateral, along, W, H, L)));
}

// A one-class prior N(x; m, diag(s^2)) with no minimum size in the way.
models::VehicleModelPrior one_class(const Eigen::Vector3d& m, const Eigen::Vector3d& s) {
  models::VehiclePriorParams p;
  p.models = {{"only", m, s, 1.0, false}};
  p.min_size = Eigen::Vector3d::Zero();
  return models::VehicleModelPrior(p);
}

VehicleEstimatorParams chain_params(VehicleSampler sampler, int samples) {
  VehicleEstimatorParams p;
  p.sampler = sampler;
  p.n_particles = samples;
  p.burn_in = 2000;
  p.thinning = 4;
  p.min_size = {0.0, 0.0, 0.0};
  return p;
}

// The Gaussian N(mu, Sigma) proportional to N(x; m, diag s^2) prod_k exp(-1/2 (x - a_k)^T M_k (x - a_k)),
// M_k = P_k S^-1 P_k (each ray's likelihood written directly as the residual of the orthogonal
// projection), in information form. With `widen`, view k's S is sigma^2 widen[k]^2 I.
std::pair<Eigen::Vector3d, Eigen::Matrix3d> gaussian_posterior(const std::vector<VehicleObservation>& views,
                                                               const Eigen::Vector3d& m, const Eigen::Vector3d& s,
                                                               double sigma, const std::vector<double>& widen = {}) {
  Eigen::Matrix3d info = s.cwiseAbs2().cwiseInverse().asDiagonal();
  Eigen::Vector3d vec = info * m;
  for (std::size_t k = 0; k < views.size(); ++k) {
    const auto& obs = views[k];
    const double sigma_k = sigma * (widen.empty() ? 1.0 : widen[k]);
    const Eigen::Vector3d d = (obs.b - obs.a).normalized();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
    const Eigen::Matrix3d M = P * P / (sigma_k * sigma_k);
    info += M;
    vec += M * obs.a;
  }
  const Eigen::Matrix3d cov = info.inverse();
  return {cov * vec, cov};
}

Eigen::Matrix3d sample_covariance(const Eigen::MatrixXd& x) {
  const Eigen::MatrixXd c = x.rowwise() - x.colwise().mean();
  return c.transpose() * c / static_cast<double>(x.rows() - 1);
}

}  // namespace

// "mh" at a vehicle's first frame samples p(z | x) p(x | M); with one Gaussian class and the
// Gaussian ray likelihood that posterior is Gaussian in closed form.
TEST(VehicleSamplers, MhMatchesTheClosedFormPosteriorOfOneFrame) {
  const Camera cam = mast_camera();
  const VehicleObservation obs = view(cam, 0.9, 22.0, 1.8, 1.5, 4.5);
  const Eigen::Vector3d m(1.7, 1.6, 4.2), s(0.2, 0.2, 0.5);
  const auto prior = one_class(m, s);
  auto p = chain_params(VehicleSampler::Mh, 20000);
  core::Rng rng(3);
  const VehiclePosterior post = filters::sample_vehicle_frame(obs, prior, nullptr, {}, p, rng);
  const auto [mu, cov] = gaussian_posterior({obs}, m, s, p.likelihood.sigma_w);
  // Monte Carlo error of the mean: ~sqrt(var / N_eff), N_eff a few thousand (autocorrelated).
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(post.mean(k), mu(k), 4.0 * std::sqrt(cov(k, k) / 2000.0)) << "dimension " << k;
  }
  const Eigen::Matrix3d c = sample_covariance(post.samples);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c(k, k) / cov(k, k), 1.0, 0.15) << "variance " << k;
  EXPECT_GT(post.acceptance_rate, 0.05);
}

// "rays" after three frames samples p(x | M) prod_k p(z_k | x): Gaussian again.
TEST(VehicleSamplers, RaysMatchesTheClosedFormPosteriorOfAllFrames) {
  const Camera cam = mast_camera();
  std::vector<VehicleObservation> views;
  filters::RaySums sums;
  auto p = chain_params(VehicleSampler::Rays, 20000);
  p.proposal_scale = 0.05;  // the product of three rays is narrow
  for (double along : {18.0, 24.0, 30.0}) {
    views.push_back(view(cam, 4.3, along, 2.5, 3.8, 12.0));
    sums.add(views.back(), p.likelihood);
  }
  const Eigen::Vector3d m(2.0, 2.5, 7.0), s(0.2, 0.3, 1.0);
  const auto prior = one_class(m, s);
  core::Rng rng(5);
  const VehiclePosterior post = filters::sample_vehicle_frame(views.back(), prior, nullptr, sums, p, rng);
  const auto [mu, cov] = gaussian_posterior(views, m, s, p.likelihood.sigma_w);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(post.mean(k), mu(k), 4.0 * std::sqrt(cov(k, k) / 1000.0)) << "dimension " << k;
  }
  const Eigen::Matrix3d c = sample_covariance(post.samples);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c(k, k) / cov(k, k), 1.0, 0.2) << "variance " << k;
  // The sums are the product of the rays: log-likelihoods differ from the direct ones by a constant.
  core::Rng r(1);
  Eigen::Matrix3Xd x(3, 5);
  for (Eigen::Index j = 0; j < x.size(); ++j) x.data()[j] = r.uniform(0.5, 12.0);
  Eigen::VectorXd direct = Eigen::VectorXd::Zero(5);
  for (const auto& o : views) direct += models::ray_log_likelihood(o, x, p.likelihood);
  for (int j = 1; j < 5; ++j) {
    EXPECT_NEAR(sums.log_likelihood(x.col(j)) - sums.log_likelihood(x.col(0)), direct(j) - direct(0), 1e-8);
  }
  // With the constant c the sums give -2 log p(z | x) itself, and one view's term the squared
  // distance from x to its ray (models::ray_distance, the Plücker projection) in units of S's sigma
  // (the outlier refit's measure).
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(sums.squared_distance(x.col(j)), -2.0 * direct(j), 1e-6 * (1.0 - direct(j)));
  filters::RaySums one;
  one.add(views.front(), p.likelihood);
  const Eigen::VectorXd d = models::ray_distance(views.front(), x) / p.likelihood.sigma_w;
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(one.squared_distance(x.col(j)), d(j) * d(j), 1e-6 * (1.0 + d(j) * d(j)));
}

// The samplers with a previous posterior against a brute-force grid of the target: for "ray" the
// 1-D density on the ray's feasible segment, p(x(h) | x*) p(x(h) | M) (Table 1); for "mh" with
// reference "all" the 3-D density p(z | x) sum_i p(x | x_i) p(x | M).
TEST(VehicleSamplers, RayAndFullMhMatchBruteForceGrids) {
  const Camera cam = mast_camera();
  const models::VehicleModelPrior prior;  // Table 1
  const VehicleObservation obs = view(cam, 0.9, 22.0, 1.8, 1.5, 4.5);
  VehiclePosterior previous;
  previous.samples.resize(3, 3);
  previous.samples << 1.6, 1.3, 3.9, 1.95, 1.75, 4.9, 1.7, 1.5, 4.4;
  previous.mean = previous.samples.colwise().mean().transpose();
  previous.map = previous.samples.row(1).transpose();
  previous.log_target = Eigen::Vector3d(0.0, 1.0, 0.0);

  // "ray", x* = the previous map sample.
  auto p = chain_params(VehicleSampler::Ray, 20000);
  p.min_size = {0.4, 0.6, 1.0};
  core::Rng rng(7);
  const VehiclePosterior ray = filters::sample_vehicle_frame(obs, prior, &previous, {}, p, rng);
  const auto heights = obs.feasible_heights(Eigen::Vector3d(0.4, 0.6, 1.0));
  const int n = 20001;
  Eigen::Matrix3Xd pts(3, n);
  for (int i = 0; i < n; ++i) {
    pts.col(i) = obs.point_at_height(heights.first + (heights.second - heights.first) * i / (n - 1.0));
  }
  const double sd2 = p.dynamic_sigma * p.dynamic_sigma;
  Eigen::ArrayXd logw = prior.log_density(pts).array() -
                        0.5 * (pts.colwise() - previous.map).colwise().squaredNorm().transpose().array() / sd2;
  Eigen::ArrayXd w = (logw - logw.maxCoeff()).exp();
  const Eigen::Vector3d grid_mean = pts * w.matrix() / w.sum();
  EXPECT_LT((ray.mean - grid_mean).norm(), 0.03) << ray.mean.transpose() << " vs " << grid_mean.transpose();
  for (Eigen::Index i = 0; i < ray.samples.rows(); ++i) {  // every sample on the ray
    ASSERT_LT(models::ray_distance(obs, ray.samples.row(i).transpose())(0), 1e-9);
  }

  // "mh", reference "all": a 3-D grid around the ray's region.
  p.sampler = VehicleSampler::Mh;
  p.reference = smc::McmcReference::All;
  p.proposal_scale = 0.1;
  p.dynamic_sigma = 0.15;  // tight, so that the sum over the previous samples matters
  const VehiclePosterior full = filters::sample_vehicle_frame(obs, prior, &previous, {}, p, rng);
  const int g = 61;
  Eigen::Matrix3Xd grid(3, g * g * g);
  const Eigen::Vector3d lo(1.0, 0.6, 2.5), hi(2.6, 2.6, 6.5);
  for (int i = 0, c = 0; i < g; ++i)
    for (int j = 0; j < g; ++j)
      for (int k = 0; k < g; ++k, ++c)
        grid.col(c) = lo + (hi - lo).cwiseProduct(Eigen::Vector3d(i, j, k) / (g - 1.0));
  Eigen::ArrayXd lg = prior.log_density(grid).array() + models::ray_log_likelihood(obs, grid, p.likelihood).array();
  const double sf2 = p.dynamic_sigma * p.dynamic_sigma;
  Eigen::ArrayXd dyn = Eigen::ArrayXd::Zero(grid.cols());
  for (int i = 0; i < 3; ++i) {
    dyn += (-0.5 * (grid.colwise() - previous.samples.row(i).transpose()).colwise().squaredNorm().transpose().array() /
            sf2).exp();
  }
  lg += dyn.log();
  const Eigen::ArrayXd wg = (lg - lg.maxCoeff()).exp();
  const Eigen::Vector3d grid3 = grid * wg.matrix() / wg.sum();
  EXPECT_LT((full.mean - grid3).norm(), 0.05) << full.mean.transpose() << " vs " << grid3.transpose();
}

// §3.3's discrete variant against brute force: every class mean projected with the Plücker
// matrix (models::project_onto_ray), clamped to the feasible segment, scored with the class's own
// density and the dynamic against y*.
TEST(VehicleSamplers, DiscreteIsTheBestScoredProjectionOfTheClassMeans) {
  const Camera cam = mast_camera();
  const models::VehicleModelPrior prior;
  VehicleEstimatorParams p;
  p.sampler = VehicleSampler::Discrete;
  VehiclePosterior previous;
  previous.samples = Eigen::RowVector3d(2.0, 2.6, 8.0);
  previous.mean = previous.map = previous.samples.row(0).transpose();
  previous.log_target = Eigen::VectorXd::Zero(1);
  for (const auto& v : std::vector<Eigen::Vector3d>{{1.8, 1.5, 4.5}, {2.5, 3.8, 12.0}, {0.8, 1.3, 2.1}}) {
    const VehicleObservation obs = view(cam, 0.9, 25.0, v(0), v(1), v(2));
    const auto heights = obs.feasible_heights(Eigen::Vector3d(0.4, 0.6, 1.0));
    for (const VehiclePosterior* prev : std::vector<const VehiclePosterior*>{nullptr, &previous}) {
      double best_score = -std::numeric_limits<double>::infinity();
      Eigen::Vector3d best = Eigen::Vector3d::Zero();
      for (int m = 0; m < prior.num_models(); ++m) {
        Eigen::Vector3d y = models::project_onto_ray(obs, prior.params().models[m].mean);
        const double h = std::clamp(y(1), heights.first, heights.second);  // H is the height on the ray
        y = obs.point_at_height(h);
        double score = prior.class_log_densities(y)(m, 0);
        if (prev) score -= 0.5 * (y - prev->mean).squaredNorm() / (p.dynamic_sigma * p.dynamic_sigma);
        if (score > best_score) best_score = score, best = y;
      }
      core::Rng rng(1);
      const VehiclePosterior post = filters::sample_vehicle_frame(obs, prior, prev, {}, p, rng);
      EXPECT_LT((post.mean - best).norm(), 1e-9);
      EXPECT_NEAR(post.class_probability.sum(), 1.0, 1e-12);
    }
  }
}

namespace {
// A vehicle driving along the road seen every `step` metres while its silhouette is inside the
// image; returns the number of frames given.
int drive(filters::VehicleDimensionEstimator& est, int id, double lateral, const Eigen::Vector3d& whl,
          double from, double to, double step = 1.5) {
  const Camera& cam = est.camera();
  int frame = 0;
  for (double along = from; along <= to; along += step) {
    est.update_polygon(id, ++frame, silhouette(cam, corners_at(cam, lateral, along, whl(0), whl(1), whl(2))));
  }
  return frame;
}
}  // namespace

TEST(VehicleDimensionEstimator, ClassifiesRenderedVehiclesLightAndHeavy) {
  struct Case {
    Eigen::Vector3d whl;
    double lateral;
    bool heavy;
  };
  const std::vector<Case> cases = {{{1.8, 1.5, 4.5}, 0.9, false}, {{2.5, 3.8, 12.0}, 4.3, true},
                                   {{1.75, 1.45, 4.0}, 8.0, false}, {{2.5, 3.2, 10.5}, 0.8, true}};
  for (VehicleSampler sampler : {VehicleSampler::Ray, VehicleSampler::Mh, VehicleSampler::Discrete,
                                 VehicleSampler::Rays}) {
    VehicleEstimatorParams p;
    p.sampler = sampler;
    filters::VehicleDimensionEstimator est(mast_camera(), {}, p);
    for (std::size_t i = 0; i < cases.size(); ++i) drive(est, static_cast<int>(i) + 1, cases[i].lateral, cases[i].whl, 16.0, 40.0);
    for (const auto& e : est.estimates()) {
      const Case& c = cases[static_cast<std::size_t>(e.vehicle_id - 1)];
      SCOPED_TRACE("sampler " + std::to_string(static_cast<int>(sampler)) + ", vehicle " + std::to_string(e.vehicle_id));
      ASSERT_TRUE(e.valid);
      EXPECT_EQ(e.heavy, c.heavy) << e.class_name << " " << e.dimensions.transpose();
      EXPECT_GT(e.frames_used, 5);
      // Exact silhouettes: the dimensions within the prior's pull of the truth.
      EXPECT_LT((e.dimensions - c.whl).cwiseAbs().maxCoeff(), c.heavy ? 2.5 : 0.8) << e.dimensions.transpose();
    }
  }
}

TEST(VehicleDimensionEstimator, HeavyByHeightWhenTheVolumeFallsShort) {
  // A truck seen only in part: its outline, cut short, gives a 2.4 x 3.4 x 5 m cuboid (41 m^3,
  // under heavy_volume's 45) -- rendered whole here as that cuboid. The "volume" rule calls it
  // light on the volume alone (heavy_height 0) and heavy by its height (the default 3.0 m); a car
  // stays light under both. Each answer against its own estimate's W H L, and the truth's.
  for (double height : {0.0, VehicleEstimatorParams{}.heavy_height}) {
    VehicleEstimatorParams p;
    p.heavy_height = height;
    filters::VehicleDimensionEstimator est(mast_camera(), {}, p);
    drive(est, 1, 4.3, {2.4, 3.4, 5.0}, 16.0, 40.0);
    drive(est, 2, 0.9, {1.8, 1.5, 4.5}, 16.0, 40.0);
    const auto tall = est.estimate(1), car = est.estimate(2);
    ASSERT_TRUE(tall.valid && car.valid);
    EXPECT_LT(tall.dimensions.prod(), p.heavy_volume) << tall.dimensions.transpose();
    EXPECT_GT(tall.dimensions.y(), 3.0) << tall.dimensions.transpose();
    EXPECT_EQ(tall.heavy, height > 0.0);
    EXPECT_FALSE(car.heavy);
  }
}

TEST(VehicleDimensionEstimator, NoWidthBeyondTheWidestVehicleCountsInTheVolume) {
  // Two cars abreast as one outline for their whole passage: a 3.6 x 2.1 x 7 m cuboid (53 m^3) --
  // rendered as that cuboid, under one broad model so that the answer follows the views. Its own
  // volume calls it heavy (max_vehicle_width 0); with the default (2.6 m, the widest road vehicle)
  // the volume counts 2.6 m of its width, 38 m^3: light. A real heavy, 2.5 x 3.0 x 9 m, is heavy
  // under both. Each answer against its own estimate's W H L.
  const std::vector<models::VehicleModel> broad{{"any", {2.5, 2.5, 7.0}, {1.0, 1.0, 3.0}, 1.0, false}};
  for (double widest : {0.0, VehicleEstimatorParams{}.max_vehicle_width}) {
    VehicleEstimatorParams p;
    p.max_vehicle_width = widest;
    p.heavy_height = 0.0;  // the volume alone
    filters::VehicleDimensionEstimator est(mast_camera(), broad, p);
    drive(est, 1, 1.0, {3.6, 2.1, 7.0}, 16.0, 40.0);
    drive(est, 2, 4.3, {2.5, 3.0, 9.0}, 16.0, 40.0);
    const auto abreast = est.estimate(1), heavy = est.estimate(2);
    ASSERT_TRUE(abreast.valid && heavy.valid);
    EXPECT_GT(abreast.dimensions.x(), 3.0) << abreast.dimensions.transpose();
    EXPECT_GT(abreast.dimensions.prod(), p.heavy_volume) << abreast.dimensions.transpose();
    EXPECT_LT(2.6 * abreast.dimensions.y() * abreast.dimensions.z(), p.heavy_volume) << abreast.dimensions.transpose();
    EXPECT_EQ(abreast.heavy, widest == 0.0);
    EXPECT_TRUE(heavy.heavy) << heavy.dimensions.transpose();
  }
}

TEST(VehicleDimensionEstimator, SameSeedSameResultWhateverTheOrderOfVehicles) {
  VehicleEstimatorParams p;
  p.seed = 11;
  filters::VehicleDimensionEstimator a(mast_camera(), {}, p), b(mast_camera(), {}, p);
  drive(a, 1, 0.9, {1.8, 1.5, 4.5}, 16.0, 30.0);
  drive(a, 2, 4.3, {2.5, 3.8, 12.0}, 16.0, 30.0);
  drive(b, 2, 4.3, {2.5, 3.8, 12.0}, 16.0, 30.0);
  drive(b, 1, 0.9, {1.8, 1.5, 4.5}, 16.0, 30.0);
  for (int id : {1, 2}) {
    EXPECT_EQ(a.posterior(id)->samples, b.posterior(id)->samples);
    EXPECT_EQ(a.estimate(id).dimensions, b.estimate(id).dimensions);
  }
  p.seed = 12;
  filters::VehicleDimensionEstimator c(mast_camera(), {}, p);
  drive(c, 1, 0.9, {1.8, 1.5, 4.5}, 16.0, 30.0);
  EXPECT_NE(a.posterior(1)->samples, c.posterior(1)->samples);
  // forget() (the video pipeline, streaming) releases one vehicle and leaves the others' answers
  // as they were: vehicle 2 done with and forgotten before vehicle 1 is estimated, as in b.
  const auto before = a.estimate(2).dimensions;
  a.forget(2);
  EXPECT_THROW(a.estimate(2), InvalidArgument);
  EXPECT_EQ(a.next_frame(2), 1);
  EXPECT_EQ(a.estimates().size(), 1u);
  EXPECT_EQ(a.estimate(1).dimensions, b.estimate(1).dimensions);
  EXPECT_EQ(before, b.estimate(2).dimensions);
}

TEST(VehicleDimensionEstimator, FramesUsedAndVehiclesNeverFullyInView) {
  filters::VehicleDimensionEstimator est(mast_camera());
  const Camera& cam = est.camera();
  // One frame: an estimate from one ray.
  EXPECT_TRUE(est.update_polygon(1, 7, silhouette(cam, corners_at(cam, 0.9, 22.0, 1.8, 1.5, 4.5))));
  auto e = est.estimate(1);
  EXPECT_TRUE(e.valid);
  EXPECT_EQ(e.frames_used, 1);
  EXPECT_EQ(e.first_frame, 7);
  EXPECT_EQ(e.last_frame, 7);
  // Cut by the image border: seen, not used, no guess.
  EXPECT_FALSE(est.update_box(2, 1, -0.5, 300.0, 120.0, 80.0));
  EXPECT_FALSE(est.update_box(2, 2, 1200.0, 300.0, 79.5, 80.0));
  e = est.estimate(2);
  EXPECT_FALSE(e.valid);
  EXPECT_EQ(e.frames_seen, 2);
  EXPECT_EQ(e.frames_used, 0);
  EXPECT_TRUE(e.class_name.empty());
  EXPECT_TRUE(std::isnan(e.dimensions(0)));
  // A degenerate (collinear) silhouette: no dimensions above min_size on its ray.
  Eigen::Matrix2Xd line(2, 3);
  line << 600.0, 610.0, 620.0, 400.0, 400.0, 400.0;
  EXPECT_FALSE(est.update_polygon(3, 1, line));
  EXPECT_FALSE(est.estimate(3).valid);
  // Refused silhouettes leave the estimator unchanged.
  Eigen::Matrix2Xd nan = line;
  nan(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(est.update_polygon(4, 1, nan), InvalidArgument);
  EXPECT_THROW(est.update_box(4, 1, 10.0, 10.0, 0.0, 5.0), InvalidArgument);
  Eigen::Matrix2Xd sky(2, 3);  // above the horizon of a camera pitched 12 degrees down
  sky << 600.0, 700.0, 650.0, 0.0, 0.0, 20.0;
  EXPECT_THROW(est.update_polygon(4, 1, sky), InvalidArgument);
  EXPECT_THROW(est.estimate(4), InvalidArgument);
  // Frames go forward.
  EXPECT_THROW(est.update_polygon(1, 6, silhouette(cam, corners_at(cam, 0.9, 23.0, 1.8, 1.5, 4.5))), InvalidArgument);
  EXPECT_EQ(est.estimates().size(), 3u);
}

namespace {
// A lorry of dimensions `whl` approaching the mast from 66 to 36 m, every 3 m: its exact
// silhouettes, their observations and the best resolution among them.
std::tuple<std::vector<Eigen::Matrix2Xd>, std::vector<VehicleObservation>, double> approaching_lorry(
    const Camera& cam, const Eigen::Vector3d& whl) {
  std::vector<Eigen::Matrix2Xd> approaching;
  std::vector<VehicleObservation> views;
  double best = std::numeric_limits<double>::infinity();
  for (double along = 66.0; along >= 36.0; along -= 3.0) {
    approaching.push_back(silhouette(cam, corners_at(cam, 4.3, along, whl(0), whl(1), whl(2))));
    views.push_back(models::observe_silhouette(cam, approaching.back()));
    best = std::min(best, views.back().edge_resolution(1));
  }
  return {approaching, views, best};
}
}  // namespace

// The resolution cut is per vehicle: with a fixed cut finer than any view of a vehicle seen only
// from afar, the cut alone leaves it no view (not fully in view); relaxed to a factor of its best
// view, it keeps exactly the views within that factor, whatever order they come in (approaching:
// the coarse views first and dropped later; receding: refused at once), and the "rays" posterior
// is the closed-form one given exactly those views.
TEST(VehicleDimensionEstimator, ResolutionCutIsRelaxedToEachVehiclesBestViews) {
  const Camera cam = mast_camera();
  const Eigen::Vector3d whl(2.5, 3.8, 12.0), m(2.3, 3.2, 10.0), s(0.3, 0.5, 2.0);
  const auto [approaching, views, best] = approaching_lorry(cam, whl);
  auto p = chain_params(VehicleSampler::Rays, 20000);
  p.proposal_scale = 0.3;  // two far rays leave L metres wide: longer steps, thinned, to mix
  p.thinning = 10;
  p.max_length_resolution = 0.5 * best;  // no view passes the fixed cut
  p.length_resolution_factor = 0.0;      // alone
  p.far_view_gate = 0.0;                 // the cut alone (far views: the next test)
  const std::vector<models::VehicleModel> one{{"only", m, s, 1.0, false}};
  filters::VehicleDimensionEstimator fixed(cam, one, p);
  for (std::size_t k = 0; k < approaching.size(); ++k) fixed.update_polygon(1, static_cast<int>(k) + 1, approaching[k]);
  EXPECT_FALSE(fixed.estimate(1).valid);

  p.length_resolution_factor = 1.3;
  std::vector<VehicleObservation> used;
  for (const auto& v : views) {
    if (v.edge_resolution(1) <= 1.3 * best) used.push_back(v);
  }
  ASSERT_GE(used.size(), 2u);
  ASSERT_LT(used.size(), views.size());
  filters::VehicleDimensionEstimator relaxed(cam, one, p), receding(cam, one, p);
  for (std::size_t k = 0; k < approaching.size(); ++k) {
    relaxed.update_polygon(1, static_cast<int>(k) + 1, approaching[k]);
    receding.update_polygon(1, static_cast<int>(k) + 1, approaching[approaching.size() - 1 - k]);
  }
  const auto [mu, cov] = gaussian_posterior(used, m, s, p.likelihood.sigma_w);
  for (const auto* est : {&relaxed, &receding}) {
    const auto e = est->estimate(1);
    ASSERT_TRUE(e.valid);
    EXPECT_EQ(e.frames_used, static_cast<int>(used.size()));
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(e.dimensions(k), mu(k), 4.0 * std::sqrt(cov(k, k) / 1000.0)) << "dimension " << k;
    }
  }
}

// Far views (far_view_gate): the views beyond the cut whose rays lie within the gate of the near
// views' answer join it, each with S widened by its resolution over the cut's. Exact silhouettes of
// one rigid cuboid all agree, so every view joins and the answer is the closed-form posterior given
// all of them so weighted; a view of a cuboid 8 m longer (two vehicles in one far outline) lies
// beyond the gate and stays out.
TEST(VehicleDimensionEstimator, FarViewsThatAgreeJoinTheAnswer) {
  const Camera cam = mast_camera();
  const Eigen::Vector3d whl(2.5, 3.8, 12.0), m(2.3, 3.2, 10.0), s(0.3, 0.5, 2.0);
  const auto [approaching, views, best] = approaching_lorry(cam, whl);
  std::vector<double> widen;  // r / (1.3 r_best) beyond the cut
  for (const auto& v : views) widen.push_back(std::max(1.0, v.edge_resolution(1) / (1.3 * best)));
  ASSERT_GT(*std::max_element(widen.begin(), widen.end()), 1.5);
  const Eigen::Matrix2Xd merged = silhouette(cam, corners_at(cam, 4.3, 75.0, whl(0), whl(1), whl(2) + 8.0));
  auto p = chain_params(VehicleSampler::Rays, 20000);
  p.proposal_scale = 0.3;
  p.thinning = 10;
  p.length_resolution_factor = 1.3;  // three views within the cut (the previous test)
  const std::vector<models::VehicleModel> one{{"only", m, s, 1.0, false}};
  filters::VehicleDimensionEstimator est(cam, one, p);
  est.update_polygon(1, 1, merged);  // the farthest: used until nearer views tighten the cut
  for (std::size_t k = 0; k < approaching.size(); ++k) est.update_polygon(1, static_cast<int>(k) + 2, approaching[k]);
  const auto [mu, cov] = gaussian_posterior(views, m, s, p.likelihood.sigma_w, widen);
  const auto e = est.estimate(1);
  ASSERT_TRUE(e.valid);
  EXPECT_EQ(e.frames_used, static_cast<int>(views.size()));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(e.dimensions(k), mu(k), 4.0 * std::sqrt(cov(k, k) / 1000.0)) << "dimension " << k;
  }
}

TEST(VehicleDimensionEstimator, ParametersAreValidated) {
  const auto bad = [](auto set) {
    VehicleEstimatorParams p;
    set(p);
    EXPECT_THROW(filters::VehicleDimensionEstimator(mast_camera(), {}, p), InvalidArgument);
  };
  bad([](VehicleEstimatorParams& p) { p.n_particles = 0; });
  bad([](VehicleEstimatorParams& p) { p.thinning = 0; });
  bad([](VehicleEstimatorParams& p) { p.burn_in = -1; });
  bad([](VehicleEstimatorParams& p) { p.proposal_scale = 0.0; });
  bad([](VehicleEstimatorParams& p) { p.dynamic_sigma = std::nan(""); });
  bad([](VehicleEstimatorParams& p) { p.min_size[1] = -1.0; });
  bad([](VehicleEstimatorParams& p) { p.likelihood.sigma_h = 0.0; });
  bad([](VehicleEstimatorParams& p) { p.heavy_volume = 0.0; });
  bad([](VehicleEstimatorParams& p) { p.border_margin_px = -1.0; });
  bad([](VehicleEstimatorParams& p) { p.max_length_resolution = std::nan(""); });
  bad([](VehicleEstimatorParams& p) { p.length_resolution_factor = 0.5; });
  bad([](VehicleEstimatorParams& p) { p.far_view_gate = -1.0; });
  bad([](VehicleEstimatorParams& p) { p.max_vehicle_width = std::nan(""); });
  // The table names every field.
  const auto& t = VehicleEstimatorParams::table();
  VehicleEstimatorParams p;
  t.set(p, "sampler", std::string("discrete"));
  EXPECT_EQ(p.sampler, VehicleSampler::Discrete);
  t.set(p, "sigma_l", 0.5);
  EXPECT_EQ(p.likelihood.sigma_l, 0.5);
}
