// Bindings of vtrack::filters: the multi-Bernoulli track-before-detect tracker.
#include "common.hpp"
#include "params.hpp"
#include "vtrack/filters/multi_bernoulli.hpp"

namespace vtrack::bindings {
namespace {

using filters::MultiBernoulliParams;

int as_int(const std::string& name, const py::handle& v) {
  if (py::isinstance<py::bool_>(v) || !PyIndex_Check(v.ptr())) {
    throw py::type_error(name + " must be an int, got " + type_name(v));
  }
  return py::int_(py::reinterpret_borrow<py::object>(v)).cast<int>();
}

std::string track_repr(const filters::Track& t) {
  return cv::format("Track(label=%llu, x=%.1f, y=%.1f, w=%.1f, h=%.1f, existence=%.4f)",
                    static_cast<unsigned long long>(t.label), t.x, t.y, t.w, t.h, t.existence);
}

}  // namespace

void bind_multi_bernoulli(py::module_& m) {
  py::class_<filters::Track>(m, "Track", "One confirmed track: its label, mean box and existence.")
      .def_readonly("label", &filters::Track::label, "Identity, kept for the track's life.")
      .def_readonly("x", &filters::Track::x, "Left edge of the box (pixels).")
      .def_readonly("y", &filters::Track::y, "Top edge of the box (pixels).")
      .def_readonly("w", &filters::Track::w, "Box width (pixels).")
      .def_readonly("h", &filters::Track::h, "Box height (pixels).")
      .def_readonly("existence", &filters::Track::existence, "Existence probability r.")
      .def_property_readonly(
          "box", [](const filters::Track& t) { return py::make_tuple(t.x, t.y, t.w, t.h); },
          "(x, y, w, h).")
      .def("__repr__", &track_repr);

  py::class_<filters::BernoulliComponent>(m, "BernoulliComponent",
                                          "One Bernoulli component of the multi-Bernoulli density.")
      .def_readonly("label", &filters::BernoulliComponent::label)
      .def_readonly("birth_frame", &filters::BernoulliComponent::birth_frame)
      .def_readonly("existence", &filters::BernoulliComponent::existence)
      .def_property_readonly(
          "particles",
          [](const filters::BernoulliComponent& c) {
            // L x 4 (x, y, w, h) float32 copy.
            const Eigen::Matrix<float, Eigen::Dynamic, 4> t = c.particles.transpose();
            return Eigen::Matrix<float, Eigen::Dynamic, 4, Eigen::RowMajor>(t);
          },
          "Particles as an (L, 4) float32 array of (x, y, w, h).")
      .def_property_readonly(
          "weights",
          [](const filters::BernoulliComponent& c) { return Eigen::VectorXd(c.log_weights.array().exp()); },
          "Normalised particle weights, shape (L,).")
      .def_property_readonly(
          "mean",
          [](const filters::BernoulliComponent& c) {
            const Eigen::Vector4f mu = c.mean();
            return py::make_tuple(mu[0], mu[1], mu[2], mu[3]);
          },
          "Weighted mean box (x, y, w, h).");

  py::class_<filters::MultiBernoulliFilter>(m, "MultiBernoulliTracker", R"doc(
SMC multi-Bernoulli track-before-detect tracker on background-subtracted images
(mb-tbd paper, eqs. 20-24). Construct with image_size=(width, height), a seed and keyword
parameters (see vtrack.MultiBernoulliTracker.default_params()); feed each frame's H x W float32
image y in [0, 1] (near 1 = background) to step(), which returns the confirmed tracks.
)doc")
      .def(py::init([](const py::handle& image_size, std::uint64_t seed, const py::kwargs& kwargs) {
             if (!py::isinstance<py::sequence>(image_size) || py::isinstance<py::str>(image_size)) {
               throw py::type_error("image_size must be a (width, height) pair, got " +
                                    type_name(image_size));
             }
             const auto size = py::reinterpret_borrow<py::sequence>(image_size);
             if (size.size() != 2) {
               throw py::value_error("image_size must be a (width, height) pair, got " +
                                     std::to_string(size.size()) + " values");
             }
             const int w = as_int("image_size[0] (width)", size[0]);
             const int h = as_int("image_size[1] (height)", size[1]);
             MultiBernoulliParams params;
             set_from_kwargs(params, kwargs, "tracker");
             return filters::MultiBernoulliFilter(w, h, params, seed);
           }),
           py::arg("image_size"), py::kw_only(), py::arg("seed") = 0)
      .def(
          "step",
          [](filters::MultiBernoulliFilter& f, const py::handle& y) {
            py::array keep;
            const cv::Mat img = gray_image(y, "y", keep);
            if (img.type() != CV_32FC1) {
              throw py::type_error("y must have dtype float32, got " +
                                   py::str(keep.dtype()).cast<std::string>());
            }
            py::gil_scoped_release release;
            return f.step(img);
          },
          py::arg("y"),
          "Process one background-subtracted image y (H x W float32 in [0, 1], H and W as "
          "image_size) and return the confirmed tracks (existence above estimate_threshold), "
          "ordered by label.")
      // Copies (returned by value): references into the filter would dangle after the next step.
      .def_property_readonly(
          "tracks",
          [](const filters::MultiBernoulliFilter& f) { return std::vector<filters::Track>(f.tracks()); },
          "The tracks returned by the last step.")
      .def_property_readonly(
          "components",
          [](const filters::MultiBernoulliFilter& f) {
            return std::vector<filters::BernoulliComponent>(f.components());
          },
          "Copies of all Bernoulli components after the last step (for debugging and plots).")
      .def_property_readonly("frame", &filters::MultiBernoulliFilter::frame,
                             "Number of steps taken.")
      .def_property_readonly(
          "image_size",
          [](const filters::MultiBernoulliFilter& f) { return py::make_tuple(f.width(), f.height()); })
      .def_property_readonly(
          "params", [](const filters::MultiBernoulliFilter& f) { return params_dict(f.params()); },
          "The parameters in use, as a dict of keyword arguments.")
      .def_static(
          "default_params", []() { return params_dict(MultiBernoulliParams{}); },
          "The default keyword parameters, as a dict.");
}

}  // namespace vtrack::bindings
