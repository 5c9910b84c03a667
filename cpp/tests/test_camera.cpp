#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <opencv2/core.hpp>

#include "road_scene.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/models/camera.hpp"

using namespace vtrack;
using models::Camera;
using models::CameraCalibration;
using road_scene::look;
using road_scene::opencv_project;

namespace {

const std::vector<double> kBarrel = {-0.25, 0.08, 0.001, -0.0015, -0.01};

// Road points spread over what each test camera sees (Y 15..80 m ahead, X -4..12 m).
Eigen::Matrix3Xd road_grid() {
  Eigen::Matrix3Xd p(3, 0);
  for (double x = -4.0; x <= 12.0; x += 4.0) {
    for (double y = 15.0; y <= 80.0; y += 13.0) {
      p.conservativeResize(3, p.cols() + 1);
      p.col(p.cols() - 1) << x, y, 0.0;
    }
  }
  return p;
}

std::vector<CameraCalibration> cameras(std::vector<double> dist = {}) {
  return {look({-3.0, 0.0, 8.0}, 12.0, 12.0, 0.0, dist), look({5.0, 0.0, 7.0}, 0.0, 10.0, 0.0, dist),
          look({-6.0, 5.0, 11.0}, 25.0, 14.0, 0.0, dist)};
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Camera, HomographyMatchesProjectPointsOfRoadPoints) {
  const Eigen::Matrix3Xd road = road_grid();
  for (const auto& c : cameras()) {
    const Camera cam(c);
    const Eigen::Matrix2Xd expected = opencv_project(c, road);
    Eigen::Matrix3Xd xy1(3, road.cols());
    xy1 << road.topRows<2>(), Eigen::RowVectorXd::Ones(road.cols());
    const Eigen::Matrix3Xd u = cam.road_to_image() * xy1;
    const Eigen::Matrix2Xd pixels = u.colwise().hnormalized();
    EXPECT_LT((pixels - expected).cwiseAbs().maxCoeff(), 1e-9);
    // The inverse homography takes the pixels back to the road points.
    const Eigen::Matrix2Xd back = (cam.image_to_road() * pixels.colwise().homogeneous()).colwise().hnormalized();
    EXPECT_LT((back - road.topRows<2>()).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(Camera, ImageToRoadInvertsOpenCvProjectionWithDistortion) {
  const Eigen::Matrix3Xd road = road_grid();
  for (const auto& c : cameras(kBarrel)) {
    const Camera cam(c);
    ASSERT_TRUE(cam.has_distortion());
    const Eigen::Matrix2Xd pixels = opencv_project(c, road);
    const Eigen::Matrix2Xd back = cam.image_to_road_points(pixels);
    EXPECT_LT((back - road.topRows<2>()).cwiseAbs().maxCoeff(), 1e-6);
    // undistort() gives the pinhole image of the same points.
    CameraCalibration pinhole = c;
    pinhole.dist.resize(0);
    EXPECT_LT((cam.undistort(pixels) - opencv_project(pinhole, road)).cwiseAbs().maxCoeff(), 1e-7);
  }
}

TEST(Camera, ProjectMatchesOpenCvAndIsNanBehindTheCamera) {
  const CameraCalibration c = look({-3.0, 0.0, 8.0}, 12.0, 12.0, 0.0, kBarrel);
  const Camera cam(c);
  Eigen::Matrix3Xd p(3, 3);
  p << 2.0, 5.0, 0.0, 30.0, 50.0, -20.0, 1.5, 0.0, 0.0;  // the third is behind the camera
  const Eigen::Matrix2Xd got = cam.project(p);
  EXPECT_LT((got.leftCols<2>() - opencv_project(c, p.leftCols<2>())).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_TRUE(std::isnan(got(0, 2)) && std::isnan(got(1, 2)));
  EXPECT_LT((cam.road_to_image_points(p.topRows<2>().leftCols<1>()) -
             opencv_project(c, Eigen::Vector3d(2.0, 30.0, 0.0)))
                .norm(),
            1e-12);
}

TEST(Camera, RaysPassThroughTheWorldPointsTheyImage) {
  for (const auto& c : cameras(kBarrel)) {
    const Camera cam(c);
    Eigen::Matrix3Xd p(3, 4);
    p << 0.0, 4.0, 8.0, -2.0, 20.0, 35.0, 60.0, 25.0, 0.0, 1.5, 3.0, 4.0;
    const Eigen::Matrix3Xd d = cam.rays(opencv_project(c, p));
    for (Eigen::Index i = 0; i < p.cols(); ++i) {
      EXPECT_NEAR(d.col(i).norm(), 1.0, 1e-12);
      const Eigen::Vector3d v = p.col(i) - cam.centre();
      EXPECT_LT(v.cross(d.col(i)).norm(), 1e-6 * v.norm()) << "point " << i;
      EXPECT_GT(v.dot(d.col(i)), 0.0);
    }
  }
}

TEST(Camera, CentreAndRoadFrame) {
  const Camera cam(look({-3.0, 2.0, 8.0}, 12.0, 12.0, 30.0));
  EXPECT_LT((cam.centre() - Eigen::Vector3d(-3.0, 2.0, 8.0)).norm(), 1e-12);
  EXPECT_LT((cam.road_axis() - Eigen::Vector3d(-0.5, std::sqrt(3.0) / 2, 0.0)).norm(), 1e-12);
  // Lateral = road axis x Z: to the right of the direction of travel.
  EXPECT_LT((cam.lateral_axis() - Eigen::Vector3d(std::sqrt(3.0) / 2, 0.5, 0.0)).norm(), 1e-12);
}

TEST(Camera, PixelAboveTheHorizonHasNoRoadPoint) {
  const Camera cam(look({0.0, 0.0, 8.0}, 0.0, 10.0));
  // The horizon is at v = 360 - 1000 tan(10 deg) = 183.7.
  Eigen::Matrix2Xd px(2, 2);
  px << 640.0, 640.0, 190.0, 170.0;
  EXPECT_NO_THROW(cam.image_to_road_points(px.leftCols<1>()));
  const std::string e = error_of([&] { cam.image_to_road_points(px); });
  EXPECT_NE(e.find("horizon"), std::string::npos) << e;
  EXPECT_NE(e.find("(640, 170)"), std::string::npos) << e;
}

TEST(Camera, ValidationNamesTheKeyAndTheProblem) {
  const CameraCalibration good = look({0.0, 0.0, 8.0}, 0.0, 15.0);
  EXPECT_NO_THROW(Camera{good});
  struct Case {
    std::function<void(CameraCalibration&)> change;
    std::string expect;
  };
  const std::vector<Case> cases = {
      {[](CameraCalibration& c) { c.K(0, 0) = -1.0; }, "K must have positive focal lengths"},
      {[](CameraCalibration& c) { c.K(0, 1) = 0.5; }, "K must have no skew"},
      {[](CameraCalibration& c) { c.K(2, 2) = 2.0; }, "K must be [[fx, 0, cx]"},
      {[](CameraCalibration& c) { c.K(1, 2) = NAN; }, "K must be finite"},
      {[](CameraCalibration& c) { c.dist = Eigen::VectorXd::Zero(3); }, "dist must have 0, 4, 5, 8, 12 or 14"},
      {[](CameraCalibration& c) { c.R(0, 0) *= 1.1; }, "R must be a rotation matrix (orthonormal)"},
      {[](CameraCalibration& c) { c.R.setZero(); }, "R must be a rotation matrix (orthonormal)"},
      {[](CameraCalibration& c) { c.R.row(0) *= -1.0; }, "(a reflection)"},
      {[](CameraCalibration& c) { c.t(1) = INFINITY; }, "t must be finite"},
      {[](CameraCalibration& c) { c.road_axis_world << 0.0, 1.0, 0.5; }, "road_axis_world must lie in the road plane"},
      {[](CameraCalibration& c) { c.road_axis_world << 0.0, 0.0, 0.0; }, "road_axis_world must be a finite non-zero"},
      {[](CameraCalibration& c) { c.image_width = 0; }, "image_size"},
      {[](CameraCalibration& c) { c.t = -c.R * Eigen::Vector3d(0.0, 0.0, -2.0); }, "at or below the road plane"},
      {[](CameraCalibration& c) { c = look({0.0, 0.0, 8.0}, 0.0, -5.0); }, "looks away from the road"},
  };
  for (const auto& k : cases) {
    CameraCalibration c = good;
    k.change(c);
    const std::string e = error_of([&] { Camera{c}; });
    EXPECT_NE(e.find(k.expect), std::string::npos) << "expected '" << k.expect << "', got: " << e;
  }
}

TEST(CameraFile, ReadsJsonYamlAndOpenCvFileStorage) {
  const CameraCalibration c = look({-3.0, 0.0, 8.0}, 12.0, 12.0, 0.0, kBarrel);
  auto row = [&](const Eigen::Matrix3d& m, int r) {
    return "[" + num(m(r, 0)) + ", " + num(m(r, 1)) + ", " + num(m(r, 2)) + "]";
  };
  auto rows = [&](const Eigen::Matrix3d& m) { return "[" + row(m, 0) + ", " + row(m, 1) + ", " + row(m, 2) + "]"; };
  const std::string t = "[" + num(c.t(0)) + ", " + num(c.t(1)) + ", " + num(c.t(2)) + "]";
  const std::string json = write_temp("camera.json",
      "{\"K\": " + rows(c.K) + ", \"dist\": [-0.25, 0.08, 0.001, -0.0015, -0.01], \"R\": " + rows(c.R) +
      ", \"t\": " + t + ", \"road_axis_world\": [0, 1, 0], \"image_size\": [1280, 720], \"note\": \"ignored\"}");
  // YAML, R as 9 numbers row-major, no road axis (default +Y), an unknown nested key.
  std::string flat_r = row(c.R, 0) + row(c.R, 1) + row(c.R, 2);
  for (std::string::size_type p; (p = flat_r.find("][")) != std::string::npos;) flat_r.replace(p, 2, ", ");
  const std::string yaml = write_temp("camera.yaml",
      "K: " + rows(c.K) + "\ndist: [-0.25, 0.08, 0.001, -0.0015, -0.01]\nR: " + flat_r + "\nt: " + t +
      "\nmetadata: {site: A12, lanes: [1, 2]}\n");
  const std::string fs_path = ::testing::TempDir() + "camera_fs.yml";
  {
    cv::FileStorage fs(fs_path, cv::FileStorage::WRITE);
    cv::Mat K, R, tt, d;
    cv::eigen2cv(c.K, K);
    cv::eigen2cv(c.R, R);
    cv::eigen2cv(c.t, tt);
    cv::eigen2cv(Eigen::VectorXd(c.dist), d);
    fs << "K" << K << "dist" << d << "R" << R << "t" << tt;
  }
  for (const std::string& path : {json, yaml, fs_path}) {
    SCOPED_TRACE(path);
    const Camera cam = models::read_camera_file(path);
    EXPECT_LT((cam.calibration().K - c.K).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((cam.calibration().R - c.R).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((cam.calibration().t - c.t).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((cam.calibration().dist - c.dist).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_EQ(cam.road_axis(), Eigen::Vector3d::UnitY());
  }
  EXPECT_EQ(models::read_camera_file(json).calibration().image_width, 1280);
}

TEST(CameraFile, ErrorsNameTheFileTheKeyAndTheProblem) {
  const std::string K = "K: [[1000, 0, 640], [0, 1000, 360], [0, 0, 1]]\n";
  const std::string R = "R: [[1, 0, 0], [0, 0, -1], [0, 1, 0]]\n";  // looks horizontally along +Y
  const std::string Rdown = "R: [[1, 0, 0], [0, -0.5, -0.8660254037844386], [0, 0.8660254037844386, -0.5]]\n";
  const std::string t = "t: [0, 6.928203230275509, 4]\n";  // C = (0, 0, 8)
  struct Case {
    std::string text, expect;
  };
  const std::vector<Case> cases = {
      {K + "dist: []\n" + Rdown, "missing key 't'"},
      {"dist: []\n" + Rdown + t, "missing key 'K'"},
      {K + Rdown + t, "missing key 'dist'"},
      {K + "dist: []\nR: [[1, 0], [0, 1]]\n" + t, "R[0] must be a row of 3 numbers"},
      {K + "dist: []\nR: [1, 2, 3]\n" + t, "R must have 9 numbers, got 3"},
      {K + "dist: [0, x, 0, 0]\n" + Rdown + t, "dist[1] must be a number, got 'x'"},
      {K + "dist: []\n" + R + "t: [0, 8, 0]\n", "looks away from the road"},
      {K + "dist: []\nR: [[1, 0, 0], [0, 1, 0], [0, 0, 0]]\n" + t, "R must be a rotation matrix"},
      {K + "dist: []\n" + Rdown + "t: [0, 0, 0]\n", "at or below the road plane"},
      {"[1, 2, 3]\n", "expected a map"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string path = write_temp("bad_camera_" + std::to_string(i) + ".yaml", cases[i].text);
    const std::string e = error_of([&] { models::read_camera_file(path); });
    EXPECT_NE(e.find("camera file " + path + ": "), std::string::npos) << e;
    EXPECT_NE(e.find(cases[i].expect), std::string::npos) << "expected '" << cases[i].expect << "', got: " << e;
    EXPECT_THROW(models::read_camera_file(path), InvalidArgument);
  }
  EXPECT_NO_THROW(models::read_camera_file(write_temp("good_camera.yaml", K + "dist: []\n" + Rdown + t)));
  EXPECT_THROW(models::read_camera_file(::testing::TempDir() + "no_such_camera.json"), IoError);
  const std::string broken = write_temp("broken_camera.json", "{\"K\": [[1, 0, 0], ");
  const std::string e = error_of([&] { models::read_camera_file(broken); });
  EXPECT_NE(e.find("not valid YAML or JSON"), std::string::npos) << e;
  EXPECT_THROW(models::read_camera_file(broken), IoError);
}
