// Bindings of vtrack::models: linear-Gaussian motion and observation models, the depth likelihood.
#include <limits>
#include <optional>
#include <utility>

#include "args.hpp"
#include "common.hpp"
#include "params.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/models/depth_likelihood.hpp"
#include "vtrack/models/linear_gaussian.hpp"
#include "vtrack/models/person_size.hpp"
#include "guard.hpp"

namespace vtrack::bindings {

namespace {

void bind_linear_gaussian(py::module_& m) {
  using models::LinearGaussianMotion;
  using models::LinearGaussianObservation;

  py::class_<LinearGaussianMotion>(m, "LinearGaussianMotion", R"doc(
Linear-Gaussian motion model x_k = F x_{k-1} + v, v ~ N(0, Q), for Gaussian trackers
(GlmbTracker). Build it from matrices or with LinearGaussianMotion.constant_velocity(...).
)doc")
      .def(py::init([](const py::handle& F, const py::handle& Q) {
             auto f = as_matrix(F, "F");
             auto q = as_matrix(Q, "Q");
             LinearGaussianMotion motion{matrix_map(f), matrix_map(q)};
             models::validate(motion);  // F finite, Q a covariance (never negative variances)
             return motion;
           }),
           py::arg("F"), py::arg("Q"))
      .def_static(
          "constant_velocity",
          [](const py::handle& axes, const py::handle& period, const py::handle& sigma_v) {
            return LinearGaussianMotion::constant_velocity(
                static_cast<int>(int_arg(axes, "axes", 1, 1000)), real_arg(period, "period"),
                real_arg(sigma_v, "sigma_v"));
          },
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
             LinearGaussianObservation observation{matrix_map(h), matrix_map(r), Eigen::MatrixXd()};
             models::validate(observation);  // H finite, R positive definite
             return observation;
           }),
           py::arg("H"), py::arg("R"))
      .def_static(
          "position",
          [](const py::handle& axes, const py::handle& R) {
            auto r = as_matrix(R, "R");
            auto observation = LinearGaussianObservation::position_of_constant_velocity(
                static_cast<int>(int_arg(axes, "axes", 1, 1000)), matrix_map(r));
            models::validate(observation);
            return observation;
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

void bind_depth_likelihood(py::module_& m) {
  using models::DepthLikelihood;
  using models::DepthLikelihoodParams;
  m.def("kinect_raw_to_depth", py::vectorize(&models::kinect_raw_to_depth), py::arg("raw"),
        py::arg("fx") = 525.0, R"doc(
Kinect raw depth to metres, rgbd-glmb-switching-observation eq. (3): T = 8 B fx / (W_max - w)
with B = 0.075 m, W_max = 1084; fx is the IR camera's horizontal focal length in pixels.
Raw values >= W_max, negative or NaN carry no reading and give 0. Scalars or arrays (float64).
)doc");
  m.def("kinect_depth_to_raw", py::vectorize(&models::kinect_depth_to_raw), py::arg("depth"),
        py::arg("fx") = 525.0, R"doc(
The inverse of kinect_raw_to_depth (unrounded), for simulating a sensor: w = W_max - 8 B fx / T.
Depth <= 0, NaN, or nearer than the sensor minimum 8 B fx / W_max give 2047 (no reading).
)doc");

  py::class_<DepthLikelihood> depth(m, "DepthLikelihood", R"doc(
The depth-intensity likelihood of rgbd-glmb-switching-observation eq. (4) for a pinhole camera:
the secondary observation of GlmbTracker's switching model.

Camera frame (metres): X right, Y down, D along the optical axis. A person at position (X, Y, D)
(the centre of its bounding box, as eq. 2's detections) covers T(x), the rectangle of metric size
person_width x person_height projected at depth D: centre (cx + fx X/D, cy + fy Y/D), size
(fx person_width/D, fy person_height/D) pixels, rounded and clipped to the width x height image.
On a background-subtracted metric depth image d (0 = background/no reading), the log ratio
  tempering * sum_{i in T(x)} [log N(d_i; D, sigma_target) - log N(d_i; 0, sigma_background)]
is computed in O(1) per state from integral images of d and d^2 (sigmas are standard deviations,
metres). tempering in (0, 1] (1 = the paper's independent pixels) flattens a likelihood that
treats every pixel as an independent observation; see models/depth_likelihood.hpp.
fy defaults to fx, (cx, cy) to the image centre ((width - 1)/2, (height - 1)/2). Keyword
parameters: DepthLikelihood.default_params().
)doc");
  depth.def(py::init([](const py::handle& width, const py::handle& height, const py::handle& fx,
                        const py::handle& fy, const py::handle& cx, const py::handle& cy,
                        const py::kwargs& kwargs) {
             const auto optional_real = [](const py::handle& v, const char* name) {
               return v.is_none() ? std::optional<double>() : std::optional<double>(real_arg(v, name));
             };
             DepthLikelihoodParams p;
             p.camera = models::PinholeCamera::of(
                 static_cast<int>(int_arg(width, "width", 1, core::kMaxImageSide)),
                 static_cast<int>(int_arg(height, "height", 1, core::kMaxImageSide)),
                 real_arg(fx, "fx"), optional_real(fy, "fy"), optional_real(cx, "cx"),
                 optional_real(cy, "cy"));
             return DepthLikelihood(params_from_kwargs(kwargs, "depth model", p));
           }),
           py::arg("width"), py::arg("height"), py::arg("fx"), py::arg("fy") = py::none(),
           py::arg("cx") = py::none(), py::arg("cy") = py::none())
      .def(
          "footprint",
          [](const DepthLikelihood& d, const py::handle& position) {
            auto x = as_vector(position, "position");
            if (x.size() != 3) throw py::value_error("position must be (X, Y, D)");
            const auto r = d.footprint(x.at(0), x.at(1), x.at(2));
            return py::make_tuple(r.x, r.y, r.width, r.height);
          },
          py::arg("position"),
          "T(x) as (x, y, width, height) pixels, clipped to the image ((0, 0, 0, 0) if empty).")
      .def(
          "log_ratio",
          [](const DepthLikelihood& d, const py::handle& depth, const py::handle& positions) {
            py::array keep;
            const cv::Mat image = depth_image(depth, "depth", keep);
            auto x = as_matrix(positions, "positions");
            if (x.shape(1) != 3) throw py::value_error("positions must have shape (N, 3)");
            Eigen::VectorXd out(x.shape(0));
            {
              py::gil_scoped_release release;
              const auto frame = d.frame(image);
              // Row-major N x 3 is column-major 3 x N.
              d.log_ratio(frame, Eigen::Map<const Eigen::Matrix3Xd>(x.data(), 3, x.shape(0)), out);
            }
            return out;
          },
          py::arg("depth"), py::arg("positions"), R"doc(
The tempered log ratio of eq. (4), log prod_{T(x)} phi_i / varphi_i times tempering, for each row
(X, Y, D) of positions (N, 3), on the depth image (H x W float32/float64 metres).
)doc")
      .def_property_readonly("width", [](const DepthLikelihood& d) { return d.params().camera.width; })
      .def_property_readonly("height", [](const DepthLikelihood& d) { return d.params().camera.height; })
      .def_property_readonly("fx", [](const DepthLikelihood& d) { return d.params().camera.fx; })
      .def_property_readonly("fy", [](const DepthLikelihood& d) { return d.params().camera.fy; })
      .def_property_readonly("cx", [](const DepthLikelihood& d) { return d.params().camera.cx; })
      .def_property_readonly("cy", [](const DepthLikelihood& d) { return d.params().camera.cy; })
      .def("__repr__", [](const DepthLikelihood& d) {
        const auto& c = d.params().camera;
        return "DepthLikelihood(" + std::to_string(c.width) + "x" + std::to_string(c.height) +
               ", fx=" + std::to_string(c.fx) + ", tempering=" + std::to_string(d.params().tempering) + ")";
      });
  def_params<DepthLikelihoodParams>(depth, [](const DepthLikelihood& d) { return d.params(); });
}

void bind_person_size(py::module_& m) {
  using models::ForegroundSizeEstimator;
  py::class_<ForegroundSizeEstimator>(m, "ForegroundSizeEstimator", R"doc(
How tall the people of a scene are, learnt from its background-subtracted images (the
MultiBernoulliTracker's learnt size prior; cpp/include/vtrack/models/person_size.hpp): observe(y)
counts the connected components of y < threshold that do not touch the image's top or
bottom border;
person_height is the median height of the components big enough to be a whole person, each
counted once (a group merged into one component counts once, not by its area).
half_life: observed frames (inf = never forget); min_area_fraction: the smallest component
counted, as a fraction of the image; aspect: a person's width / height.
)doc")
      .def(py::init([](const py::handle& half_life, const py::handle& min_area_fraction,
                       const py::handle& aspect) {
             return ForegroundSizeEstimator(real_arg(half_life, "half_life"),
                                            real_arg(min_area_fraction, "min_area_fraction"),
                                            real_arg(aspect, "aspect"));
           }),
           py::kw_only(), py::arg("half_life") = std::numeric_limits<double>::infinity(),
           py::arg("min_area_fraction") = 1e-4, py::arg("aspect") = 0.35)
      .def(
          "observe",
          [](ForegroundSizeEstimator& e, const py::handle& y, const py::handle& threshold) {
            py::array keep;
            const cv::Mat img = float32_image(y, "y", keep);
            const auto t = static_cast<float>(real_arg(threshold, "threshold"));
            ObjectGuard guard(&e);
            py::gil_scoped_release release;
            e.observe(img, t);
          },
          py::arg("y"), py::kw_only(), py::arg("threshold") = 0.5,
          "Count the foreground components of y (H x W float32, near 1 = background).")
      .def_property_readonly("person_height", guarded(&ForegroundSizeEstimator::person_height),
                             "The learnt person height (px); 0 before any component.")
      .def_property_readonly(
          "person_height_line",
          [](const ForegroundSizeEstimator& e) {
            const models::PersonHeightLine line = e.person_height_line();
            py::dict d;
            d["slope"] = line.slope;
            d["intercept"] = line.intercept;
            d["min_height"] = line.min_height;
            d["max_height"] = line.max_height;
            d["by_row"] = line.by_row;
            d["rising_share"] = line.rising_share;
            d["fit_share"] = line.fit_share;
            return d;
          },
          "The person height by foot row, h = slope x row + intercept (px) clamped to "
          "[min_height, max_height], and whether the data support a slope (by_row; else the "
          "constant intercept = person_height).")
      .def_property_readonly("weight", guarded(&ForegroundSizeEstimator::weight),
                             "The (decayed) total area of the components counted (px).")
      .def_property_readonly("frames", guarded(&ForegroundSizeEstimator::frames),
                             "Number of images observed.")
      .def("reset", guarded(&ForegroundSizeEstimator::reset));
}

}  // namespace

void bind_models(py::module_& m) {
  bind_linear_gaussian(m);
  bind_depth_likelihood(m);
  bind_person_size(m);
}

}  // namespace vtrack::bindings
