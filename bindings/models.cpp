// Bindings of vtrack::models: linear-Gaussian motion and observation models.
#include "common.hpp"
#include "vtrack/models/linear_gaussian.hpp"

namespace vtrack::bindings {

void bind_models(py::module_& m) {
  using models::LinearGaussianMotion;
  using models::LinearGaussianObservation;

  py::class_<LinearGaussianMotion>(m, "LinearGaussianMotion", R"doc(
Linear-Gaussian motion model x_k = F x_{k-1} + v, v ~ N(0, Q), for Gaussian trackers
(GlmbTracker). Build it from matrices or with LinearGaussianMotion.constant_velocity(...).
)doc")
      .def(py::init([](const py::handle& F, const py::handle& Q) {
             auto f = as_matrix(F, "F");
             auto q = as_matrix(Q, "Q");
             return LinearGaussianMotion{matrix_map(f), matrix_map(q)};
           }),
           py::arg("F"), py::arg("Q"))
      .def_static("constant_velocity", &LinearGaussianMotion::constant_velocity,
                  py::arg("axes") = 2, py::arg("period") = 1.0, py::arg("sigma_v") = 5.0, R"doc(
Constant velocity in `axes` dimensions (rgbd-glmb-switching-observation eq. 7): state
[p_1, v_1, p_2, v_2, ...], F = I (x) [[1, T], [0, 1]], Q = sigma_v^2 (I (x) g g^T) with
g = [T^2/2, T]. The defaults are the standard GLMB scenario's (2-D, T = 1, sigma_v = 5).
)doc")
      .def_property_readonly("F", [](const LinearGaussianMotion& mo) { return mo.F; },
                             "State transition matrix (x_dim x x_dim).")
      .def_property_readonly("Q", [](const LinearGaussianMotion& mo) { return mo.Q; },
                             "Process noise covariance (x_dim x x_dim).")
      .def("__repr__", [](const LinearGaussianMotion& mo) {
        return "LinearGaussianMotion(x_dim=" + std::to_string(mo.F.rows()) + ")";
      });

  py::class_<LinearGaussianObservation>(m, "LinearGaussianObservation", R"doc(
Linear-Gaussian observation model z = H x + w, w ~ N(0, R), the detection likelihood of the
GLMB tracker (rgbd-glmb-switching-observation eq. 2). Build it from matrices or with
LinearGaussianObservation.position(...).
)doc")
      .def(py::init([](const py::handle& H, const py::handle& R) {
             auto h = as_matrix(H, "H");
             auto r = as_matrix(R, "R");
             return LinearGaussianObservation{matrix_map(h), matrix_map(r)};
           }),
           py::arg("H"), py::arg("R"))
      .def_static(
          "position",
          [](int axes, const py::handle& R) {
            auto r = as_matrix(R, "R");
            return LinearGaussianObservation::position_of_constant_velocity(axes, matrix_map(r));
          },
          py::arg("axes") = 2, py::arg("R") = Eigen::MatrixXd(Eigen::Matrix2d::Identity() * 100.0),
          R"doc(
The positions of a constant-velocity state ([p_1, v_1, p_2, v_2, ...]), one row of H per axis,
with noise covariance R (axes x axes). The defaults are the standard GLMB scenario's
(2-D, R = 100 I).
)doc")
      .def_property_readonly("H", [](const LinearGaussianObservation& o) { return o.H; },
                             "Observation matrix (z_dim x x_dim).")
      .def_property_readonly("R", [](const LinearGaussianObservation& o) { return o.R; },
                             "Measurement noise covariance (z_dim x z_dim).")
      .def("__repr__", [](const LinearGaussianObservation& o) {
        return "LinearGaussianObservation(z_dim=" + std::to_string(o.H.rows()) +
               ", x_dim=" + std::to_string(o.H.cols()) + ")";
      });
}

}  // namespace vtrack::bindings
