// Binding of vtrack::filters::GlmbTracker (the delta-GLMB filter with Gaussian or particle track
// densities) as vtrack.GlmbTracker.
#include <optional>
#include <string>
#include <vector>

#include "args.hpp"
#include "common.hpp"
#include "guard.hpp"
#include "params.hpp"
#include "tracks.hpp"
#include "vtrack/filters/glmb_tracker.hpp"

namespace vtrack::bindings {
namespace {

using filters::GaussianBirth;

// births: a sequence of (existence, mean, cov) triples.
std::vector<GaussianBirth> births_from(const py::handle& obj) {
  if (!py::isinstance<py::sequence>(obj) || py::isinstance<py::str>(obj)) {
    throw py::type_error("births must be a sequence of (existence, mean, cov) tuples");
  }
  std::vector<GaussianBirth> births;
  for (const auto& item : obj.cast<py::sequence>()) {
    if (!py::isinstance<py::sequence>(item) || py::len(item) != 3) {
      throw py::type_error("births: each entry must be an (existence, mean, cov) tuple, got " +
                           py::repr(item).cast<std::string>());
    }
    const auto triple = item.cast<py::sequence>();
    auto mean = as_vector(triple[1], "births mean");
    auto cov = as_matrix(triple[2], "births cov");
    births.push_back({real_arg(triple[0], "births existence"), {vector_map(mean), matrix_map(cov)}});
  }
  return births;
}

}  // namespace

void bind_glmb(py::module_& m) {
  using filters::GlmbTracker;
  using filters::GlmbTrackerParams;
  py::class_<GlmbTracker> cls(m, "GlmbTracker", R"doc(
Labelled multi-object tracker: the delta-GLMB filter, in the joint prediction-update form of
Vo, Vo & Hoang (IEEE TSP 2017) with Murty's ranked assignments (rgbd-glmb-switching-observation
eqs. 5-8).

motion: LinearGaussianMotion; observation: LinearGaussianObservation; births: a list of
(existence, mean, cov), one labelled Bernoulli birth component each (LMB birth).
adaptive_birth_cov: if given (x_dim x x_dim), every detection also proposes a birth at the next
scan, centred on H^+ z (zero velocity), with this covariance and existence
min(adaptive_birth_max_existence, adaptive_birth_rate (1 - r_U(z)) / sum(1 - r_U)), r_U(z) the
probability that z was assigned to a track (Reuter et al.'s LMB adaptive birth).
depth_model: a DepthLikelihood (needs densities="particles"): step(detections, depth) then
applies the switching observation model -- a track a hypothesis leaves undetected is scored and
reweighted by the depth image (eq. 4) instead of (1 - p_D) alone.

Keyword parameters (GlmbTracker.default_params(); the C++ headers filters/glmb.hpp,
particle_glmb.hpp and track_management.hpp document each): p_S, p_D, the clutter intensity per
unit measurement volume, the hypothesis budget (shared among prior hypotheses in proportion to
sqrt(weight)) and cap, pruning, the squared Mahalanobis gate (inf = none), the adaptive birth's
rate and cap, ranking "murty" (exact) or "gibbs" (Vo, Vo & Hoang's sampler, seeded), seed,
densities "gaussian" (Kalman; the default) or "particles" (n_particles per track, resampled
when N_eff < resample_threshold n_particles, regularised with regularise; the switching model's
options depth_for_births, mask_detections, mask_depth_margin, occlusion_margin,
track_occluders, occluded_detection_probability), and
the reporting options confirm_frames, lost_memory, relabel_overlap, relabel_distance.

step() returns vtrack.Tracks: ids 1, 2, ... in the order labels are first reported, scores =
each label's posterior existence probability, states and covariances = the track densities'
moments, labels = (birth time, birth index). Boxes are NaN (the state is the user's). The
Gaussian filter with Murty's ranking is deterministic. step() releases the GIL; calls on one
tracker from several threads are serialised (each waits for the previous one), and Ctrl-C
interrupts a long step.
)doc");
  cls.def(py::init([](const models::LinearGaussianMotion& motion,
                      const models::LinearGaussianObservation& observation,
                      const py::handle& births, const py::handle& adaptive_birth_cov,
                      std::optional<models::DepthLikelihood> depth_model,
                      const py::kwargs& kwargs) {
            GlmbTrackerParams p = params_from_kwargs<GlmbTrackerParams>(kwargs, "tracker");
            if (!adaptive_birth_cov.is_none()) {
              auto cov = as_matrix(adaptive_birth_cov, "adaptive_birth_cov");
              p.glmb.adaptive_birth.enabled = true;
              p.glmb.adaptive_birth.cov = matrix_map(cov);
            }
            return GlmbTracker(motion, observation, births_from(births), p, std::move(depth_model));
          }),
          py::arg("motion"), py::arg("observation"), py::arg("births"), py::kw_only(),
          py::arg("adaptive_birth_cov") = py::none(), py::arg("depth_model") = py::none())
      .def(
          "step",
          [](GlmbTracker& t, const py::handle& detections, const py::handle& depth) {
            auto z = as_matrix(detections, "detections");
            const auto z_dim = t.z_dim();
            if (z.shape(1) != z_dim && z.shape(0) > 0) {
              throw py::value_error("detections must have shape (M, " + std::to_string(z_dim) +
                                    "), got (" + std::to_string(z.shape(0)) + ", " +
                                    std::to_string(z.shape(1)) + ")");
            }
            py::array keep;
            cv::Mat image;
            if (!depth.is_none()) image = depth_image(depth, "depth", keep);
            ObjectGuard guard(&t);
            PythonInterrupts interrupts;  // a large hypothesis budget makes a step long
            py::gil_scoped_release release;
            // Row-major M x z_dim is column-major z_dim x M: one detection per column.
            const Eigen::Map<const Eigen::MatrixXd> columns(z.data(), z_dim, z.shape(0));
            return TrackSet{t.step(columns, image.empty() ? nullptr : &image)};
          },
          py::arg("detections"), py::arg("depth") = py::none(), R"doc(
One joint prediction-update with the detections of the next scan, an (M, z_dim) array (M may be
0), and the tracks reported at that scan (vtrack.Tracks). `depth` (a tracker with a
depth_model only): the scan's background-subtracted metric depth image, H x W float32/float64
metres of the depth model's camera, 0 where there is no target or no reading; tracks left
undetected are then scored by it (the switching model). Without it a step is detection-only.
Raises TypeError for a non-numeric dtype and ValueError for a wrong shape or NaN/inf.
)doc")
      .def_property_readonly("tracks", last_tracks<GlmbTracker>(),
                             "The tracks reported by the last step.")
      .def("cardinality_distribution", guarded(&GlmbTracker::cardinality_distribution),
           "P(n targets) for n = 0 .. the largest hypothesis size, a float64 array summing to 1.")
      .def_property_readonly("map_cardinality", guarded(&GlmbTracker::map_cardinality),
                             "The most probable number of targets.")
      .def_property_readonly("hypothesis_count", guarded(&GlmbTracker::hypothesis_count),
                             "Number of hypotheses kept after the last step.")
      .def_property_readonly("track_count", guarded(&GlmbTracker::track_count),
                             "Number of distinct track histories the hypotheses share.")
      .def_property_readonly("time", guarded(&GlmbTracker::time),
                             "Number of scans processed (the current scan index).")
      .def_property_readonly("has_depth_model", &GlmbTracker::has_depth_model,
                             "Whether step() accepts a depth image (the switching observation model).");
  def_params<GlmbTrackerParams>(cls, [](const GlmbTracker& t) { return t.params(); });
}

}  // namespace vtrack::bindings
