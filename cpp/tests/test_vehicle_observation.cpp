#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "road_scene.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/models/vehicle_observation.hpp"

using namespace vtrack;
using models::Camera;
using models::CameraCalibration;
using models::VehicleObservation;

namespace {

struct Vehicle {
  double lateral, along;  // footprint corner with the smallest road coordinates
  double W, H, L;
};

struct Setup {
  const char* name;
  CameraCalibration calibration;
};

// Roadside masts, a gantry above lane 2 (camera within the width of its vehicles), a steep view
// (camera within the length of nearby ones), a side view, a rotated road axis, lens distortion.
std::vector<Setup> setups() {
  using road_scene::look;
  const std::vector<double> barrel = {-0.25, 0.08, 0.001, -0.0015, -0.01};
  return {{"mast", look({-3.0, 0.0, 8.0}, 12.0, 12.0)},
          {"gantry", look({5.25, 0.0, 7.0}, 0.0, 14.0)},
          {"steep", look({4.0, 16.5, 12.0}, 0.0, 88.0)},
          {"side", look({-8.0, 10.0, 10.0}, 40.0, 16.0)},
          {"rotated road", look({-3.0, 0.0, 8.0}, 12.0, 12.0, 30.0)},
          {"mast, distorted", look({-3.0, 0.0, 8.0}, 12.0, 12.0, 0.0, barrel)}};
}

std::vector<Vehicle> vehicles() {
  return {{0.9, 22.0, 1.8, 1.5, 4.5},  {4.3, 30.0, 2.5, 3.8, 12.0}, {7.9, 18.0, 0.8, 1.3, 2.1},
          {4.4, 14.0, 1.9, 2.4, 5.5}, {0.8, 45.0, 2.55, 3.2, 13.0}, {8.0, 36.0, 1.75, 1.45, 4.2}};
}

Eigen::Matrix<double, 3, 8> corners_of(const Camera& cam, const Vehicle& v) {
  const Eigen::Vector3d origin = v.lateral * cam.lateral_axis() + v.along * cam.road_axis();
  return road_scene::cuboid(origin, cam.lateral_axis(), cam.road_axis(), v.W, v.H, v.L);
}

bool in_image(const Eigen::Matrix2Xd& px, const CameraCalibration& c) {
  return px.allFinite() && px.row(0).minCoeff() > 2 && px.row(1).minCoeff() > 2 &&
         px.row(0).maxCoeff() < c.image_width - 3 && px.row(1).maxCoeff() < c.image_height - 3;
}

// The exact silhouette of a cuboid without distortion: the convex hull of its projected corners.
Eigen::Matrix2Xd exact_silhouette(const Camera& cam, const Eigen::Matrix<double, 3, 8>& corners) {
  const Eigen::Matrix2Xd px = cam.project(corners);
  std::vector<cv::Point2f> pts, hull;
  for (int i = 0; i < 8; ++i) pts.emplace_back(static_cast<float>(px(0, i)), static_cast<float>(px(1, i)));
  cv::convexHull(pts, hull);
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(hull.size()));
  for (std::size_t i = 0; i < hull.size(); ++i) out.col(static_cast<Eigen::Index>(i)) << hull[i].x, hull[i].y;
  return out;
}

// Metres on the road moved by `px` pixels at an image point, the largest over the 4 directions.
double metres_per(const Camera& cam, const Eigen::Vector2d& at, double px) {
  Eigen::Matrix2Xd p(2, 5);
  p << at.x(), at.x() + px, at.x() - px, at.x(), at.x(), at.y(), at.y(), at.y(), at.y() + px, at.y() - px;
  const Eigen::Matrix2Xd r = cam.image_to_road_points(p);
  return (r.rightCols<4>().colwise() - r.col(0)).colwise().norm().maxCoeff();
}

// The foot of the perpendicular from x to the line through p and q, directly.
Eigen::Vector3d line_foot(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& x) {
  const Eigen::Vector3d d = q - p;
  return p + d * (x - p).dot(d) / d.squaredNorm();
}

}  // namespace

TEST(VehicleObservation, PluckerProjectionIsTheLinePlaneIntersection) {
  const Camera cam(setups()[0].calibration);
  const VehicleObservation obs = models::observe_box(cam, 600.0, 300.0, 120.0, 90.0);
  core::Rng rng(3);
  Eigen::Matrix3Xd x(3, 200);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    x.col(i) << 3.0 * rng.normal(), 2.0 + 2.0 * rng.normal(), 6.0 + 5.0 * rng.normal();
  }
  const Eigen::Matrix3Xd y = models::project_onto_ray(obs, x);
  const Eigen::VectorXd dist = models::ray_distance(obs, x);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const Eigen::Vector3d expected = line_foot(obs.a, obs.b, x.col(i));
    EXPECT_LT((y.col(i) - expected).norm(), 1e-9 * (1.0 + expected.norm()));
    EXPECT_NEAR(dist(i), (x.col(i) - expected).norm(), 1e-9);
  }
  // L = a b^T - b a^T is antisymmetric with rank 2.
  EXPECT_LT((obs.plucker + obs.plucker.transpose()).norm(), 1e-12);
  EXPECT_NEAR(obs.plucker.determinant(), 0.0, 1e-6);
}

TEST(VehicleObservation, RenderedCuboidRayPassesThroughItsTopFarCorner) {
  int within_width = 0, within_length = 0, checked = 0;
  for (const auto& s : setups()) {
    const Camera cam(s.calibration);
    for (const auto& v : vehicles()) {
      const auto corners = corners_of(cam, v);
      if (!in_image(cam.project(corners), s.calibration)) continue;
      SCOPED_TRACE(std::string(s.name) + ", vehicle at along " + std::to_string(v.along));
      ++checked;
      const cv::Mat mask = road_scene::render_mask(s.calibration, corners);
      const VehicleObservation obs = models::observe_silhouette(cam, road_scene::mask_contour(mask));
      within_width += obs.camera_within_width;
      within_length += obs.camera_within_length;
      // Pixel quantisation of the rasterised silhouette (~1 px at both corners) in metres.
      const Eigen::Vector2d far_px = cam.road_to_image_points(obs.far_corner_world.head<2>());
      const Eigen::Vector2d near_px = cam.road_to_image_points(obs.reference_world.head<2>());
      const double tol = metres_per(cam, far_px, 1.5) + metres_per(cam, near_px, 1.5);
      const Eigen::Vector3d truth(v.W, v.H, v.L);
      EXPECT_LT(models::ray_distance(obs, truth)(0), tol) << "tolerance " << tol;
      if (obs.camera_within_width || obs.camera_within_length) continue;
      // The paper's construction: the reference point is the footprint corner nearest the
      // camera, and the cuboid's top far corner images onto the box's far-most corner.
      const Eigen::Matrix<double, 3, 8> whl = obs.to_whl(corners);
      EXPECT_LT(whl.colwise().norm().minCoeff(), metres_per(cam, near_px, 1.5));
      Eigen::Index top_far = 0;
      (whl.row(0) + whl.row(2) + 10.0 * whl.row(1)).maxCoeff(&top_far);
      EXPECT_LT((cam.project(corners.col(top_far)) - far_px).norm(), 1.5);
    }
  }
  EXPECT_GE(checked, 25);
  EXPECT_GE(within_width, 2);   // the gantry's lane-2 vehicles
  EXPECT_GE(within_length, 1);  // the steep view's nearest vehicle
}

TEST(VehicleObservation, LikelihoodIsMaximalAtTheTrueDimensionsOnExactViews) {
  const models::RayLikelihoodParams params;
  for (const auto& s : setups()) {
    if (s.calibration.dist.size() > 0) continue;  // the exact silhouette below is distortion-free
    const Camera cam(s.calibration);
    for (const auto& v : vehicles()) {
      const auto corners = corners_of(cam, v);
      if (!cam.project(corners).allFinite()) continue;
      const VehicleObservation obs = models::observe_silhouette(cam, exact_silhouette(cam, corners));
      const Eigen::Vector3d truth(v.W, v.H, v.L);
      EXPECT_LT(models::ray_distance(obs, truth)(0), 1e-5);
      // On a grid around the truth, nothing scores higher, and every point off the ray by more
      // than 1 cm scores lower.
      Eigen::Matrix3Xd grid(3, 0);
      for (double dw = -0.6; dw <= 0.61; dw += 0.2) {
        for (double dh = -0.6; dh <= 0.61; dh += 0.2) {
          for (double dl = -1.5; dl <= 1.51; dl += 0.5) {
            grid.conservativeResize(3, grid.cols() + 1);
            grid.col(grid.cols() - 1) = truth + Eigen::Vector3d(dw, dh, dl);
          }
        }
      }
      const double at_truth = models::ray_log_likelihood(obs, truth, params)(0);
      const Eigen::VectorXd ll = models::ray_log_likelihood(obs, grid, params);
      const Eigen::VectorXd d = models::ray_distance(obs, grid);
      EXPECT_NEAR(at_truth, 0.0, 1e-9);
      for (Eigen::Index i = 0; i < grid.cols(); ++i) {
        EXPECT_LE(ll(i), at_truth + 1e-12);
        if (d(i) > 0.01) {
          EXPECT_LT(ll(i), at_truth - 0.5 * 0.01 * 0.01 / (0.25 * 0.25) * 0.99);
        }
      }
    }
  }
}

TEST(VehicleObservation, LikelihoodIsTheGaussianOfTheResidual) {
  const Camera cam(setups()[1].calibration);
  const VehicleObservation obs = models::observe_box(cam, 560.0, 280.0, 160.0, 150.0);
  models::RayLikelihoodParams p;
  p.sigma_w = 0.2;
  p.sigma_h = 0.4;
  p.sigma_l = 0.8;
  const Eigen::Vector3d x(2.0, 1.0, 5.0);
  const Eigen::Vector3d r = line_foot(obs.a, obs.b, x) - x;
  const double expected = -0.5 * (std::pow(r(0) / 0.2, 2) + std::pow(r(1) / 0.4, 2) + std::pow(r(2) / 0.8, 2));
  EXPECT_NEAR(models::ray_log_likelihood(obs, x, p)(0), expected, 1e-9);
  p.sigma_h = 0.0;
  EXPECT_THROW(models::ray_log_likelihood(obs, x, p), InvalidArgument);
}

TEST(VehicleObservation, FeasibleHeightsBoundTheSegmentOfTheRay) {
  const Camera cam(setups()[0].calibration);
  const VehicleObservation obs = models::observe_box(cam, 700.0, 330.0, 90.0, 70.0);
  const Eigen::Vector3d min_size(0.4, 0.6, 1.0);
  const auto [h0, h1] = obs.feasible_heights(min_size);
  ASSERT_LT(h0, h1);
  EXPECT_NEAR(h0, 0.6, 1e-12);
  EXPECT_LT(h1, obs.b.y());
  // Brute force over heights: feasible exactly inside [h0, h1].
  for (double h = 0.0; h < obs.b.y(); h += 0.01) {
    const Eigen::Vector3d x = obs.point_at_height(h);
    EXPECT_NEAR(x.y(), h, 1e-12);
    const bool ok = (x.array() >= min_size.array() - 1e-12).all();
    EXPECT_EQ(ok, h >= h0 - 1e-9 && h <= h1 + 1e-9) << "h = " << h;
  }
  const auto [e0, e1] = obs.feasible_heights(Eigen::Vector3d(100.0, 0.6, 1.0));
  EXPECT_GT(e0, e1);
}

TEST(VehicleObservation, BoxObservationContainsTheSilhouetteObservation) {
  const Camera cam(setups()[0].calibration);
  const Vehicle v{4.3, 30.0, 2.5, 3.8, 12.0};
  const auto corners = corners_of(cam, v);
  const Eigen::Matrix2Xd poly = exact_silhouette(cam, corners);
  const Eigen::Vector2d lo = poly.rowwise().minCoeff(), hi = poly.rowwise().maxCoeff();
  const auto box = models::observe_box(cam, lo.x(), lo.y(), hi.x() - lo.x(), hi.y() - lo.y()).box;
  const auto sil = models::observe_silhouette(cam, poly).box;
  EXPECT_LE(box.lateral_min, sil.lateral_min + 1e-9);
  EXPECT_GE(box.lateral_max, sil.lateral_max - 1e-9);
  EXPECT_LE(box.along_min, sil.along_min + 1e-9);
  EXPECT_GE(box.along_max, sil.along_max - 1e-9);
}

TEST(VehicleObservation, BadSilhouettesAreRefused) {
  const Camera cam(road_scene::look({0.0, 0.0, 8.0}, 0.0, 10.0));
  EXPECT_THROW(models::observe_box(cam, 600.0, 300.0, NAN, 20.0), InvalidArgument);
  EXPECT_THROW(models::observe_box(cam, 600.0, 300.0, -5.0, 20.0), InvalidArgument);
  Eigen::Matrix2Xd two(2, 2);
  two << 1.0, 2.0, 300.0, 310.0;
  EXPECT_THROW(models::observe_silhouette(cam, two), InvalidArgument);
  try {  // the horizon is at v = 183.7
    models::observe_box(cam, 600.0, 150.0, 40.0, 60.0);
    ADD_FAILURE() << "a silhouette across the horizon was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("silhouette vertex (600, 150) is at or above the horizon"),
              std::string::npos)
        << e.what();
  }
}

// ---- §3.2 -------------------------------------------------------------------------------------------

TEST(VehicleModelPrior, Table1IsTheDefault) {
  const auto m = models::table1_vehicle_models();
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[2].name, "truck");
  EXPECT_EQ(m[2].mean, Eigen::Vector3d(2.0, 2.5, 7.0));
  EXPECT_EQ(m[2].sigma, Eigen::Vector3d(0.2, 0.3, 1.0));
  EXPECT_EQ(m[3].name, "trailer");
  EXPECT_EQ(m[3].sigma, Eigen::Vector3d(0.1, 0.1, 2.0));
  EXPECT_EQ(m[4].mean, Eigen::Vector3d(2.0, 2.5, 10.0));
  EXPECT_TRUE(m[2].heavy && m[4].heavy && !m[0].heavy && !m[1].heavy && !m[3].heavy);
}

TEST(VehicleModelPrior, LogDensityIsTheNormalisedMixture) {
  models::VehiclePriorParams p;
  p.models[1].weight = 3.0;  // unequal weights must be normalised
  const models::VehicleModelPrior prior(p);
  core::Rng rng(11);
  Eigen::Matrix3Xd x(3, 300);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    x.col(i) << 1.8 + 0.3 * rng.normal(), 2.0 + 0.6 * rng.normal(), 7.0 + 3.0 * rng.normal();
  }
  x.col(0) << 0.3, 1.5, 4.0;  // below min_size W
  int truncated = 0;
  const Eigen::VectorXd got = prior.log_density(x);
  const Eigen::MatrixXd post = prior.class_log_posteriors(x);
  const std::vector<int> map = prior.map_class(x);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    double sum = 0.0, total_w = 0.0, best = -1.0;
    int best_m = -1;
    for (const auto& m : p.models) total_w += m.weight;
    for (std::size_t m = 0; m < p.models.size(); ++m) {
      const auto& c = p.models[m];
      double pdf = c.weight / total_w;
      for (int k = 0; k < 3; ++k) {
        pdf *= std::exp(-0.5 * std::pow((x(k, i) - c.mean(k)) / c.sigma(k), 2)) / (std::sqrt(2 * M_PI) * c.sigma(k));
      }
      sum += pdf;
      if (pdf > best) best = pdf, best_m = static_cast<int>(m);
    }
    if ((x.col(i).array() < p.min_size.array()).any()) {
      EXPECT_EQ(got(i), -std::numeric_limits<double>::infinity());
      ++truncated;
    } else if (sum > 1e-300) {
      EXPECT_NEAR(got(i), std::log(sum), 1e-9 * std::max(1.0, std::abs(std::log(sum))));
    }
    if (best > 1e-300) {
      EXPECT_EQ(map[static_cast<std::size_t>(i)], best_m);
    }
    EXPECT_NEAR(post.col(i).array().exp().sum(), 1.0, 1e-12);
  }
  EXPECT_GE(truncated, 1);
}

TEST(VehicleModelPrior, ValidationAndModelsFile) {
  models::VehiclePriorParams p;
  p.models[2].sigma(1) = 0.0;
  EXPECT_THROW(models::VehicleModelPrior{p}, InvalidArgument);
  p = {};
  p.models[3].name = "car";
  EXPECT_THROW(models::VehicleModelPrior{p}, InvalidArgument);
  p = {};
  p.models.clear();
  EXPECT_THROW(models::VehicleModelPrior{p}, InvalidArgument);

  const std::string path = ::testing::TempDir() + "models.yaml";
  std::ofstream(path) << "other: 1\nmodels:\n"
                         "  - {name: car, W: 1.8, H: 1.5, L: 4.5, sigma_w: 0.1, sigma_h: 0.15, sigma_l: 0.4}\n"
                         "  - {name: lorry, W: 2.5, H: 3.5, L: 10, sigma_w: 0.1, sigma_h: 0.4, sigma_l: 2.5,"
                         " weight: 0.2, heavy: true}\n";
  const auto models = models::read_vehicle_models_file(path);
  ASSERT_EQ(models.size(), 2u);
  EXPECT_EQ(models[1].name, "lorry");
  EXPECT_EQ(models[1].sigma, Eigen::Vector3d(0.1, 0.4, 2.5));
  EXPECT_DOUBLE_EQ(models[1].weight, 0.2);
  EXPECT_TRUE(models[1].heavy && !models[0].heavy);
  auto error_for = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      models::read_vehicle_models_file(path);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(error_for("models:\n  - {name: car, W: 1.8, H: 1.5, L: 4.5, sigma_w: 0.1, sigma_h: 0.1, sigma_l: 0.4, "
                      "heavvy: true}\n")
                .find("models[0]: unknown key 'heavvy'"),
            std::string::npos);
  EXPECT_NE(error_for("models:\n  - {name: car, W: 1.8, H: 1.5, sigma_w: 0.1, sigma_h: 0.1, sigma_l: 0.4}\n")
                .find("missing key 'L'"),
            std::string::npos);
  EXPECT_NE(error_for("models:\n  - {name: car, W: -1.8, H: 1.5, L: 4, sigma_w: 0.1, sigma_h: 0.1, sigma_l: 0.4}\n")
                .find("models[0] (car): W must be a positive finite number"),
            std::string::npos);
  EXPECT_NE(error_for("cars: []\n").find("vehicle models file " + path + ": expected a map with a list 'models'"),
            std::string::npos);
}
