// Binding of the delta-GLMB filters (vtrack::filters::GaussianGlmbFilter and ParticleGlmbFilter)
// as one Python class, vtrack.GlmbTracker: the track density is chosen by the keywords.
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "common.hpp"
#include "vtrack/filters/glmb.hpp"
#include "vtrack/filters/particle_glmb.hpp"

namespace vtrack::bindings {
namespace {

using filters::GaussianBirth;
using filters::GaussianGlmbFilter;
using filters::GlmbEstimate;
using filters::GlmbParams;
using filters::ParticleGlmbFilter;

// The Python object: one filter or the other, dispatched once per call (not per particle).
struct GlmbTracker {
  std::variant<GaussianGlmbFilter, ParticleGlmbFilter> filter;
  template <class F>
  decltype(auto) visit(F&& f) {
    return std::visit(std::forward<F>(f), filter);
  }
  template <class F>
  decltype(auto) visit(F&& f) const {
    return std::visit(std::forward<F>(f), filter);
  }
};

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
    births.push_back({triple[0].cast<double>(), {vector_map(mean), matrix_map(cov)}});
  }
  return births;
}

py::tuple label_tuple(const filters::TrackLabel& l) {
  return py::make_tuple(l.birth_time, l.birth_index);
}

}  // namespace

void bind_glmb(py::module_& m) {
  py::class_<GlmbEstimate>(m, "GlmbEstimate", "One labelled track estimate of a GlmbTracker.")
      .def_property_readonly(
          "label", [](const GlmbEstimate& e) { return label_tuple(e.label); },
          "(birth_time, birth_index): the scan the track was born at (from 1) and the index of "
          "its birth component (fixed births first, then adaptive births by detection index).")
      .def_readonly("mean", &GlmbEstimate::mean, "State mean (x_dim,).")
      .def_readonly("cov", &GlmbEstimate::cov, "State covariance (x_dim, x_dim).")
      .def("__repr__", [](const GlmbEstimate& e) {
        return "GlmbEstimate(label=" + py::repr(label_tuple(e.label)).cast<std::string>() +
               ", mean=" + py::repr(py::cast(e.mean)).cast<std::string>() + ")";
      });

  const GlmbParams defaults;
  const filters::ParticleParams particle_defaults;
  py::class_<GlmbTracker>(m, "GlmbTracker", R"doc(
Labelled multi-object tracker: the delta-GLMB filter, in the joint prediction-update form of
Vo, Vo & Hoang (IEEE TSP 2017) with Murty's ranked assignments (rgbd-glmb-switching-observation
eqs. 5-8).

motion: LinearGaussianMotion; observation: LinearGaussianObservation; births: a list of
(existence, mean, cov), one labelled Bernoulli birth component each (LMB birth).
Keyword parameters (defaults: the standard GLMB scenario's):
  survival_probability  p_S
  detection_probability p_D
  clutter_intensity     Poisson clutter intensity per unit measurement volume (mean count /
                        surveillance volume)
  hypothesis_budget     posterior hypotheses requested per scan, shared among prior hypotheses
                        in proportion to sqrt(weight)
  max_hypotheses        cap after each update (largest weights kept)
  prune_threshold       hypotheses below this normalised weight are dropped
  gate_threshold        squared Mahalanobis gate (chi-square quantile; inf = no gating)
  adaptive_birth_cov    if given (x_dim x x_dim), every detection also proposes a birth at the
                        next scan, centred on H^+ z (zero velocity), with this covariance and
                        existence min(adaptive_birth_max_existence,
                        adaptive_birth_rate (1 - r_U(z)) / sum(1 - r_U)), r_U(z) the probability
                        that z was assigned to a track (Reuter et al.'s LMB adaptive birth)
  adaptive_birth_rate   expected number of adaptive births per scan (lambda_B)
  adaptive_birth_max_existence  cap on one detection's birth existence
  ranking               "murty" (the k best assignments per prior hypothesis, exact) or "gibbs"
                        (Vo, Vo & Hoang's Gibbs sampler, as many sweeps as hypotheses requested;
                        random, seeded by `seed`)
Track densities: Gaussian (Kalman) by default. Particles when `particles` or `depth_model` is
given (the paper's particle implementation):
  particles             particles per track (default 500 with a depth model)
  depth_model           a DepthLikelihood: step(detections, depth) then applies the switching
                        observation model -- a track a hypothesis leaves undetected is scored and
                        reweighted by the depth image (eq. 4) instead of (1 - p_D) alone
  resample_threshold    systematic resampling when N_eff < resample_threshold * particles
  seed                  the random engine of the particle filter and of the Gibbs ranking (same
                        seed, same tracks)
  depth_for_births      births' missed branch is scored by the depth image too (default True,
                        eq. 8's psi for every label; False: (1 - p_D) alone)
  mask_detections       blank the footprints of the scan's detections in the depth image before
                        scoring missed tracks (default True: a detected person's pixels are
                        explained by the detection, so duplicate tracks cannot live on them;
                        False = eq. 4 on the raw image, as the paper)
  occlusion_margin      with mask_detections: pixels of a detection's footprint are left out of the
                        eq. 4 score of states farther than its depth + this margin (m; default 0.3,
                        inf = off): the detected person hides them
  occluded_detection_probability  with occlusion: p_D(x) = p_D x the visible fraction of T(x)
                        (default False: it lets duplicates live behind detected people; eq. 8's
                        state-dependent p_D)

The Gaussian filter with Murty's ranking is deterministic (no random numbers). step() releases the GIL; one tracker
must not be stepped from two threads at once.
)doc")
      .def(py::init([](const models::LinearGaussianMotion& motion,
                       const models::LinearGaussianObservation& observation,
                       const py::handle& births, double survival_probability,
                       double detection_probability, double clutter_intensity,
                       int hypothesis_budget, int max_hypotheses, double prune_threshold,
                       double gate_threshold, const py::handle& adaptive_birth_cov,
                       double adaptive_birth_rate, double adaptive_birth_max_existence,
                       const std::string& ranking, std::optional<int> particles,
                       std::optional<models::DepthLikelihood> depth_model,
                       double resample_threshold, std::uint64_t seed, bool depth_for_births,
                       bool mask_detections, double occlusion_margin,
                       bool occluded_detection_probability) {
             GlmbParams p;
             p.survival_probability = survival_probability;
             p.detection_probability = detection_probability;
             p.clutter_intensity = clutter_intensity;
             p.hypothesis_budget = hypothesis_budget;
             p.max_hypotheses = max_hypotheses;
             p.prune_threshold = prune_threshold;
             p.gate_threshold = gate_threshold;
             if (!adaptive_birth_cov.is_none()) {
               auto cov = as_matrix(adaptive_birth_cov, "adaptive_birth_cov");
               p.adaptive_birth.enabled = true;
               p.adaptive_birth.cov = matrix_map(cov);
             }
             p.adaptive_birth.expected_births = adaptive_birth_rate;
             p.adaptive_birth.max_existence = adaptive_birth_max_existence;
             if (ranking != "murty" && ranking != "gibbs") {
               throw py::value_error("ranking must be 'murty' or 'gibbs', got '" + ranking + "'");
             }
             p.ranking = ranking == "gibbs" ? filters::HypothesisRanking::gibbs
                                            : filters::HypothesisRanking::murty;
             p.seed = seed;
             if (!particles && !depth_model) {
               return GlmbTracker{GaussianGlmbFilter(motion, observation, births_from(births), p)};
             }
             filters::ParticleParams pp;
             if (particles) pp.particles = *particles;
             pp.resample_threshold = resample_threshold;
             pp.seed = seed;
             pp.depth_for_births = depth_for_births;
             pp.mask_detections = mask_detections;
             pp.occlusion_margin = occlusion_margin;
             pp.occluded_detection_probability = occluded_detection_probability;
             return GlmbTracker{ParticleGlmbFilter(motion, observation, births_from(births), p, pp,
                                                   std::move(depth_model))};
           }),
           py::arg("motion"), py::arg("observation"), py::arg("births"), py::kw_only(),
           py::arg("survival_probability") = defaults.survival_probability,
           py::arg("detection_probability") = defaults.detection_probability,
           py::arg("clutter_intensity") = defaults.clutter_intensity,
           py::arg("hypothesis_budget") = defaults.hypothesis_budget,
           py::arg("max_hypotheses") = defaults.max_hypotheses,
           py::arg("prune_threshold") = defaults.prune_threshold,
           py::arg("gate_threshold") = defaults.gate_threshold,
           py::arg("adaptive_birth_cov") = py::none(),
           py::arg("adaptive_birth_rate") = defaults.adaptive_birth.expected_births,
           py::arg("adaptive_birth_max_existence") = defaults.adaptive_birth.max_existence,
           py::arg("ranking") = "murty", py::arg("particles") = py::none(), py::arg("depth_model") = py::none(),
           py::arg("resample_threshold") = particle_defaults.resample_threshold,
           py::arg("seed") = particle_defaults.seed,
           py::arg("depth_for_births") = particle_defaults.depth_for_births,
           py::arg("mask_detections") = particle_defaults.mask_detections,
           py::arg("occlusion_margin") = particle_defaults.occlusion_margin,
           py::arg("occluded_detection_probability") =
               particle_defaults.occluded_detection_probability)
      .def(
          "step",
          [](GlmbTracker& t, const py::handle& detections, const py::handle& depth) {
            auto z = as_matrix(detections, "detections");
            const auto z_dim = t.visit([](const auto& f) { return f.z_dim(); });
            if (z.shape(1) != z_dim && z.shape(0) > 0) {
              throw py::value_error("detections must have shape (M, " + std::to_string(z_dim) +
                                    "), got (" + std::to_string(z.shape(0)) + ", " +
                                    std::to_string(z.shape(1)) + ")");
            }
            py::array keep;
            cv::Mat image;
            if (!depth.is_none()) {
              if (!std::holds_alternative<ParticleGlmbFilter>(t.filter)) {
                throw py::value_error("depth needs a tracker built with a depth_model");
              }
              image = depth_image(depth, "depth", keep);
            }
            {
              py::gil_scoped_release release;
              // Row-major M x z_dim is column-major z_dim x M: one detection per column.
              const Eigen::Map<const Eigen::MatrixXd> columns(z.data(), z_dim, z.shape(0));
              t.visit([&](auto& f) {
                if constexpr (std::is_same_v<std::decay_t<decltype(f)>, ParticleGlmbFilter>) {
                  f.step(columns, image.empty() ? nullptr : &image);
                } else {
                  f.step(columns);
                }
              });
            }
            return t.visit([](const auto& f) { return f.estimates(); });
          },
          py::arg("detections"), py::arg("depth") = py::none(), R"doc(
One joint prediction-update with the detections of the next scan, an (M, z_dim) array (M may be
0), and the estimates at that scan (as estimates()). `depth` (particle tracker with a
depth_model only): the scan's background-subtracted metric depth image, H x W float32/float64
metres of the depth model's camera, 0 where there is no target or no reading; tracks left
undetected are then scored by it (the switching model). Without it a step is detection-only.
Raises TypeError for a non-numeric dtype and ValueError for a wrong shape or NaN/inf.
)doc")
      .def(
          "estimates", [](const GlmbTracker& t) { return t.visit([](const auto& f) { return f.estimates(); }); },
          R"doc(
The labelled estimates at the current scan, a list of GlmbEstimate: the tracks of the most
probable hypothesis with the MAP cardinality (particle tracks: weighted mean and covariance).
)doc")
      .def(
          "cardinality_distribution",
          [](const GlmbTracker& t) {
            return t.visit([](const auto& f) { return f.cardinality_distribution(); });
          },
          "P(n targets) for n = 0 .. the largest hypothesis size, a float64 array summing to 1.")
      .def_property_readonly(
          "map_cardinality",
          [](const GlmbTracker& t) { return t.visit([](const auto& f) { return f.map_cardinality(); }); },
          "The most probable number of targets.")
      .def_property_readonly(
          "hypothesis_count",
          [](const GlmbTracker& t) { return t.visit([](const auto& f) { return f.hypothesis_count(); }); },
          "Number of hypotheses kept after the last step.")
      .def_property_readonly(
          "track_count",
          [](const GlmbTracker& t) { return t.visit([](const auto& f) { return f.track_count(); }); },
          "Number of distinct track histories the hypotheses share.")
      .def_property_readonly(
          "time", [](const GlmbTracker& t) { return t.visit([](const auto& f) { return f.time(); }); },
          "Number of scans processed (the current scan index).")
      .def_property_readonly(
          "particles",
          [](const GlmbTracker& t) -> std::optional<int> {
            if (const auto* f = std::get_if<ParticleGlmbFilter>(&t.filter)) {
              return f->particle_params().particles;
            }
            return std::nullopt;
          },
          "Particles per track, or None for Gaussian (Kalman) track densities.")
      .def_property_readonly(
          "has_depth_model",
          [](const GlmbTracker& t) {
            const auto* f = std::get_if<ParticleGlmbFilter>(&t.filter);
            return f && f->has_depth_model();
          },
          "Whether step() accepts a depth image (the switching observation model).");
}

}  // namespace vtrack::bindings
