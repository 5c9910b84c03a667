#include "vtrack/models/vehicle_observation.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/weights.hpp"

namespace vtrack::models {

namespace {

using core::kInf;

// Where the camera's foot c stands relative to the box extent [lo, hi] on one road axis (see the
// header): the far edge is the one farther from c; b_coord is the optical centre's coordinate on
// this axis in the WHL frame, measured from the near edge towards the far one (<= 0 when the
// camera is outside the extent), clamped to 0 when c lies inside it.
struct AxisGeometry {
  double near = 0.0, far = 0.0, sign = 1.0, b_coord = 0.0;
  bool within = false;
};

AxisGeometry axis_geometry(double lo, double hi, double c) {
  AxisGeometry g;
  const bool far_is_hi = hi - c >= c - lo;
  g.near = far_is_hi ? lo : hi;
  g.far = far_is_hi ? hi : lo;
  g.sign = far_is_hi ? 1.0 : -1.0;
  g.within = lo < c && c < hi;
  g.b_coord = g.within ? 0.0 : g.sign * (c - g.near);
  return g;
}

// The polygon with every edge (the closing one included) cut into pieces of at most max_edge
// pixels.
Eigen::Matrix2Xd densify(const Eigen::Ref<const Eigen::Matrix2Xd>& polygon, double max_edge) {
  const Eigen::Index n = polygon.cols();
  std::vector<Eigen::Vector2d> points;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d p = polygon.col(i), q = polygon.col((i + 1) % n);
    const int pieces = std::max(1, static_cast<int>(std::ceil((q - p).norm() / max_edge)));
    for (int k = 0; k < pieces; ++k) points.push_back(p + (q - p) * (static_cast<double>(k) / pieces));
  }
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) out.col(static_cast<Eigen::Index>(i)) = points[i];
  return out;
}

}  // namespace

void validate(const RayLikelihoodParams& p) {
  const char* names[] = {"sigma_w", "sigma_h", "sigma_l"};
  const double sigmas[] = {p.sigma_w, p.sigma_h, p.sigma_l};
  for (int k = 0; k < 3; ++k) {
    require(sigmas[k] > 0.0 && std::isfinite(sigmas[k]), names[k], sigmas[k], "a positive finite number (metres)");
  }
  require(p.max_edge_px > 0.0 && std::isfinite(p.max_edge_px), "max_edge_px", p.max_edge_px,
          "a positive finite number (pixels)");
}

const core::ParameterTable<RayLikelihoodParams>& RayLikelihoodParams::table() {
  using P = RayLikelihoodParams;
  static const auto table = core::ParameterTable<P>()
                                .add("sigma_w", &P::sigma_w)
                                .add("sigma_h", &P::sigma_h)
                                .add("sigma_l", &P::sigma_l)
                                .add("max_edge_px", &P::max_edge_px);
  return table;
}

namespace {

// Image points (2 x n) -> road frame (lateral, along), metres.
Eigen::Matrix2Xd to_road_frame(const Camera& camera, const Eigen::Ref<const Eigen::Matrix2Xd>& image) {
  const Eigen::Matrix2Xd world = camera.image_to_road_points(image, "silhouette vertex");
  Eigen::Matrix2Xd road(2, world.cols());
  road.row(0) = camera.lateral_axis().head<2>().transpose() * world;
  road.row(1) = camera.road_axis().head<2>().transpose() * world;
  return road;
}

// The silhouette's (densified) image vertices.
Eigen::Matrix2Xd silhouette_vertices(const Camera& camera, const Eigen::Ref<const Eigen::Matrix2Xd>& polygon,
                                     double max_edge_px) {
  if (polygon.cols() < 3) {
    throw InvalidArgument("silhouette must have at least 3 vertices, got " + std::to_string(polygon.cols()));
  }
  if (!polygon.allFinite()) throw InvalidArgument("silhouette vertices must be finite (got NaN or inf)");
  return camera.has_distortion() ? densify(polygon, max_edge_px) : Eigen::Matrix2Xd(polygon);
}

constexpr double kUnresolved = 1e6;  // metres per pixel where a probe leaves the road (the horizon)

// Metres per pixel of road coordinate `axis` (0 lateral, 1 along) at image point p: the norm of
// that coordinate's gradient in the image (central differences of +-0.25 px).
double metres_per_pixel(const Camera& camera, const Eigen::Vector2d& p, int axis) {
  constexpr double h = 0.25;
  Eigen::Matrix2Xd probes(2, 4);
  probes << p.x() - h, p.x() + h, p.x(), p.x(), p.y(), p.y(), p.y() - h, p.y() + h;
  try {
    const Eigen::Matrix2Xd road = to_road_frame(camera, probes);
    const double du = (road(axis, 1) - road(axis, 0)) / (2 * h), dv = (road(axis, 3) - road(axis, 2)) / (2 * h);
    return std::min(kUnresolved, std::hypot(du, dv));
  } catch (const InvalidArgument&) {
    return kUnresolved;
  }
}

// VehicleObservation::edge_resolution (see the header).
Eigen::Vector2d edge_resolution(const Camera& camera, const Eigen::Matrix2Xd& image, const Eigen::Matrix2Xd& road) {
  Eigen::Vector2d out;
  for (int axis = 0; axis < 2; ++axis) {
    Eigen::Index lo = 0, hi = 0;
    road.row(axis).minCoeff(&lo);
    road.row(axis).maxCoeff(&hi);
    out(axis) = std::min(kUnresolved, std::hypot(metres_per_pixel(camera, image.col(lo), axis),
                                                 metres_per_pixel(camera, image.col(hi), axis)));
  }
  return out;
}

}  // namespace

Eigen::Matrix2Xd silhouette_on_road(const Camera& camera, const Eigen::Ref<const Eigen::Matrix2Xd>& polygon,
                                    double max_edge_px) {
  return to_road_frame(camera, silhouette_vertices(camera, polygon, max_edge_px));
}

VehicleObservation observe_silhouette(const Camera& camera, const Eigen::Ref<const Eigen::Matrix2Xd>& polygon,
                                      const RayLikelihoodParams& params) {
  validate(params);
  VehicleObservation obs;
  const Eigen::Matrix2Xd image = silhouette_vertices(camera, polygon, params.max_edge_px);
  obs.road_polygon = to_road_frame(camera, image);
  obs.edge_resolution = edge_resolution(camera, image, obs.road_polygon);
  const Eigen::Vector2d lo = obs.road_polygon.rowwise().minCoeff();
  const Eigen::Vector2d hi = obs.road_polygon.rowwise().maxCoeff();
  obs.box = {lo(0), hi(0), lo(1), hi(1)};

  const Eigen::Vector3d& C = camera.centre();
  const Eigen::Vector3d& lat = camera.lateral_axis();
  const Eigen::Vector3d& along = camera.road_axis();
  const AxisGeometry w = axis_geometry(lo(0), hi(0), C.dot(lat));
  const AxisGeometry l = axis_geometry(lo(1), hi(1), C.dot(along));
  obs.camera_within_width = w.within;
  obs.camera_within_length = l.within;
  obs.reference_world = w.near * lat + l.near * along;
  obs.far_corner_world = w.far * lat + l.far * along;
  obs.w_axis_world = w.sign * lat;
  obs.l_axis_world = l.sign * along;
  // §3.1: a = the far-most corner, b = the optical centre, both in the WHL frame.
  obs.a = Eigen::Vector3d(hi(0) - lo(0), 0.0, hi(1) - lo(1));
  obs.b = Eigen::Vector3d(w.b_coord, C.z(), l.b_coord);
  const Eigen::Vector4d ah = obs.a.homogeneous(), bh = obs.b.homogeneous();
  obs.plucker = ah * bh.transpose() - bh * ah.transpose();
  return obs;
}

VehicleObservation observe_box(const Camera& camera, double x, double y, double w, double h,
                               const RayLikelihoodParams& params) {
  if (!std::isfinite(x) || !std::isfinite(y) || !(w > 0.0) || !(h > 0.0) || !std::isfinite(w) ||
      !std::isfinite(h)) {
    throw InvalidArgument("box must be finite with w, h > 0, got (" + value_text(x) + ", " + value_text(y) +
                          ", " + value_text(w) + ", " + value_text(h) + ")");
  }
  Eigen::Matrix2Xd corners(2, 4);
  corners << x, x + w, x + w, x, y, y, y + h, y + h;
  return observe_silhouette(camera, corners, params);
}

Eigen::Matrix3Xd VehicleObservation::to_whl(const Eigen::Ref<const Eigen::Matrix3Xd>& world) const {
  const Eigen::Matrix3Xd d = world.colwise() - reference_world;
  Eigen::Matrix3Xd out(3, world.cols());
  out.row(0) = w_axis_world.transpose() * d;
  out.row(1) = d.row(2);
  out.row(2) = l_axis_world.transpose() * d;
  return out;
}

Eigen::Matrix3Xd VehicleObservation::to_world(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const {
  Eigen::Matrix3d axes;
  axes << w_axis_world, Eigen::Vector3d::UnitZ(), l_axis_world;
  return (axes * whl).colwise() + reference_world;
}

Eigen::Vector3d VehicleObservation::point_at_height(double h) const { return a + (h / b.y()) * (b - a); }

std::pair<double, double> VehicleObservation::feasible_heights(const Eigen::Vector3d& min_size) const {
  // Each dimension is linear in h on the line: d_k(h) = a_k + h s_k, s_k = (b_k - a_k) / b_H.
  double first = -kInf, second = b.y();
  for (int k = 0; k < 3; ++k) {
    const double s = (b(k) - a(k)) / b.y();
    const double bound = s != 0.0 ? (min_size(k) - a(k)) / s : 0.0;
    if (s > 0.0) {
      first = std::max(first, bound);
    } else if (s < 0.0) {
      second = std::min(second, bound);
    } else if (a(k) < min_size(k)) {
      return {kInf, -kInf};
    }
  }
  return {first, second};
}

Eigen::Matrix3Xd project_onto_ray(const VehicleObservation& obs, const Eigen::Ref<const Eigen::Matrix3Xd>& whl) {
  // §3.1: pi_t = (n, D) with n the ray's direction and D = -n . x_t; y_t = L_t pi_t.
  const Eigen::Vector3d n = obs.a - obs.b;
  Eigen::Matrix4Xd pi(4, whl.cols());
  pi.topRows<3>().colwise() = n;
  pi.row(3) = -n.transpose() * whl;
  const Eigen::Matrix4Xd y = obs.plucker * pi;
  return y.topRows<3>().array().rowwise() / y.row(3).array();
}

Eigen::VectorXd ray_distance(const VehicleObservation& obs, const Eigen::Ref<const Eigen::Matrix3Xd>& whl) {
  return (project_onto_ray(obs, whl) - whl).colwise().norm().transpose();
}

Eigen::VectorXd ray_log_likelihood(const VehicleObservation& obs, const Eigen::Ref<const Eigen::Matrix3Xd>& whl,
                                   const RayLikelihoodParams& params) {
  validate(params);
  const Eigen::Array3d inv_sigma(1.0 / params.sigma_w, 1.0 / params.sigma_h, 1.0 / params.sigma_l);
  const Eigen::Array3Xd r = (project_onto_ray(obs, whl) - whl).array().colwise() * inv_sigma;
  return -0.5 * r.square().colwise().sum().transpose().matrix();
}

// ---- §3.2 -----------------------------------------------------------------------------------------

std::vector<VehicleModel> table1_vehicle_models() {
  return {
      {"car", {1.6, 1.5, 4.0}, {0.1, 0.1, 0.2}, 1.0, false},
      {"motorbike", {1.6, 1.5, 2.0}, {0.1, 0.1, 0.2}, 1.0, false},
      {"truck", {2.0, 2.5, 7.0}, {0.2, 0.3, 1.0}, 1.0, true},
      {"trailer", {1.6, 1.5, 7.0}, {0.1, 0.1, 2.0}, 1.0, false},
      {"bus", {2.0, 2.5, 10.0}, {0.2, 0.3, 1.0}, 1.0, true},
  };
}

void validate(const VehiclePriorParams& p) {
  if (p.models.empty()) throw InvalidArgument("models must hold at least one vehicle model");
  std::set<std::string> names;
  for (std::size_t i = 0; i < p.models.size(); ++i) {
    const VehicleModel& c = p.models[i];
    const std::string where = "models[" + std::to_string(i) + "] (" + c.name + ")";
    if (c.name.empty()) throw InvalidArgument(where + ": name must not be empty");
    if (!names.insert(c.name).second) throw InvalidArgument(where + ": name appears twice");
    const char* fields[] = {"W", "H", "L", "sigma_w", "sigma_h", "sigma_l"};
    for (int k = 0; k < 6; ++k) {
      const double v = k < 3 ? c.mean(k) : c.sigma(k - 3);
      if (!(v > 0.0) || !std::isfinite(v)) {
        throw InvalidArgument(where + ": " + fields[k] + " must be a positive finite number (metres), got " +
                              value_text(v));
      }
    }
    if (!(c.weight > 0.0) || !std::isfinite(c.weight)) {
      throw InvalidArgument(where + ": weight must be a positive finite number, got " + value_text(c.weight));
    }
  }
  for (int k = 0; k < 3; ++k) {
    require(p.min_size(k) >= 0.0 && std::isfinite(p.min_size(k)), "min_size", p.min_size(k),
            "three finite numbers >= 0 (W, H, L metres)");
  }
}

VehicleModelPrior::VehicleModelPrior(VehiclePriorParams params) : params_(std::move(params)) {
  validate(params_);
  const auto m = static_cast<Eigen::Index>(params_.models.size());
  means_.resize(3, m);
  inv_sigma_.resize(3, m);
  log_constant_.resize(m);
  double total_weight = 0.0;
  for (const auto& c : params_.models) total_weight += c.weight;
  for (Eigen::Index i = 0; i < m; ++i) {
    const VehicleModel& c = params_.models[static_cast<std::size_t>(i)];
    means_.col(i) = c.mean;
    inv_sigma_.col(i) = c.sigma.cwiseInverse();
    log_constant_(i) = std::log(c.weight / total_weight) - 1.5 * std::log(2.0 * M_PI) -
                       c.sigma.array().log().sum();
  }
}

Eigen::MatrixXd VehicleModelPrior::class_log_densities(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const {
  // Row by row over the hypotheses, so every operation runs over n contiguous values (vectorised).
  Eigen::MatrixXd out(means_.cols(), whl.cols());
  for (Eigen::Index m = 0; m < means_.cols(); ++m) {
    Eigen::ArrayXd q = Eigen::ArrayXd::Zero(whl.cols());
    for (int k = 0; k < 3; ++k) {
      q += ((whl.row(k).array().transpose() - means_(k, m)) * inv_sigma_(k, m)).square();
    }
    out.row(m) = (log_constant_(m) - 0.5 * q).matrix().transpose();
  }
  return out;
}

namespace {
// Column-wise log-sum-exp of a matrix (rows = models), vectorised over the columns. Columns whose
// maximum is not finite (never for finite hypotheses) keep that maximum.
Eigen::RowVectorXd column_log_sum_exp(const Eigen::MatrixXd& d) {
  const Eigen::Array<double, 1, Eigen::Dynamic> top = d.colwise().maxCoeff().array();
  const Eigen::Array<double, 1, Eigen::Dynamic> sum = (d.array().rowwise() - top).exp().colwise().sum();
  return (top.isFinite()).select(top + sum.log(), top).matrix();
}
}  // namespace

Eigen::VectorXd VehicleModelPrior::log_density(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const {
  Eigen::VectorXd out = column_log_sum_exp(class_log_densities(whl)).transpose();
  // Below the minimum size in any dimension: outside the prior's support.
  const auto below = ((whl.array().colwise() - params_.min_size.array()) < 0.0).colwise().any();
  return below.transpose().select(-kInf, out.array()).matrix();
}

Eigen::MatrixXd VehicleModelPrior::class_log_posteriors(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const {
  const Eigen::MatrixXd d = class_log_densities(whl);
  return d.rowwise() - column_log_sum_exp(d);
}

std::vector<int> VehicleModelPrior::map_class(const Eigen::Ref<const Eigen::Matrix3Xd>& whl) const {
  const Eigen::MatrixXd d = class_log_densities(whl);
  std::vector<int> out(static_cast<std::size_t>(whl.cols()));
  for (Eigen::Index j = 0; j < whl.cols(); ++j) {
    Eigen::Index best = 0;
    d.col(j).maxCoeff(&best);
    out[static_cast<std::size_t>(j)] = static_cast<int>(best);
  }
  return out;
}

}  // namespace vtrack::models
