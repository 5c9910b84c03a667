#pragma once
// A calibrated camera over a road (particle-filters-human-vehicle.txt §3.1: "provided the
// calibration of the camera is available"), in OpenCV's conventions, and the camera file it is
// read from.
//
// Conventions. World coordinates in metres, Z up, the road is the plane Z = 0. A world point X
// has camera coordinates x_cam = R X + t (x right, y down, z forward, OpenCV's), undistorted
// pixel coordinates u ~ K x_cam, and image (distorted) pixel coordinates given by OpenCV's
// distortion model with the coefficients `dist` (cv::projectPoints). Image coordinates are
// continuous with pixel centres at integers (OpenCV's). The road axis (the direction vehicles
// travel, default +Y) and the lateral axis road_axis x Z span the road frame of the vehicle
// geometry (models/vehicle_observation.hpp).
//
// The road homography. A road point (X, Y, 0) projects to u ~ K [r1 r2 t] (X, Y, 1)^T, so
// H_road->image = K [r1 r2 t] (r_i the columns of R) maps road points to UNDISTORTED pixels;
// det H = -det K * C_z (C the optical centre), so it is invertible exactly when the camera is off
// the road plane. Image points are undistorted first (cv::undistortPoints, iterated to 1e-12)
// before H^-1 maps them to the road. A pixel whose ray does not point below the horizon (its
// world direction has d_z >= 0) sees no road point: H^-1 would return the point "behind" the
// camera where the backward ray meets Z = 0, so image_to_road refuses it.
#include <string>

#include <Eigen/Core>

namespace vtrack::models {

struct CameraCalibration {
  // Intrinsics [fx 0 cx; 0 fy cy; 0 0 1]. No skew: cv::projectPoints ignores K(0, 1), so a skewed
  // K would make the homography disagree with the projection; it is refused.
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  // OpenCV distortion coefficients (k1, k2, p1, p2[, k3[, k4, k5, k6[, s1..s4[, tx, ty]]]]):
  // 0, 4, 5, 8, 12 or 14 of them; empty or all zero = no distortion.
  Eigen::VectorXd dist;
  // World -> camera rotation (orthonormal, det +1) and translation: x_cam = R X_world + t.
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  // The direction vehicles travel, in the road plane (its Z component must be 0); normalised.
  Eigen::Vector3d road_axis_world = Eigen::Vector3d::UnitY();
  // Image size in pixels, optional (0 x 0 = not given). Not needed by the geometry; kept for
  // callers that check silhouettes against the image border.
  int image_width = 0;
  int image_height = 0;
};

// InvalidArgument naming the key (K, dist, R, t, road_axis_world, image_size) and the problem:
// non-finite numbers; K not of the form above (fx, fy > 0, no skew, last row 0 0 1); a distortion
// vector of another length; R not a rotation (|R^T R - I| > 1e-6, or det R = -1, a reflection;
// a singular R fails the first test); a road axis off the road plane or zero; the optical centre
// at or below the road plane (the homography is then singular or sees the road from below);
// the optical axis at or above the horizon (the camera looks away from the road).
void validate(const CameraCalibration& calibration);

class Camera {
 public:
  // Validates (see validate()) and normalises the road axis.
  explicit Camera(CameraCalibration calibration);

  const CameraCalibration& calibration() const { return calibration_; }
  bool has_distortion() const { return has_distortion_; }
  // Optical centre in world coordinates, C = -R^T t.
  const Eigen::Vector3d& centre() const { return centre_; }
  // Unit road axis (direction of travel), lateral axis road_axis x Z, both in the plane Z = 0.
  const Eigen::Vector3d& road_axis() const { return calibration_.road_axis_world; }
  const Eigen::Vector3d& lateral_axis() const { return lateral_axis_; }

  // H = K [r1 r2 t]: road (X, Y, 1) -> undistorted pixel (homogeneous), and its inverse.
  const Eigen::Matrix3d& road_to_image() const { return road_to_image_; }
  const Eigen::Matrix3d& image_to_road() const { return image_to_road_; }

  // World points (3 x n) -> image pixels (2 x n) with distortion, by cv::projectPoints. A point
  // at or behind the camera's focal plane (z_cam <= 0) has no image: its column is NaN.
  Eigen::Matrix2Xd project(const Eigen::Ref<const Eigen::Matrix3Xd>& world) const;
  // Image pixels (2 x n) -> undistorted pixels (2 x n), the pinhole image K x_cam of the same
  // rays (cv::undistortPoints with P = K, iterated to convergence). Identity without distortion.
  Eigen::Matrix2Xd undistort(const Eigen::Ref<const Eigen::Matrix2Xd>& pixels) const;
  // Unit world directions (3 x n) of the rays from the optical centre through image pixels.
  Eigen::Matrix3Xd rays(const Eigen::Ref<const Eigen::Matrix2Xd>& pixels) const;
  // Where the ray of each image pixel meets the road: world (X, Y) (2 x n), through undistort and
  // H^-1. InvalidArgument naming `what` and the pixel when a ray does not point below the horizon.
  Eigen::Matrix2Xd image_to_road_points(const Eigen::Ref<const Eigen::Matrix2Xd>& pixels,
                                        const char* what = "pixel") const;
  // Road points (X, Y) (2 x n, Z = 0) -> image pixels with distortion (= project with Z = 0).
  Eigen::Matrix2Xd road_to_image_points(const Eigen::Ref<const Eigen::Matrix2Xd>& road) const;

 private:
  CameraCalibration calibration_;
  bool has_distortion_ = false;
  Eigen::Vector3d centre_;
  Eigen::Vector3d lateral_axis_;
  Eigen::Matrix3d road_to_image_;
  Eigen::Matrix3d image_to_road_;
};

// Reads a camera file, YAML or JSON (yaml-cpp reads both), a map with the keys
//   K: 3x3, dist: n (n = 0, 4, 5, 8, 12, 14), R: 3x3, t: 3,
//   road_axis_world: 3 (optional, default [0, 1, 0]), image_size: [width, height] (optional).
// Matrices are lists of rows ([[fx, 0, cx], [0, fy, cy], [0, 0, 1]]), flat row-major lists
// ([fx, 0, cx, 0, fy, cy, 0, 0, 1]) or OpenCV FileStorage matrices ({rows, cols, dt, data}); a
// file written by cv::FileStorage (first line "%YAML:1.0") is read as well. Unknown keys are
// ignored. IoError for a missing or unparsable file; InvalidArgument "camera file PATH: ..."
// naming the key for a missing key, a wrong shape, a value that is not a number, and everything
// validate() refuses.
Camera read_camera_file(const std::string& path);

}  // namespace vtrack::models
