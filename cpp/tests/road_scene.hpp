#pragma once
// Test helpers for the vehicle geometry: road cameras built from a pose, and cuboid vehicles
// rendered with OpenCV alone (cv::projectPoints, cv::fillPoly), independently of
// vtrack::models::Camera.
#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>

#include "vtrack/models/camera.hpp"

namespace road_scene {

// A camera at `position` (world, metres) whose optical axis has heading `yaw_deg` from the road
// axis towards the lateral axis and looks `pitch_deg` below the horizon; no roll. The road axis
// is (cos(road_deg), sin(road_deg)) rotated from +Y towards -X, i.e. +Y for road_deg = 0.
inline vtrack::models::CameraCalibration look(const Eigen::Vector3d& position, double yaw_deg, double pitch_deg,
                                              double road_deg = 0.0, std::vector<double> dist = {}) {
  const double d2r = M_PI / 180.0;
  const Eigen::Vector3d along(-std::sin(road_deg * d2r), std::cos(road_deg * d2r), 0.0);
  const Eigen::Vector3d lateral = along.cross(Eigen::Vector3d::UnitZ());
  const double yaw = yaw_deg * d2r, pitch = pitch_deg * d2r;
  const Eigen::Vector3d heading = std::cos(yaw) * along + std::sin(yaw) * lateral;
  const Eigen::Vector3d forward = std::cos(pitch) * heading - std::sin(pitch) * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  vtrack::models::CameraCalibration c;
  c.R.row(0) = right;
  c.R.row(1) = down;
  c.R.row(2) = forward;
  c.t = -c.R * position;
  c.K << 1000.0, 0.0, 640.0, 0.0, 1000.0, 360.0, 0.0, 0.0, 1.0;
  c.dist = Eigen::Map<const Eigen::VectorXd>(dist.data(), static_cast<Eigen::Index>(dist.size()));
  c.road_axis_world = along;
  c.image_width = 1280;
  c.image_height = 720;
  return c;
}

// World corners (3 x 8) of a cuboid standing on the road: the footprint corner `origin`
// (Z = 0), W along `lateral`, L along `along`, H up; corner i has bits (w, l, h) = (i&1, i&2, i&4).
inline Eigen::Matrix<double, 3, 8> cuboid(const Eigen::Vector3d& origin, const Eigen::Vector3d& lateral,
                                          const Eigen::Vector3d& along, double W, double H, double L) {
  Eigen::Matrix<double, 3, 8> c;
  for (int i = 0; i < 8; ++i) {
    c.col(i) = origin + ((i & 1) ? W : 0.0) * lateral + ((i & 2) ? L : 0.0) * along +
               ((i & 4) ? H : 0.0) * Eigen::Vector3d::UnitZ();
  }
  return c;
}

// Image points (2 x n) of world points through OpenCV directly.
inline Eigen::Matrix2Xd opencv_project(const vtrack::models::CameraCalibration& c,
                                       const Eigen::Ref<const Eigen::Matrix3Xd>& world) {
  std::vector<cv::Point3d> pts;
  for (Eigen::Index i = 0; i < world.cols(); ++i) pts.emplace_back(world(0, i), world(1, i), world(2, i));
  cv::Mat K, R, rvec, t;
  cv::eigen2cv(c.K, K);
  cv::eigen2cv(c.R, R);
  cv::eigen2cv(c.t, t);
  cv::Rodrigues(R, rvec);
  cv::Mat dist(1, static_cast<int>(c.dist.size()), CV_64F);
  for (int i = 0; i < dist.cols; ++i) dist.at<double>(0, i) = c.dist(i);
  std::vector<cv::Point2d> out;
  cv::projectPoints(pts, rvec, t, K, dist, out);
  Eigen::Matrix2Xd m(2, world.cols());
  for (Eigen::Index i = 0; i < world.cols(); ++i) m.col(i) << out[i].x, out[i].y;
  return m;
}

// The cuboid's silhouette as a binary mask: each of its six faces, its edges sampled every few
// centimetres (so lens distortion bends them), projected with OpenCV and filled.
inline cv::Mat render_mask(const vtrack::models::CameraCalibration& c, const Eigen::Matrix<double, 3, 8>& corners) {
  static const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  cv::Mat mask = cv::Mat::zeros(c.image_height, c.image_width, CV_8U);
  constexpr int kSamples = 64, kShift = 4;
  for (const auto& f : faces) {
    Eigen::Matrix3Xd edge(3, 4 * kSamples);
    for (int e = 0; e < 4; ++e) {
      for (int s = 0; s < kSamples; ++s) {
        const double u = static_cast<double>(s) / kSamples;
        edge.col(e * kSamples + s) = (1 - u) * corners.col(f[e]) + u * corners.col(f[(e + 1) % 4]);
      }
    }
    const Eigen::Matrix2Xd px = opencv_project(c, edge);
    std::vector<cv::Point> poly;
    for (Eigen::Index i = 0; i < px.cols(); ++i) {
      poly.emplace_back(static_cast<int>(std::lround(px(0, i) * (1 << kShift))),
                        static_cast<int>(std::lround(px(1, i) * (1 << kShift))));
    }
    cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255), cv::LINE_8, kShift);
  }
  return mask;
}

// The outer contour of the largest blob of a mask (pixel centres), 2 x n.
inline Eigen::Matrix2Xd mask_contour(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  std::size_t best = 0;
  for (std::size_t i = 1; i < contours.size(); ++i) {
    if (contours[i].size() > contours[best].size()) best = i;
  }
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(contours.at(best).size()));
  for (std::size_t i = 0; i < contours[best].size(); ++i) {
    out.col(static_cast<Eigen::Index>(i)) << contours[best][i].x, contours[best][i].y;
  }
  return out;
}

}  // namespace road_scene
