#pragma once
// The vehicle observation geometry and the class prior of particle-filters-human-vehicle.txt §3.1
// and §3.2: a vehicle is a cuboid of width, height and length x = (W, H, L) (metres) standing on
// the road with yaw 0 (its length along the road axis of the Camera).
//
// §3.1, the observation. The vehicle's image silhouette (a polygon, or an image box) is projected
// into the rectified view of the road plane: each vertex is undistorted and mapped by the road
// homography H^-1 (models/camera.hpp). Coordinates in that view are the road frame (lateral,
// along) = (X . lateral_axis, X . road_axis), metres. The observation is the silhouette's bounding
// box there, aligned with the road axis. Seen from the optical centre C, a cuboid's silhouette on
// the road is its "shadow" cast by a point light at C: a point P at height P_z < C_z lands at
// C + (P - C) C_z / (C_z - P_z). So along each road axis, with c the camera's foot coordinate and
// [lo, hi] the box's extent:
//   * c outside [lo, hi] (the usual case): the near edge is the vehicle's near face on the road,
//     the far edge the shadow of its top far edge. The box corner nearest the camera is the
//     reference point X_{t,0} (the paper's "closest point of the quadrilateral to the optical
//     centre"), the opposite corner the far-most corner, and the top far corner of the cuboid,
//     (W, H, L) in the WHL frame at X_{t,0}, lies on the ray through the far-most corner and C.
//   * c inside [lo, hi] (a camera above the vehicle's lane, or looking down on its roof): both
//     edges are shadows of top edges, the extent is e = D C_z / (C_z - H) for the vehicle's
//     dimension D on that axis, so D = e (1 - H / C_z). The paper's construction would add the
//     camera's offset from the near edge to D; instead the optical centre's coordinate on that
//     axis is clamped to 0 (the near edge), which gives exactly D = e (1 - H / C_z) on the line.
//     In this case the line is the locus of dimensions consistent with the box (a line in WHL
//     space), no longer a physical ray.
// The WHL frame (§3.1: "x_t = R_0 X_t - X_{t,0}"): origin X_{t,0}, W along the lateral axis and L
// along the road axis, each pointing from the reference corner to the far-most corner, H = +Z
// (the paper has Y up and Z along the road; R_0 is built from the camera file's road axis rather
// than approximated by the identity). With a = the far-most corner (H = 0) and b = the optical
// centre (clamped as above) in WHL coordinates, the ray is the Plücker matrix L = a b^T - b a^T
// (homogeneous a, b). A volume hypothesis x is projected onto it as y = L pi, pi = (n, -n . x)
// the plane through x whose normal n = a - b is the ray's direction: y is the foot of the
// perpendicular from x to the ray (dehomogenised: L pi's last coordinate is n . (b - a) = -|n|^2,
// never 0). On the line, the dimensions at height h are a + (h / C_z) (b - a).
//
// The likelihood (§3.1): p(z | x) ∝ exp(-(y - x)^T S^-1 (y - x)) in the paper. Choice: the
// standard Gaussian exponent -1/2 (y - x)^T S^-1 (y - x) (the paper's S then being a covariance,
// like Table 1's sigmas), S = diag(sigma_w^2, sigma_h^2, sigma_l^2), unnormalised (the constant
// cancels in every MH ratio and every normalisation over hypotheses; and y - x lies in the 2-D
// plane normal to the ray, so a 3-D normaliser would be wrong anyway). y stays the orthogonal
// projection of the paper, also when S is not isotropic.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/parameters.hpp"
#include "vtrack/models/camera.hpp"

namespace vtrack::models {

// §3.1's likelihood and the silhouette projection.
struct RayLikelihoodParams {
  // S = diag(sigma_w^2, sigma_h^2, sigma_l^2), metres, in the likelihood exponent
  // -1/2 (y - x)^T S^-1 (y - x) (§3.1; "the covariance expresses our confidence about the
  // measurement of the 2D silhouette and the calibration"). The paper gives no value. 0.25 m is
  // the scale of pixel quantisation: on vtrack.synthetic_road's five camera set-ups the true
  // dimensions lie within 0.25 m of the ray of the rendered silhouette's contour in 79-100 % of
  // the views (medians 0.004-0.13 m; benchmarks/vehicle_geometry.py); with 1 px of noise on the
  // outline only 12-61 % do (medians 0.2-0.7 m), so a noisier segmentation needs a larger S.
  double sigma_w = 0.25;
  double sigma_h = 0.25;
  double sigma_l = 0.25;
  // Under lens distortion a straight image edge is not straight on the road: silhouette edges
  // longer than this (pixels) are subdivided before projection. Without distortion the
  // homography maps lines to lines and the vertices alone are exact.
  double max_edge_px = 4.0;

  // Names for config files and Python keywords (core/parameters.hpp).
  static const core::ParameterTable<RayLikelihoodParams>& table();
};
// InvalidArgument naming the parameter: sigmas and max_edge_px must be positive and finite.
void validate(const RayLikelihoodParams& params);

// The silhouette's bounding box in the road frame (metres).
struct RoadBox {
  double lateral_min = 0.0, lateral_max = 0.0;
  double along_min = 0.0, along_max = 0.0;
};

// One frame's observation of one vehicle (§3.1), see the header comment.
struct VehicleObservation {
  Eigen::Matrix2Xd road_polygon;    // the silhouette's (densified) vertices, road frame
  RoadBox box;                      // their bounding box, road frame
  Eigen::Vector3d reference_world;  // X_{t,0}, the box corner nearest the camera (Z = 0)
  Eigen::Vector3d far_corner_world; // the opposite (far-most) corner (Z = 0)
  Eigen::Vector3d w_axis_world;     // unit world directions of the WHL frame's W and L axes
  Eigen::Vector3d l_axis_world;     // (H is +Z)
  bool camera_within_width = false;   // the camera's foot lies within the box's lateral extent
  bool camera_within_length = false;  // ... within its extent along the road
  Eigen::Vector3d a;                // far-most corner in WHL: (box width, 0, box length)
  Eigen::Vector3d b;                // optical centre in WHL, clamped to 0 on "within" axes
  Eigen::Matrix4d plucker;          // L = a b^T - b a^T, a and b homogeneous (w = 1)
  // Metres of road per pixel of the box's extents (width, length): at the two vertices that make
  // each extent (its smallest and largest coordinate), the norm of that road coordinate's row of
  // the image -> road Jacobian, combined as sqrt(r_near^2 + r_far^2). Centimetres near the
  // camera, metres near the horizon; 1e6 within a pixel of the horizon.
  Eigen::Vector2d edge_resolution = Eigen::Vector2d::Zero();

  // World point(s) -> WHL coordinates (3 x n) and back.
  Eigen::Matrix3Xd to_whl(const Eigen::Ref<const Eigen::Matrix3Xd>& world) const;
  Eigen::Matrix3Xd to_world(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const;
  // The dimensions on the line at height h: a + (h / b_H) (b - a).
  Eigen::Vector3d point_at_height(double h) const;
  // The heights h at which every dimension on the line is at least min_size (W, H, L) and h is
  // below the camera (h < b_H): [first, second]; first > second when there is none (§3.1: "there
  // are a number of constraints that bound the solution to a segment of the ray: positive and
  // minimum height, width and length").
  std::pair<double, double> feasible_heights(const Eigen::Vector3d& min_size) const;
};

// The silhouette polygon (2 x n image pixels, n >= 3, finite) in the road frame, edges
// subdivided under distortion. InvalidArgument for a vertex whose ray does not meet the road (a
// silhouette crossing the horizon), NaN, or fewer than 3 vertices.
Eigen::Matrix2Xd silhouette_on_road(const Camera& camera, const Eigen::Ref<const Eigen::Matrix2Xd>& polygon,
                                    double max_edge_px);

// §3.1's observation from a silhouette polygon (2 x n image pixels) or an image box (x, y, w, h:
// the rectangle [x, x + w] x [y, y + h] in continuous pixel coordinates; a box of whole pixels
// i0..i1 is x = i0 - 0.5, w = i1 - i0 + 1). A box is a coarser observation than the silhouette:
// its corners are not on the vehicle, and its road projection is larger than the silhouette's.
VehicleObservation observe_silhouette(const Camera& camera, const Eigen::Ref<const Eigen::Matrix2Xd>& polygon,
                                      const RayLikelihoodParams& params = {});
VehicleObservation observe_box(const Camera& camera, double x, double y, double w, double h,
                               const RayLikelihoodParams& params = {});

// y = L pi for each column x of `whl` (3 x n volume hypotheses (W, H, L)): its projection on the
// observation's ray, 3 x n.
Eigen::Matrix3Xd project_onto_ray(const VehicleObservation& obs, const Eigen::Ref<const Eigen::Matrix3Xd>& whl);
// |y - x| (metres) for each column.
Eigen::VectorXd ray_distance(const VehicleObservation& obs, const Eigen::Ref<const Eigen::Matrix3Xd>& whl);
// log p(z | x) = -1/2 (y - x)^T S^-1 (y - x) for each column (unnormalised, see above).
Eigen::VectorXd ray_log_likelihood(const VehicleObservation& obs, const Eigen::Ref<const Eigen::Matrix3Xd>& whl,
                                   const RayLikelihoodParams& params);

// ---- §3.2, the class mixture prior --------------------------------------------------------------

// One vehicle model of Table 1: N(x; mean, diag(sigma^2)) in WHL space.
struct VehicleModel {
  std::string name;
  Eigen::Vector3d mean;   // (W_m, H_m, L_m), metres
  Eigen::Vector3d sigma;  // (sigma_w, sigma_h, sigma_l), metres (Table 1's columns)
  double weight = 1.0;    // mixture weight (prior frequency), normalised over the classes
  bool heavy = false;     // light/heavy label of the class (the application's two categories)
};

// Table 1 exactly: car, motorbike, truck, trailer, bus, equal weights. Heavy: truck and bus (the
// two with W = 2.0 and H = 2.5); "trailer" (a car's W and H, 7 m long: a car towing a trailer)
// and the others light. Table 1's motorbike has a car's W and H (1.6, 1.5), which real
// motorbikes (W ~0.8 m) do not; kept as the paper's default, configurable from a file.
std::vector<VehicleModel> table1_vehicle_models();

struct VehiclePriorParams {
  std::vector<VehicleModel> models = table1_vehicle_models();
  // §3.1/§3.2's "positive and minimum height, width and length": the prior is 0 (log -inf) below
  // these (metres). The paper gives no values; these are below any road vehicle's (a narrow
  // motorbike is ~0.6 m wide, ~1.0 m high, ~1.7 m long).
  Eigen::Vector3d min_size = Eigen::Vector3d(0.4, 0.6, 1.0);
};
// InvalidArgument naming the class and field: at least one class, names non-empty and distinct,
// means and sigmas finite and positive, weights finite and positive, min_size finite and >= 0.
void validate(const VehiclePriorParams& params);

// p(x | M) = sum_m w_m N(x; x_m, S_m) (§3.2), S_m = diag(sigma_m^2), w_m the normalised weights.
// Choices: the paper writes each term as exp((x - x_m)^T S_m^-1 (x - x_m)), with no sign, no 1/2
// and no normaliser; here each is a proper normalised Gaussian with exponent -1/2 (...), so that
// the class posteriors p(m | x) are meaningful (a broad class does not win by its breadth alone).
// The paper's unnormalised sum of exp(-1/2 ...) is recovered with weights w_m ∝ prod sigma_m.
class VehicleModelPrior {
 public:
  explicit VehicleModelPrior(VehiclePriorParams params = {});
  const VehiclePriorParams& params() const { return params_; }
  int num_models() const { return static_cast<int>(params_.models.size()); }

  // log p(x | M) for each column of a 3 x n matrix of (W, H, L); -inf below min_size.
  Eigen::VectorXd log_density(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const;
  // log w_m N(x; x_m, S_m) for each class (row) and hypothesis (column): num_models x n
  // (not truncated by min_size).
  Eigen::MatrixXd class_log_densities(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const;
  // log p(m | x) = log w_m N_m(x) - log sum_m' w_m' N_m'(x): num_models x n.
  Eigen::MatrixXd class_log_posteriors(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const;
  // The most probable class of each hypothesis (argmax_m p(m | x)).
  std::vector<int> map_class(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const;

 private:
  VehiclePriorParams params_;
  Eigen::Matrix3Xd means_;          // 3 x M
  Eigen::Matrix3Xd inv_sigma_;      // 3 x M, 1 / sigma
  Eigen::VectorXd log_constant_;    // log w_m - 3/2 log(2 pi) - sum log sigma_m
};

// Reads vehicle models (classes) from a YAML or JSON file with a list `models`, each
//   {name: car, W: 1.6, H: 1.5, L: 4.0, sigma_w: 0.1, sigma_h: 0.1, sigma_l: 0.2,
//    weight: 1.0 (optional), heavy: false (optional)}.
// Other top-level keys are ignored; an unknown key inside a model is refused (a misspelt
// `heavy` would silently change the classification). IoError for a missing or unparsable file,
// InvalidArgument "vehicle models file PATH: models[i] (name): ..." for bad entries.
std::vector<VehicleModel> read_vehicle_models_file(const std::string& path);

}  // namespace vtrack::models
