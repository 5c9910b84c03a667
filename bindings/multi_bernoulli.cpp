// Bindings of vtrack::filters: the multi-Bernoulli track-before-detect tracker.
#include "common.hpp"
#include "guard.hpp"
#include "params.hpp"
#include "tracks.hpp"
#include "vtrack/filters/multi_bernoulli.hpp"

namespace vtrack::bindings {

void bind_multi_bernoulli(py::module_& m) {
  using filters::MultiBernoulliFilter;
  using filters::MultiBernoulliParams;
  py::class_<filters::BernoulliComponent>(m, "BernoulliComponent",
                                          "One Bernoulli component of the multi-Bernoulli density.")
      .def_readonly("label", &filters::BernoulliComponent::label)
      .def_readonly("birth_frame", &filters::BernoulliComponent::birth_frame)
      .def_readonly("existence", &filters::BernoulliComponent::existence)
      .def_property_readonly(
          "particles",
          [](const filters::BernoulliComponent& c) {
            // L x 4 (x, y, w, h) float32 copy.
            return Eigen::Matrix<float, Eigen::Dynamic, 4, Eigen::RowMajor>(c.particles.states());
          },
          "Particles as an (L, 4) float32 array of (x, y, w, h).")
      .def_property_readonly(
          "weights",
          [](const filters::BernoulliComponent& c) { return Eigen::VectorXd(c.particles.weights()); },
          "Normalised particle weights, shape (L,).")
      .def_property_readonly(
          "mean",
          [](const filters::BernoulliComponent& c) {
            const Eigen::Vector4f mu = c.mean();
            return py::make_tuple(mu[0], mu[1], mu[2], mu[3]);
          },
          "Weighted mean box (x, y, w, h).");

  py::class_<MultiBernoulliFilter> cls(m, "MultiBernoulliTracker", R"doc(
SMC multi-Bernoulli track-before-detect tracker on background-subtracted images
(mb-tbd paper, eqs. 20-24). Construct with image_size=(width, height) and keyword parameters
(MultiBernoulliTracker.default_params(); `seed` seeds its random engine); feed each frame's
H x W float32 image y in [0, 1] (near 1 = background) to step(), which returns the reported
tracks as vtrack.Tracks (scores = existence probabilities, states = the filter's own box before
the box calibration).
)doc");
  def_foreground_tracker<MultiBernoulliFilter, MultiBernoulliParams>(cls);
  // Copies (returned by value): references into the filter would dangle after the next step.
  cls.def_property_readonly(
          "components",
          [](const MultiBernoulliFilter& f) {
            ObjectGuard guard(&f);
            return std::vector<filters::BernoulliComponent>(f.components());
          },
          "Copies of all Bernoulli components after the last step (for debugging and plots).")
      .def_property_readonly("frame", guarded(&MultiBernoulliFilter::frame), "Number of steps taken.")
      .def_property_readonly(
          "closing_pixels", [](const MultiBernoulliFilter& f) { return f.likelihood().closing_pixels(); },
          "The side of the closing the tracker applies to y (pixels; 0 or 1: none): closing_size, "
          "or closing_ratio x the learnt person height.")
      .def_property_readonly(
          "size_prior",
          [](const MultiBernoulliFilter& f) {
            const auto& s = f.size_prior();
            py::dict d;
            d["width"] = s.width;
            d["height"] = s.height;
            d["width_range"] = py::make_tuple(s.width_min, s.width_max);
            d["height_range"] = py::make_tuple(s.height_min, s.height_max);
            d["learnt"] = s.learnt;
            return d;
          },
          "The people size prior in force, in pixels: mean width and height, the ranges boxes are "
          "clamped to, and whether it was learnt from the foreground (see height_mean).");
}

}  // namespace vtrack::bindings
