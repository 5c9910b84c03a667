// Bindings of the vehicle geometry (particle-filters-human-vehicle §3.1-3.2): the road camera, the
// ray observation of a vehicle's silhouette, the class mixture prior. Conversion only.
#include <algorithm>
#include <climits>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "args.hpp"
#include "common.hpp"
#include "params.hpp"
#include "guard.hpp"
#include "tracks.hpp"
#include "vtrack/apps/output_paths.hpp"
#include "vtrack/apps/vehicles.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/filters/vehicle_dimensions.hpp"
#include "vtrack/models/camera.hpp"
#include "vtrack/models/vehicle_observation.hpp"

namespace vtrack::bindings {

namespace {

using models::Camera;
using models::VehicleModel;
using models::VehicleObservation;

// An (N, Dim) float64 array, checked; columns() is its Dim x N column-major view (a C-contiguous
// N x Dim array is the column-major Dim x N matrix).
template <int Dim>
struct PointRows {
  py::array_t<double> keep;
  Eigen::Map<const Eigen::Matrix<double, Dim, Eigen::Dynamic>> columns() const {
    return {keep.data(), Dim, static_cast<Eigen::Index>(keep.shape(0))};
  }
};

template <int Dim>
PointRows<Dim> point_rows(const py::handle& obj, const char* name) {
  PointRows<Dim> p{as_matrix(obj, name)};
  if (p.keep.shape(1) != Dim) {
    throw py::value_error(std::string(name) + " must have shape (N, " + std::to_string(Dim) + "), got (" +
                          std::to_string(p.keep.shape(0)) + ", " + std::to_string(p.keep.shape(1)) + ")");
  }
  return p;
}

// dim x N Eigen -> (N, dim) NumPy.
Eigen::MatrixXd rows_of(const Eigen::MatrixXd& columns) { return columns.transpose(); }

// Binds a method that maps points given as rows (N, InDim) to points as rows: `f(self, columns)`
// works on the InDim x N column view and returns a Dim x N matrix.
template <int InDim, typename Class, typename F>
void def_rows(py::class_<Class>& cls, const char* name, const char* arg, F f, const char* doc) {
  cls.def(
      name,
      [f, arg](const Class& self, const py::handle& x) {
        const auto p = point_rows<InDim>(x, arg);
        return rows_of(f(self, p.columns()));
      },
      py::arg(arg), doc);
}

py::dict model_to_dict(const VehicleModel& m) {
  py::dict d;
  d["name"] = m.name;
  d["W"] = m.mean(0);
  d["H"] = m.mean(1);
  d["L"] = m.mean(2);
  d["sigma_w"] = m.sigma(0);
  d["sigma_h"] = m.sigma(1);
  d["sigma_l"] = m.sigma(2);
  d["weight"] = m.weight;
  d["heavy"] = m.heavy;
  return d;
}

VehicleModel model_from_dict(const py::handle& obj, std::size_t i) {
  const std::string where = "models[" + std::to_string(i) + "]";
  if (!py::isinstance<py::dict>(obj)) throw py::type_error(where + " must be a dict, got " + type_name(obj));
  const auto d = py::reinterpret_borrow<py::dict>(obj);
  for (const auto& kv : d) {
    const std::string key = py::str(kv.first);
    static const char* known[] = {"name", "W", "H", "L", "sigma_w", "sigma_h", "sigma_l", "weight", "heavy"};
    if (std::find(std::begin(known), std::end(known), key) == std::end(known)) {
      throw py::value_error(where + ": unknown key '" + key + "'");
    }
  }
  auto get = [&](const char* key) -> py::object {
    if (!d.contains(key)) throw py::value_error(where + ": missing key '" + key + "'");
    return d[key];
  };
  auto real = [&](const char* key) {
    return std::get<double>(
        parameter_from_python(where + "." + key, core::ParameterKind::real, 0, get(key)));
  };
  VehicleModel m;
  const py::object name = get("name");
  if (!py::isinstance<py::str>(name)) throw py::type_error(where + ".name must be a str, got " + type_name(name));
  m.name = name.cast<std::string>();
  m.mean << real("W"), real("H"), real("L");
  m.sigma << real("sigma_w"), real("sigma_h"), real("sigma_l");
  if (d.contains("weight")) m.weight = real("weight");
  if (d.contains("heavy")) {
    m.heavy = std::get<bool>(
        parameter_from_python(where + ".heavy", core::ParameterKind::flag, 0, d["heavy"]));
  }
  return m;
}

py::list models_to_list(const std::vector<VehicleModel>& models) {
  py::list out;
  for (const auto& m : models) out.append(model_to_dict(m));
  return out;
}

VehicleObservation observe(const Camera& camera, const py::handle& silhouette, double max_edge_px) {
  models::RayLikelihoodParams params;
  params.max_edge_px = max_edge_px;
  py::array a = py::array::ensure(silhouette);
  if (a && a.ndim() == 1) {
    auto box = as_vector(silhouette, "silhouette");
    if (box.size() != 4) throw py::value_error("silhouette as a box must be (x, y, w, h)");
    const double* b = box.data();
    py::gil_scoped_release release;
    return models::observe_box(camera, b[0], b[1], b[2], b[3], params);
  }
  const auto poly = point_rows<2>(silhouette, "silhouette");
  py::gil_scoped_release release;
  return models::observe_silhouette(camera, poly.columns(), params);
}

void bind_camera(py::module_& m) {
  py::class_<Camera> camera(m, "Camera", R"doc(
A calibrated camera over a road, OpenCV conventions (particle-filters-human-vehicle §3.1).

World in metres, Z up, road plane Z = 0; x_cam = R X_world + t; K = [[fx, 0, cx], [0, fy, cy],
[0, 0, 1]] (no skew); dist = OpenCV distortion coefficients (0, 4, 5, 8, 12 or 14 of them);
road_axis_world = the direction vehicles travel (in the road plane, default +Y); image_size =
(width, height) or None. Image coordinates are continuous, pixel centres at integers. Invalid
calibrations (R not a rotation, camera at or below the road, looking away from the road, ...)
raise vtrack.InvalidArgument naming the key. See read_camera_file for the file format.
)doc");
  camera
      .def(py::init([](const py::handle& K, const py::handle& dist, const py::handle& R, const py::handle& t,
                       const py::handle& road_axis_world, std::optional<std::pair<int, int>> image_size) {
             models::CameraCalibration c;
             auto k = as_matrix(K, "K");
             auto r = as_matrix(R, "R");
             if (k.shape(0) != 3 || k.shape(1) != 3) throw py::value_error("K must have shape (3, 3)");
             if (r.shape(0) != 3 || r.shape(1) != 3) throw py::value_error("R must have shape (3, 3)");
             c.K = matrix_map(k);
             c.R = matrix_map(r);
             c.dist = vector_map(as_vector(dist, "dist"));
             auto tv = as_vector(t, "t");
             auto axis = as_vector(road_axis_world, "road_axis_world");
             if (tv.size() != 3) throw py::value_error("t must have 3 elements");
             if (axis.size() != 3) throw py::value_error("road_axis_world must have 3 elements");
             c.t = vector_map(tv);
             c.road_axis_world = vector_map(axis);
             if (image_size) std::tie(c.image_width, c.image_height) = *image_size;
             return Camera(c);
           }),
           py::arg("K"), py::arg("dist"), py::arg("R"), py::arg("t"), py::kw_only(),
           py::arg("road_axis_world") = std::vector<double>{0.0, 1.0, 0.0}, py::arg("image_size") = py::none())
      .def_property_readonly("K", [](const Camera& c) { return c.calibration().K; })
      .def_property_readonly("dist", [](const Camera& c) { return c.calibration().dist; })
      .def_property_readonly("R", [](const Camera& c) { return c.calibration().R; })
      .def_property_readonly("t", [](const Camera& c) { return c.calibration().t; })
      .def_property_readonly("image_size",
                             [](const Camera& c) -> std::optional<std::pair<int, int>> {
                               if (c.calibration().image_width == 0) return std::nullopt;
                               return std::make_pair(c.calibration().image_width, c.calibration().image_height);
                             })
      .def_property_readonly("has_distortion", &Camera::has_distortion)
      .def_property_readonly("centre", &Camera::centre, "Optical centre in world coordinates, -R^T t.")
      .def_property_readonly("road_axis", &Camera::road_axis, "Unit direction of travel (world).")
      .def_property_readonly("lateral_axis", &Camera::lateral_axis, "road_axis x Z (world), the W direction.")
      .def_property_readonly("road_to_image_homography", &Camera::road_to_image,
                             "H = K [r1 r2 t]: road (X, Y, 1) -> undistorted pixel, homogeneous.")
      .def_property_readonly("image_to_road_homography", &Camera::image_to_road, "H^-1.")
      .def("__repr__", [](const Camera& c) {
        const Eigen::Vector3d& C = c.centre();
        return "Camera(centre=(" + std::to_string(C.x()) + ", " + std::to_string(C.y()) + ", " +
               std::to_string(C.z()) + "), fx=" + std::to_string(c.calibration().K(0, 0)) + ")";
      });
  def_rows<3>(camera, "project", "points", [](const Camera& c, const auto& x) { return c.project(x); },
              "World points (N, 3) -> image pixels (N, 2) with distortion (cv::projectPoints); NaN rows for "
              "points at or behind the camera's focal plane.");
  def_rows<2>(camera, "undistort", "pixels", [](const Camera& c, const auto& x) { return c.undistort(x); },
              "Image pixels (N, 2) -> undistorted (pinhole) pixels (N, 2).");
  def_rows<2>(camera, "rays", "pixels", [](const Camera& c, const auto& x) { return c.rays(x); },
              "Unit world directions (N, 3) of the rays from the optical centre through pixels (N, 2).");
  def_rows<2>(camera, "image_to_road", "pixels",
              [](const Camera& c, const auto& x) { return c.image_to_road_points(x); },
              "Where the rays of image pixels (N, 2) meet the road: world (X, Y) (N, 2). InvalidArgument for "
              "a pixel at or above the horizon.");
  def_rows<2>(camera, "road_to_image", "road",
              [](const Camera& c, const auto& x) { return c.road_to_image_points(x); },
              "Road points (N, 2) world (X, Y), Z = 0 -> image pixels (N, 2) with distortion.");

  m.def(
      "read_camera_file",
      [](const py::handle& path) { return models::read_camera_file(path_arg(path, "path")); },
      py::arg("path"), R"doc(
Read a camera file (YAML or JSON): K (3x3), dist (OpenCV coefficients, [] or zeros for none),
R (3x3), t (3) with x_cam = R X_world + t; optional road_axis_world (3, default [0, 1, 0]) and
image_size ([width, height]); unknown keys are ignored. Matrices as lists of rows, flat
row-major lists, or OpenCV FileStorage matrices (files written by cv::FileStorage are read).
vtrack.IoError for a missing or unparsable file, vtrack.InvalidArgument naming the file, the key
and the problem otherwise.
)doc");
}

void bind_observation(py::module_& m) {
  const models::RayLikelihoodParams defaults;
  py::class_<VehicleObservation> observation(m, "VehicleObservation", R"doc(
One frame's observation of one vehicle (particle-filters-human-vehicle §3.1), from
observe_vehicle: the silhouette in the road frame (lateral, along), its bounding box there, the
reference point X_0 (the box corner nearest the camera, origin of the vehicle's W-H-L frame), the
far-most corner, and the ray through the far-most corner a and the optical centre b as the
Plücker matrix L = a b^T - b a^T (a, b in W-H-L coordinates). Hypotheses are rows (W, H, L).
When the camera's foot lies within the box's extent along an axis, b's coordinate on that axis is
clamped to 0 and the "ray" is the line of dimensions consistent with the box (see
cpp/include/vtrack/models/vehicle_observation.hpp).
)doc");
  observation
      .def_property_readonly("road_polygon", [](const VehicleObservation& o) { return rows_of(o.road_polygon); },
                             "The silhouette's vertices in the road frame (N, 2): (lateral, along), metres.")
      .def_property_readonly("box",
                             [](const VehicleObservation& o) {
                               return py::make_tuple(o.box.lateral_min, o.box.lateral_max, o.box.along_min,
                                                     o.box.along_max);
                             },
                             "(lateral_min, lateral_max, along_min, along_max), road frame, metres.")
      .def_readonly("reference_world", &VehicleObservation::reference_world)
      .def_readonly("far_corner_world", &VehicleObservation::far_corner_world)
      .def_readonly("w_axis_world", &VehicleObservation::w_axis_world)
      .def_readonly("l_axis_world", &VehicleObservation::l_axis_world)
      .def_readonly("camera_within_width", &VehicleObservation::camera_within_width)
      .def_readonly("camera_within_length", &VehicleObservation::camera_within_length)
      .def_readonly("a", &VehicleObservation::a, "The far-most corner in W-H-L coordinates (H = 0).")
      .def_readonly("b", &VehicleObservation::b, "The optical centre in W-H-L coordinates (clamped, see above).")
      .def_readonly("plucker", &VehicleObservation::plucker, "L = a b^T - b a^T (4 x 4, a and b homogeneous).")
      .def("point_at_height", &VehicleObservation::point_at_height, py::arg("h"),
           "The dimensions (W, H, L) on the line at height h.")
      .def(
          "feasible_heights",
          [](const VehicleObservation& o, const py::handle& min_size) {
            auto s = as_vector(min_size, "min_size");
            if (s.size() != 3) throw py::value_error("min_size must be (W, H, L)");
            return o.feasible_heights(vector_map(s));
          },
          py::arg("min_size"),
          "(h0, h1): the heights where every dimension on the line is >= min_size and h is below the camera; "
          "h0 > h1 when there is none.")
      .def(
          "distance",
          [](const VehicleObservation& o, const py::handle& whl) {
            const auto p = point_rows<3>(whl, "whl");
            return Eigen::VectorXd(models::ray_distance(o, p.columns()));
          },
          py::arg("whl"), "|y - x| (metres) for each hypothesis row.")
      .def(
          "log_likelihood",
          [](const VehicleObservation& o, const py::handle& whl, double sigma_w, double sigma_h, double sigma_l) {
            const auto p = point_rows<3>(whl, "whl");
            models::RayLikelihoodParams params;
            params.sigma_w = sigma_w;
            params.sigma_h = sigma_h;
            params.sigma_l = sigma_l;
            py::gil_scoped_release release;
            return Eigen::VectorXd(models::ray_log_likelihood(o, p.columns(), params));
          },
          py::arg("whl"), py::kw_only(), py::arg("sigma_w") = defaults.sigma_w, py::arg("sigma_h") = defaults.sigma_h,
          py::arg("sigma_l") = defaults.sigma_l,
          "log p(z | x) = -1/2 (y - x)^T S^-1 (y - x), S = diag(sigma^2) (unnormalised), per hypothesis row.");
  using Obs = VehicleObservation;
  def_rows<3>(observation, "to_whl", "world", [](const Obs& o, const auto& x) { return o.to_whl(x); },
              "World points (N, 3) -> W-H-L coordinates (N, 3).");
  def_rows<3>(observation, "to_world", "whl", [](const Obs& o, const auto& x) { return o.to_world(x); },
              "W-H-L coordinates (N, 3) -> world points (N, 3).");
  def_rows<3>(observation, "project", "whl", [](const Obs& o, const auto& x) { return models::project_onto_ray(o, x); },
              "y = L pi for each hypothesis row (W, H, L): its projection on the ray (N, 3).");

  m.def("observe_vehicle", &observe, py::arg("camera"), py::arg("silhouette"), py::kw_only(),
        py::arg("max_edge_px") = defaults.max_edge_px, R"doc(
The §3.1 observation of a vehicle: `silhouette` is an image polygon (N, 2), N >= 3, or an image
box (x, y, w, h) = the rectangle [x, x + w] x [y, y + h] in continuous pixel coordinates (a box
of whole pixels i0..i1 has x = i0 - 0.5, w = i1 - i0 + 1). Under lens distortion, edges longer
than max_edge_px are subdivided before projection. vtrack.InvalidArgument for a silhouette that
crosses the horizon, NaN, or w, h <= 0.
)doc");
}

void bind_prior(py::module_& m) {
  m.def("table1_vehicle_models", [] { return models_to_list(models::table1_vehicle_models()); }, R"doc(
The vehicle models of particle-filters-human-vehicle Table 1 (car, motorbike, truck, trailer,
bus) as dicts {name, W, H, L, sigma_w, sigma_h, sigma_l, weight, heavy}; truck and bus heavy.
)doc");
  m.def(
      "read_vehicle_models_file",
      [](const py::handle& path) {
        return models_to_list(models::read_vehicle_models_file(path_arg(path, "path")));
      },
      py::arg("path"), R"doc(
Read vehicle models from a YAML/JSON file with a list `models` of
{name, W, H, L, sigma_w, sigma_h, sigma_l, weight (optional, 1), heavy (optional, false)}.
)doc");

  const models::VehiclePriorParams defaults;
  py::class_<models::VehicleModelPrior>(m, "VehicleModelPrior", R"doc(
The class mixture prior of particle-filters-human-vehicle §3.2: p(x | M) = sum_m w_m N(x; x_m, S_m)
over vehicle models (default Table 1), S_m = diag(sigma_m^2), w_m the normalised weights; each
term a normalised Gaussian (the paper's unnormalised terms are weights w_m ∝ prod sigma_m), and 0
below min_size = (W, H, L) metres. Hypotheses are rows (W, H, L).
)doc")
      .def(py::init([](const std::optional<py::list>& model_list, const py::handle& min_size) {
             models::VehiclePriorParams p;
             if (model_list) {
               p.models.clear();
               for (std::size_t i = 0; i < model_list->size(); ++i) p.models.push_back(model_from_dict((*model_list)[i], i));
             }
             auto s = as_vector(min_size, "min_size");
             if (s.size() != 3) throw py::value_error("min_size must be (W, H, L)");
             p.min_size = vector_map(s);
             return models::VehicleModelPrior(p);
           }),
           py::arg("models") = py::none(), py::kw_only(),
           py::arg("min_size") = std::vector<double>(defaults.min_size.data(), defaults.min_size.data() + 3))
      .def_property_readonly("models", [](const models::VehicleModelPrior& p) { return models_to_list(p.params().models); })
      .def_property_readonly("names",
                             [](const models::VehicleModelPrior& p) {
                               std::vector<std::string> n;
                               for (const auto& c : p.params().models) n.push_back(c.name);
                               return n;
                             })
      .def_property_readonly("min_size", [](const models::VehicleModelPrior& p) { return p.params().min_size; })
      .def(
          "log_density",
          [](const models::VehicleModelPrior& p, const py::handle& whl) {
            const auto x = point_rows<3>(whl, "whl");
            py::gil_scoped_release release;
            return Eigen::VectorXd(p.log_density(x.columns()));
          },
          py::arg("whl"), "log p(x | M) per hypothesis row (W, H, L); -inf below min_size.")
      .def(
          "class_log_posteriors",
          [](const models::VehicleModelPrior& p, const py::handle& whl) {
            const auto x = point_rows<3>(whl, "whl");
            py::gil_scoped_release release;
            return Eigen::MatrixXd(p.class_log_posteriors(x.columns()).transpose());
          },
          py::arg("whl"), "log p(m | x), (N, number of models).")
      .def(
          "map_class",
          [](const models::VehicleModelPrior& p, const py::handle& whl) {
            const auto x = point_rows<3>(whl, "whl");
            const std::vector<int> c = p.map_class(x.columns());
            return py::array_t<int>(static_cast<py::ssize_t>(c.size()), c.data());
          },
          py::arg("whl"), "Index of the most probable model per hypothesis row, (N,) int.");
}

using filters::VehicleDimensionEstimator;
using filters::VehicleEstimate;

// `models`: None (Table 1), a list of dicts, or a models file path.
std::vector<VehicleModel> models_arg(const py::handle& models) {
  std::vector<VehicleModel> out;
  if (models.is_none()) return out;
  if (py::isinstance<py::list>(models) || py::isinstance<py::tuple>(models)) {
    const auto seq = py::reinterpret_borrow<py::sequence>(models);
    for (std::size_t i = 0; i < seq.size(); ++i) out.push_back(model_from_dict(seq[i], i));
    if (out.empty()) throw py::value_error("models must not be empty");
    return out;
  }
  return models::read_vehicle_models_file(path_arg(models, "models"));
}

py::dict estimate_dict(const VehicleEstimate& e) {
  py::dict d;
  d["vehicle_id"] = e.vehicle_id;
  d["valid"] = e.valid;
  d["class"] = e.valid ? py::object(py::str(e.class_name)) : py::object(py::str("not_fully_in_view"));
  d["light_heavy"] = e.valid ? (e.heavy ? "heavy" : "light") : "unknown";
  d["W"] = e.dimensions(0);
  d["H"] = e.dimensions(1);
  d["L"] = e.dimensions(2);
  d["first_frame"] = e.first_frame;
  d["last_frame"] = e.last_frame;
  d["frames_seen"] = e.frames_seen;
  d["frames_used"] = e.frames_used;
  d["class_probability"] = e.valid ? py::object(py::cast(Eigen::VectorXd(e.class_probability))) : py::none();
  return d;
}

py::list estimates_list(const std::vector<VehicleEstimate>& estimates) {
  py::list out;
  for (const auto& e : estimates) out.append(estimate_dict(e));
  return out;
}

int vehicle_id_arg(const py::handle& id) { return static_cast<int>(int_arg(id, "vehicle_id", 0, INT_MAX)); }

bool update(VehicleDimensionEstimator& est, const py::handle& id_arg, const py::handle& silhouette,
            const py::handle& frame_arg) {
  ObjectGuard guard(&est);
  const int id = vehicle_id_arg(id_arg);
  const int frame = frame_arg.is_none() ? est.next_frame(id) : static_cast<int>(int_arg(frame_arg, "frame", 1, INT_MAX));
  py::array a = py::array::ensure(silhouette);
  if (a && a.ndim() == 1) {
    auto box = as_vector(silhouette, "silhouette");
    if (box.size() != 4) throw py::value_error("silhouette as a box must be (x, y, w, h)");
    const double* b = box.data();
    py::gil_scoped_release release;
    return est.update_box(id, frame, b[0], b[1], b[2], b[3]);
  }
  const auto poly = point_rows<2>(silhouette, "silhouette");
  py::gil_scoped_release release;
  return est.update_polygon(id, frame, poly.columns());
}

void bind_estimator(py::module_& m) {
  py::class_<VehicleDimensionEstimator> est(m, "VehicleDimensionEstimator", R"doc(
Per-vehicle width, height, length and class from its silhouettes in a calibrated road camera
(particle-filters-human-vehicle §3; cpp/include/vtrack/filters/vehicle_dimensions.hpp).

VehicleDimensionEstimator(camera, *, models=None, **params): models None (Table 1), a list of
dicts as table1_vehicle_models() returns, or a models file path. params (default_params()):
sampler "rays" (beyond the paper, the default: the exact rigid posterior given every frame's ray),
"ray" (§3.3's samples on the ray), "mh" (MH in W-H-L space) or "discrete" (the projected class
models);
reference "map" | "mean" | "random" (x*) | "all" (the full acceptance ratio); n_particles,
burn_in, thinning; proposal_scale and dynamic_sigma (metres); min_size (W, H, L); sigma_w,
sigma_h, sigma_l (S of §3.1) and max_edge_px; light_heavy_rule "volume" (W H L >=
heavy_volume m^3, or H >= heavy_height m when > 0) | "class" (the MAP class's heavy flag); decision "auto" (last for rays, else
mean) | "mean" (over the frames used) | "last"; border_margin_px; seed.

update(vehicle_id, silhouette, frame=None) takes an image polygon (N, 2) or box (x, y, w, h) and
returns whether the frame was used (not cut by the image border, a feasible ray); frame defaults
to the vehicle's previous frame + 1. estimates() lists a dict per vehicle: vehicle_id, valid,
class, light_heavy, W, H, L, first_frame, last_frame, frames_seen, frames_used,
class_probability (a vehicle never fully in view: class "not_fully_in_view", light_heavy
"unknown", NaN dimensions). The same seed gives the same estimates, whatever the order in which
vehicles are updated.
)doc");
  est.def(py::init([](const Camera& camera, const py::handle& models, const py::kwargs& kwargs) {
            auto params = params_from_kwargs<filters::VehicleEstimatorParams>(kwargs, "vehicle estimator");
            auto list = models_arg(models);
            return VehicleDimensionEstimator(camera, std::move(list), params);
          }),
          py::arg("camera"), py::kw_only(), py::arg("models") = py::none())
      .def("update", &update, py::arg("vehicle_id"), py::arg("silhouette"), py::arg("frame") = py::none(),
           "Add one frame's silhouette of a vehicle; True when the frame was used.")
      .def(
          "estimate",
          [](const VehicleDimensionEstimator& e, const py::handle& id) {
            ObjectGuard guard(&e);
            return estimate_dict(e.estimate(vehicle_id_arg(id)));
          },
          py::arg("vehicle_id"), "The dict of one vehicle (see the class).")
      .def(
          "estimates",
          [](const VehicleDimensionEstimator& e) {
            ObjectGuard guard(&e);
            return estimates_list(e.estimates());
          },
          "One dict per vehicle, by id (see the class).")
      .def(
          "posterior",
          [](const VehicleDimensionEstimator& e, const py::handle& id) -> py::object {
            ObjectGuard guard(&e);
            const auto* p = e.posterior(vehicle_id_arg(id));
            if (p == nullptr) return py::none();
            py::dict d;
            d["samples"] = Eigen::MatrixXd(p->samples);
            d["log_target"] = Eigen::VectorXd(p->log_target);
            d["mean"] = Eigen::Vector3d(p->mean);
            d["map"] = Eigen::Vector3d(p->map);
            d["class_probability"] = Eigen::VectorXd(p->class_probability);
            d["acceptance_rate"] = p->acceptance_rate;
            return std::move(d);
          },
          py::arg("vehicle_id"),
          "The last used frame's posterior: samples (N_s, 3), log_target, mean, map, class_probability, "
          "acceptance_rate; None before any used frame.")
      .def_property_readonly("models",
                             [](const VehicleDimensionEstimator& e) { return models_to_list(e.prior().params().models); })
      .def_property_readonly("camera", [](const VehicleDimensionEstimator& e) { return e.camera(); });
  def_params<filters::VehicleEstimatorParams>(
      est, [](const VehicleDimensionEstimator& e) { return e.params(); });

  m.def(
      "_estimate_vehicles_from_file",
      [](const py::handle& observations, const Camera& camera, const py::handle& models, const py::dict& params,
         const py::handle& out) {
        const std::string path = path_arg(observations, "observations");
        const std::string out_path = out.is_none() ? "" : path_arg(out, "out");
        auto p = params_from_kwargs<filters::VehicleEstimatorParams>(params, "vehicle estimator");
        VehicleDimensionEstimator est(camera, models_arg(models), p);
        std::vector<VehicleEstimate> result;
        {
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          if (!out_path.empty()) apps::check_outputs({{"observations", path}}, {{"out", out_path}});
          result = apps::estimate_vehicles(est, apps::read_vehicle_observations(path));
          if (!out_path.empty()) apps::write_vehicles_csv(out_path, result);
        }
        return estimates_list(result);
      },
      py::arg("observations"), py::arg("camera"), py::arg("models"), py::arg("params"), py::arg("out"),
      "The compiled half of vtrack.vehicles.estimate_vehicles (use that).");
}

// Sets `name` in the table of `params` when it has it.
template <class Params>
bool set_in(Params& params, const std::string& name, const py::handle& value) {
  const auto* e = Params::table().find(name);
  if (e == nullptr) return false;
  e->set(params, parameter_from_python(name, e->kind, e->size, value));
  return true;
}

// The video pipeline's parameters: config sections {"seed", "background", "blobs", "estimator"}
// (what vtrack.load_config returns), then keywords of any section.
apps::VehiclePipelineParams vehicle_pipeline_params(const py::dict& config, const py::dict& params) {
  apps::VehiclePipelineParams p;
  auto set = [&p](const std::string& section, const std::string& name, const py::handle& value) {
    const bool any = section.empty();
    if ((any || section == "estimator") && set_in(p.estimator, name, value)) return;
    if ((any || section == "blobs") && set_in(p.blobs, name, value)) return;
    if ((any || section == "background") && set_in(p.background, name, value)) return;
    std::vector<std::string> names;
    if (any || section == "estimator") names = filters::VehicleEstimatorParams::table().names();
    if (any || section == "blobs") for (const auto& n : apps::VehicleBlobParams::table().names()) names.push_back(n);
    if (any || section == "background") for (const auto& n : image::KdeBackgroundParams::table().names()) names.push_back(n);
    throw_unknown_keyword(name, any ? "vehicles" : section, names);
  };
  for (const auto& item : config) {
    const std::string section = py::str(item.first).cast<std::string>();
    if (section == "seed") {
      set("estimator", "seed", item.second);
      continue;
    }
    if (section != "background" && section != "blobs" && section != "estimator") {
      throw py::value_error("config: vehicles has the sections background, blobs and estimator, got '" + section + "'");
    }
    if (!py::isinstance<py::dict>(item.second)) throw py::type_error("config section '" + section + "' must be a dict");
    for (const auto& entry : item.second.cast<py::dict>()) set(section, py::str(entry.first).cast<std::string>(), entry.second);
  }
  for (const auto& item : params) set("", py::str(item.first).cast<std::string>(), item.second);
  apps::validate(p);
  return p;
}

void bind_pipeline(py::module_& m) {
  m.def(
      "_measure_vehicles",
      [](const py::handle& video_arg, const Camera& camera, const py::handle& models, const py::dict& config,
         const py::dict& params, const py::handle& render_arg, const py::handle& out_arg, const py::handle& tracks_arg,
         const py::object& progress) {
        const std::string video = path_arg(video_arg, "video");
        const std::string render = render_arg.is_none() ? "" : path_arg(render_arg, "render");
        const std::string out = out_arg.is_none() ? "" : path_arg(out_arg, "out");
        const std::string tracks = tracks_arg.is_none() ? "" : path_arg(tracks_arg, "tracks");
        if (!render.empty() && !apps::is_video_output(render)) {
          throw py::value_error("render must name a .avi, .mp4 or .mkv file, got '" + render + "'");
        }
        const auto p = vehicle_pipeline_params(config, params);
        auto list = models_arg(models);
        const apps::FrameProgress report = progress_callback(progress);
        apps::VehiclePipelineResult result;
        {
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          std::vector<apps::NamedPath> outputs;
          for (const auto& [name, path] : {std::pair{"out", out}, {"tracks", tracks}, {"render", render}}) {
            if (!path.empty()) outputs.push_back({name, path});
          }
          apps::check_outputs({{"video", video}}, outputs);
          result = apps::measure_vehicles(video, camera, std::move(list), p, render, report);
          if (!out.empty()) apps::write_vehicles_csv(out, result.vehicles);
          if (!tracks.empty()) apps::write_mot(tracks, result.tracks);
        }
        py::dict counts;  // what the run held (HeldViews in src/apps/vehicles.cpp)
        counts["frames"] = result.frames;
        counts["views"] = result.views;
        counts["peak_held_views"] = result.peak_held_views;
        return py::make_tuple(estimates_list(result.vehicles), track_rows(result.tracks), counts);
      },
      py::arg("video"), py::arg("camera"), py::arg("models"), py::arg("config"), py::arg("params"),
      py::arg("render"), py::arg("out"), py::arg("tracks"), py::arg("progress"),
      "The compiled half of vtrack.vehicles.measure_vehicles (use that).");
}

}  // namespace

void bind_vehicles(py::module_& m) {
  bind_camera(m);
  bind_observation(m);
  bind_prior(m);
  bind_estimator(m);
  bind_pipeline(m);
}

}  // namespace vtrack::bindings
