#include "vtrack/models/camera.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "vtrack/core/errors.hpp"

namespace vtrack::models {

namespace {

bool all_finite(const Eigen::Ref<const Eigen::MatrixXd>& m) { return m.allFinite(); }

void check_intrinsics(const Eigen::Matrix3d& K) {
  if (!all_finite(K)) throw InvalidArgument("K must be finite");
  if (!(K(0, 0) > 0.0) || !(K(1, 1) > 0.0)) {
    throw InvalidArgument("K must have positive focal lengths fx = K[0][0] and fy = K[1][1], got " +
                          value_text(K(0, 0)) + " and " + value_text(K(1, 1)));
  }
  if (K(0, 1) != 0.0) {
    throw InvalidArgument("K must have no skew (K[0][1] = 0; cv::projectPoints ignores it), got " +
                          value_text(K(0, 1)));
  }
  if (K(1, 0) != 0.0 || K(2, 0) != 0.0 || K(2, 1) != 0.0 || std::abs(K(2, 2) - 1.0) > 1e-12) {
    throw InvalidArgument("K must be [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]: its row 2 is [" +
                          value_text(K(2, 0)) + ", " + value_text(K(2, 1)) + ", " +
                          value_text(K(2, 2)) + "] and K[1][0] = " + value_text(K(1, 0)));
  }
}

void check_rotation(const Eigen::Matrix3d& R) {
  if (!all_finite(R)) throw InvalidArgument("R must be finite");
  const double orthonormality = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthonormality > 1e-6) {
    throw InvalidArgument("R must be a rotation matrix (orthonormal): max |R^T R - I| = " +
                          value_text(orthonormality) + " (tolerance 1e-6)");
  }
  if (R.determinant() < 0.0) {
    throw InvalidArgument("R must be a rotation matrix, got det R = " + value_text(R.determinant()) +
                          " (a reflection)");
  }
}

cv::Mat dist_mat(const Eigen::VectorXd& dist) {
  cv::Mat d(1, static_cast<int>(dist.size()), CV_64F);
  for (Eigen::Index i = 0; i < dist.size(); ++i) d.at<double>(0, static_cast<int>(i)) = dist(i);
  return d;
}

}  // namespace

void validate(const CameraCalibration& c) {
  check_intrinsics(c.K);
  const auto n = c.dist.size();
  if (n != 0 && n != 4 && n != 5 && n != 8 && n != 12 && n != 14) {
    throw InvalidArgument("dist must have 0, 4, 5, 8, 12 or 14 OpenCV coefficients, got " +
                          std::to_string(n));
  }
  if (!all_finite(c.dist)) throw InvalidArgument("dist must be finite");
  check_rotation(c.R);
  if (!all_finite(c.t)) throw InvalidArgument("t must be finite");
  const Eigen::Vector3d& a = c.road_axis_world;
  if (!all_finite(a) || a.head<2>().norm() == 0.0) {
    throw InvalidArgument("road_axis_world must be a finite non-zero direction in the road plane");
  }
  if (std::abs(a.z()) > 1e-6 * a.norm()) {
    throw InvalidArgument("road_axis_world must lie in the road plane (Z component 0), got Z = " +
                          value_text(a.z()));
  }
  if (c.image_width < 0 || c.image_height < 0 || (c.image_width == 0) != (c.image_height == 0)) {
    throw InvalidArgument("image_size must be two positive integers (or absent), got " +
                          std::to_string(c.image_width) + " x " + std::to_string(c.image_height));
  }
  // C = -R^T t. Its height decides whether the road homography exists (det H = -det K * C_z).
  const Eigen::Vector3d centre = -c.R.transpose() * c.t;
  if (!(centre.z() > 0.0)) {
    throw InvalidArgument("t: the optical centre -R^T t is at Z = " + value_text(centre.z()) +
                          " m, at or below the road plane Z = 0 (the road homography is singular "
                          "or sees the road from below)");
  }
  // The optical axis in world coordinates is R^T (0, 0, 1), the third row of R.
  if (!(c.R(2, 2) < 0.0)) {
    throw InvalidArgument("R: the camera looks away from the road: its optical axis (row 2 of R) "
                          "has world Z component " + value_text(c.R(2, 2)) +
                          " >= 0, at or above the horizon");
  }
}

Camera::Camera(CameraCalibration calibration) : calibration_(std::move(calibration)) {
  validate(calibration_);
  calibration_.road_axis_world.z() = 0.0;
  calibration_.road_axis_world.normalize();
  has_distortion_ = calibration_.dist.size() > 0 && calibration_.dist.cwiseAbs().maxCoeff() > 0.0;
  const auto& R = calibration_.R;
  centre_ = -R.transpose() * calibration_.t;
  lateral_axis_ = road_axis().cross(Eigen::Vector3d::UnitZ());
  Eigen::Matrix3d Rt;
  Rt << R.col(0), R.col(1), calibration_.t;
  road_to_image_ = calibration_.K * Rt;
  image_to_road_ = road_to_image_.inverse();
}

Eigen::Matrix2Xd Camera::project(const Eigen::Ref<const Eigen::Matrix3Xd>& world) const {
  const Eigen::Index n = world.cols();
  Eigen::Matrix2Xd out(2, n);
  if (n == 0) return out;
  std::vector<cv::Point3d> points(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) points[i] = {world(0, i), world(1, i), world(2, i)};
  cv::Mat K, R, rvec, t;
  cv::eigen2cv(calibration_.K, K);
  cv::eigen2cv(calibration_.R, R);
  cv::eigen2cv(calibration_.t, t);
  cv::Rodrigues(R, rvec);
  std::vector<cv::Point2d> pixels;
  cv::projectPoints(points, rvec, t, K, dist_mat(calibration_.dist), pixels);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Eigen::Index i = 0; i < n; ++i) {
    // cv::projectPoints divides by z_cam whatever its sign: a point behind the camera would be
    // mirrored onto the image, so it gets NaN instead.
    const double z = calibration_.R.row(2).dot(world.col(i)) + calibration_.t.z();
    out(0, i) = z > 0.0 ? pixels[i].x : nan;
    out(1, i) = z > 0.0 ? pixels[i].y : nan;
  }
  return out;
}

Eigen::Matrix2Xd Camera::undistort(const Eigen::Ref<const Eigen::Matrix2Xd>& pixels) const {
  Eigen::Matrix2Xd out = pixels;
  if (!has_distortion_ || pixels.cols() == 0) return out;
  std::vector<cv::Point2d> src(static_cast<std::size_t>(pixels.cols())), dst;
  for (Eigen::Index i = 0; i < pixels.cols(); ++i) src[i] = {pixels(0, i), pixels(1, i)};
  cv::Mat K;
  cv::eigen2cv(calibration_.K, K);
  // The default undistortPoints stops after 5 fixed-point iterations (a few 0.1 px off for a
  // wide-angle lens); iterate to convergence instead.
  cv::undistortPoints(src, dst, K, dist_mat(calibration_.dist), cv::noArray(), K,
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-12));
  for (Eigen::Index i = 0; i < pixels.cols(); ++i) out.col(i) << dst[i].x, dst[i].y;
  return out;
}

Eigen::Matrix3Xd Camera::rays(const Eigen::Ref<const Eigen::Matrix2Xd>& pixels) const {
  // d_world = R^T K^-1 (u, 1) for the undistorted pixel u.
  Eigen::Matrix3Xd d = (calibration_.R.transpose() * calibration_.K.inverse()) *
                       undistort(pixels).colwise().homogeneous();
  d.colwise().normalize();
  return d;
}

Eigen::Matrix2Xd Camera::image_to_road_points(const Eigen::Ref<const Eigen::Matrix2Xd>& pixels,
                                              const char* what) const {
  const Eigen::Matrix2Xd u = undistort(pixels);
  Eigen::Matrix2Xd out(2, pixels.cols());
  for (Eigen::Index i = 0; i < pixels.cols(); ++i) {
    // The ray's world Z component (up to a positive factor) is row 2 of R^T K^-1 times (u, 1).
    const Eigen::Vector3d uh = u.col(i).homogeneous();
    const double dz = calibration_.R.col(2).dot(calibration_.K.triangularView<Eigen::Upper>().solve(uh));
    if (!(dz < 0.0)) {
      throw InvalidArgument(std::string(what) + " (" + value_text(pixels(0, i)) + ", " +
                            value_text(pixels(1, i)) +
                            ") is at or above the horizon: its ray does not meet the road");
    }
    const Eigen::Vector3d X = image_to_road_ * uh;
    out.col(i) = X.head<2>() / X.z();
  }
  return out;
}

Eigen::Matrix2Xd Camera::road_to_image_points(const Eigen::Ref<const Eigen::Matrix2Xd>& road) const {
  Eigen::Matrix3Xd world(3, road.cols());
  world.topRows<2>() = road;
  world.row(2).setZero();
  return project(world);
}

}  // namespace vtrack::models
