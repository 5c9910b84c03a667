// Bindings of vtrack::filters: the re-clustering SIR (particle-filters-human-vehicle §2).
#include <cmath>

#include "common.hpp"
#include "guard.hpp"
#include "params.hpp"
#include "tracks.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/filters/reclustering_sir.hpp"

namespace vtrack::bindings {

void bind_reclustering_sir(py::module_& m) {
  using filters::ReclusteringSir;
  using filters::ReclusteringSirParams;
  py::class_<ReclusteringSir> cls(m, "ReclusteringSirTracker", R"doc(
Multi-person SIR with measurement-guided re-clustering (particle-filters-human-vehicle §2): one
particle set of ellipses (x, y, vx, vy, a, b) for all the people, each particle carrying a cluster
index (its object), weighted by the §2.1 likelihood over the foreground pixels of y associated
with its object, with new particles injected near measurements no object explains. Construct with
image_size=(width, height) and keyword parameters (ReclusteringSirTracker.default_params());
step(y) takes the background model's H x W float32 image y in [0, 1] (1 = background; the
foreground pixels y < foreground_threshold are the measurements: pass 1 - mask for a binary
mask) and returns vtrack.Tracks (boxes: the ellipses' bounding boxes after the box calibration,
scores: the share of the object's measurements inside its ellipse, states: (x, y, vx, vy, a, b)).
)doc");
  def_foreground_tracker<ReclusteringSir, ReclusteringSirParams>(cls);
  cls.def_property_readonly(
          "particles",
          [](const ReclusteringSir& f) {
            ObjectGuard guard(&f);
            return Eigen::Matrix<float, Eigen::Dynamic, 6, Eigen::RowMajor>(f.particles().states());
          },
          "Copy of the particles after the last step, an (N, 6) float32 array of "
          "(x, y, vx, vy, a, b).")
      .def_property_readonly(
          "clusters",
          [](const ReclusteringSir& f) {
            ObjectGuard guard(&f);
            const auto& c = f.clusters();
            return Eigen::VectorXi(Eigen::Map<const Eigen::VectorXi>(c.data(), Eigen::Index(c.size())));
          },
          "Cluster index of each particle, shape (N,): 0 free (the §2.2 initialisation), k >= 1 "
          "the object objects[k - 1].")
      .def_property_readonly(
          "objects",
          [](const ReclusteringSir& f) {
            ObjectGuard guard(&f);
            py::list out;
            for (const auto& o : f.objects()) {
              py::dict d;
              d["label"] = o.label;
              d["birth_frame"] = o.birth_frame;
              d["particles"] = o.count;
              d["estimate"] = Eigen::VectorXd(o.estimate.cast<double>());
              d["confirmed"] = o.record.confirmed;
              out.append(d);
            }
            return out;
          },
          "The objects after the last step: label, birth_frame, particles (its cluster's size "
          "before resampling), estimate (x, y, vx, vy, a, b), confirmed.")
      .def_property_readonly("frame", guarded(&ReclusteringSir::frame), "Number of steps taken.")
      .def_property_readonly("person_height", guarded(&ReclusteringSir::person_height),
                             "The person height in force (px): height_mean, or learnt from the "
                             "foreground, or size_initial x the image height before that.")
      .def_property_readonly("grid_pixels", guarded(&ReclusteringSir::grid_pixels),
                             "The measurement grid's step in force (px).");

  m.def(
      "ellipse_log_likelihood",
      [](const py::handle& ellipse, const py::handle& points, double rho,
         const py::handle& sigma, double shape_power) {
        const Eigen::VectorXd e = vector_map(as_vector(ellipse, "ellipse"));
        const Eigen::VectorXd s = vector_map(as_vector(sigma, "sigma"));
        const auto pts = as_matrix(points, "points");
        if (e.size() != 4) throw py::value_error("ellipse must be (cx, cy, a, b)");
        if (s.size() != 2) throw py::value_error("sigma must be (sx, sy)");
        if (pts.shape(1) != 2) throw py::value_error("points must have shape (N, 2)");
        require(rho > 0.0 && std::isfinite(rho), "rho", rho, "a positive finite number");
        require(s.minCoeff() > 0.0, "sigma", s.minCoeff(), "> 0");
        require(std::isfinite(shape_power), "shape_power", shape_power, "finite");
        const Eigen::Matrix2Xf z = matrix_map(pts).transpose().cast<float>();
        return filters::ellipse_log_likelihood(float(e[0]), float(e[1]), float(e[2]), float(e[3]),
                                               z, rho, float(s[0]), float(s[1]), shape_power);
      },
      py::arg("ellipse"), py::arg("points"), py::arg("rho"), py::arg("sigma"),
      py::arg("shape_power") = 1.0,
      "log L(Z | x) of particle-filters-human-vehicle §2.1 for an ellipse (cx, cy, a, b) over "
      "the measurements `points` (N x 2 x, y): shape_power (log(N_in / (pi a b)) + "
      "log(N_in / N)) + sum_j log(rho + h(z_j | x)), h the Gaussian of the Mahalanobis distance "
      "with C = diag(sx^2, sy^2) for sigma = (sx, sy). -inf when no point is inside (or none is "
      "given). The ReclusteringSirTracker's weight (shape_power 1 + shape_weight N).");
}

}  // namespace vtrack::bindings
