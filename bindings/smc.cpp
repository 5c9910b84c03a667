// Bindings of the SMC engine (vtrack::smc) and its models: ParticleFilter (SIR, resample-move),
// MCMCParticleFilter, the motion models and the range-bearing observation. Conversion only: the
// model a Python caller passes selects a compile-time instantiation of the engine once, at
// construction (a std::variant of filters); each step is one std::visit, never a dispatch per
// particle. Models written in Python are called once per step on whole arrays.
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "common.hpp"
#include "guard.hpp"
#include "params.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/models/linear_gaussian.hpp"
#include "vtrack/models/linear_gaussian_likelihood.hpp"
#include "vtrack/models/linear_transition.hpp"
#include "vtrack/models/motion.hpp"
#include "vtrack/models/range_bearing.hpp"
#include "vtrack/smc/mcmc.hpp"
#include "vtrack/smc/sir.hpp"

namespace vtrack::bindings {
namespace {

using models::LinearTransition;

// ---- Python models: called once per step with the whole (N, d) particle array --------------

// The particles as a new (N, d) float64 array: a copy, so a model may keep it or modify it (a
// few percent of what a vectorised NumPy model costs per particle).
py::object particles_array(const Eigen::MatrixXd& x) { return py::cast(x); }

struct PyMotion {
  static constexpr bool whole_array = true;
  py::object model;
  int d;
  py::object rng;  // numpy.random.Generator seeded from the filter's seed

  int dim() const { return d; }
  void propagate_all(const Eigen::MatrixXd& prev, Eigen::MatrixXd& next) const {
    py::gil_scoped_acquire gil;
    py::object out = model.attr("propagate")(particles_array(prev), rng);
    auto a = as_matrix(out, "propagate() result");
    if (a.shape(0) != prev.rows() || a.shape(1) != prev.cols()) {
      throw py::value_error("propagate() must return an array of shape (" +
                            std::to_string(prev.rows()) + ", " + std::to_string(prev.cols()) +
                            "), like its input");
    }
    next = matrix_map(a);
    if (!next.allFinite()) throw py::value_error("propagate() returned inf");
  }
};

struct PyObservation {
  static constexpr bool whole_array = true;
  py::object model;

  int min_state_dim() const { return 1; }
  void check(const Eigen::VectorXd& z) const {
    if (!z.allFinite()) throw InvalidArgument("z contains NaN or inf");
  }
  void log_likelihood_all(const Eigen::MatrixXd& x, const Eigen::VectorXd& z,
                          Eigen::VectorXd& out) const {
    py::gil_scoped_acquire gil;
    py::object result = model.attr("log_likelihood")(particles_array(x), py::cast(z));
    auto a = as_vector(result, "log_likelihood() result", Nan::Allowed);
    if (a.size() != x.rows()) {
      throw py::value_error("log_likelihood() must return " + std::to_string(x.rows()) +
                            " values (one per particle), got " + std::to_string(a.size()));
    }
    out = vector_map(a);  // NaN or +inf: the engine's InvalidArgument names the particle
  }
};

using Motion = std::variant<LinearTransition, PyMotion>;
using Observation =
    std::variant<models::LinearGaussianLikelihood, models::RangeBearingObservation, PyObservation>;

Motion motion_from(const py::handle& obj, std::uint64_t seed) {
  if (py::isinstance<LinearTransition>(obj)) return obj.cast<LinearTransition>();
  if (py::isinstance<models::LinearGaussianMotion>(obj)) {
    return LinearTransition::from_motion(obj.cast<models::LinearGaussianMotion>());
  }
  if (!py::hasattr(obj, "propagate")) {
    throw py::type_error(
        "motion must be a vtrack motion model (RandomWalk, ConstantVelocity, "
        "SecondOrderAutoRegressive, LinearGaussianMotion) or an object with a propagate(particles, "
        "rng) method, got " + type_name(obj));
  }
  if (!py::hasattr(obj, "dim")) {
    throw py::type_error("a Python motion model needs a `dim` attribute (the state dimension)");
  }
  const int d = obj.attr("dim").cast<int>();
  if (d < 1) throw py::value_error("motion.dim must be >= 1, got " + std::to_string(d));
  py::object rng = py::module_::import("numpy").attr("random").attr("default_rng")(
      py::make_tuple(seed, 0x5eedULL));
  return PyMotion{py::reinterpret_borrow<py::object>(obj), d, rng};
}

Observation observation_from(const py::handle& obj) {
  if (py::isinstance<models::RangeBearingObservation>(obj)) {
    return obj.cast<models::RangeBearingObservation>();
  }
  if (py::isinstance<models::LinearGaussianObservation>(obj)) {
    return models::LinearGaussianLikelihood(obj.cast<models::LinearGaussianObservation>());
  }
  if (!py::hasattr(obj, "log_likelihood")) {
    throw py::type_error(
        "observation must be a vtrack observation model (LinearGaussianObservation, "
        "RangeBearingObservation) or an object with a log_likelihood(particles, z) method, got " +
        type_name(obj));
  }
  return PyObservation{py::reinterpret_borrow<py::object>(obj)};
}

int motion_dim(const Motion& m) {
  return std::visit([](const auto& v) { return v.dim(); }, m);
}

// ---- ParticleFilter: SIR over the model combinations ---------------------------------------

template <class M, class O, typename Scalar = double>
using Sir = smc::Sir<M, O, smc::Bootstrap, Scalar>;
// Float states for the built-in models only: Python models take and return float64 arrays.
using SirVariant = std::variant<Sir<LinearTransition, models::LinearGaussianLikelihood>,
                                Sir<LinearTransition, models::RangeBearingObservation>,
                                Sir<LinearTransition, models::LinearGaussianLikelihood, float>,
                                Sir<LinearTransition, models::RangeBearingObservation, float>,
                                Sir<LinearTransition, PyObservation>,
                                Sir<PyMotion, models::LinearGaussianLikelihood>,
                                Sir<PyMotion, models::RangeBearingObservation>,
                                Sir<PyMotion, PyObservation>>;

// What both Python-facing filters share: dispatch on the variant of model types, and step.
// Every access goes through visit(), which holds the object's guard (guard.hpp): calls from two
// Python threads on one filter take turns (step releases the GIL), and a Python model that calls
// back into its own filter gets a RuntimeError instead of a deadlock. Call with the GIL held.
template <class Variant>
class VariantFilter {
 public:
  template <class F>
  auto visit(F&& fn) {
    ObjectGuard guard(this);
    return std::visit(std::forward<F>(fn), filter_);
  }
  template <class F>
  auto visit(F&& fn) const {
    ObjectGuard guard(this);
    return std::visit(std::forward<F>(fn), filter_);
  }

  Eigen::VectorXd step(const py::handle& z) {
    auto zz = as_vector(z, "z");
    const Eigen::VectorXd measurement = vector_map(zz);
    return visit([&](auto& f) {
      py::gil_scoped_release release;
      return Eigen::VectorXd(f.step(measurement));
    });
  }

 protected:
  explicit VariantFilter(Variant filter) : filter_(std::move(filter)) {}

  Variant filter_;
};

class ParticleFilter : public VariantFilter<SirVariant> {
 public:
  ParticleFilter(const py::handle& motion, const py::handle& observation, const py::handle& prior,
                 const smc::SirParams& params, bool single_precision)
      : VariantFilter(make(motion_from(motion, params.seed), observation_from(observation), prior,
                           params, single_precision)) {}

  Eigen::VectorXd predict() {
    return visit([&](auto& f) {
      py::gil_scoped_release release;
      return Eigen::VectorXd(f.predict());
    });
  }

 private:
  static SirVariant make(Motion motion, Observation observation, const py::handle& prior,
                         const smc::SirParams& params, bool single_precision) {
    const bool gaussian = py::isinstance<core::Gaussian>(prior);
    Eigen::MatrixXd particles;
    if (!gaussian) {
      auto p = as_matrix(prior, "prior");
      particles = matrix_map(p);
    }
    auto build = [&](auto tag, auto& m, auto& o) -> SirVariant {
      using F = Sir<std::decay_t<decltype(m)>, std::decay_t<decltype(o)>, decltype(tag)>;
      if (gaussian) return F(std::move(m), std::move(o), prior.cast<const core::Gaussian&>(), params);
      return F(std::move(m), std::move(o), std::move(particles), params);
    };
    return std::visit(
        [&](auto& m, auto& o) -> SirVariant {
          using M = std::decay_t<decltype(m)>;
          using O = std::decay_t<decltype(o)>;
          if constexpr (std::is_same_v<M, LinearTransition> && !std::is_same_v<O, PyObservation>) {
            if (single_precision) return build(float{}, m, o);
          } else if (single_precision) {
            throw py::type_error(
                "dtype='float32' needs built-in motion and observation models (Python models "
                "take and return float64 arrays)");
          }
          return build(double{}, m, o);
        },
        motion, observation);
  }
};

// ---- MCMCParticleFilter ------------------------------------------------------------------

template <class O>
using Mcmc = smc::McmcFilter<LinearTransition, O>;
using McmcVariant = std::variant<Mcmc<models::LinearGaussianLikelihood>,
                                 Mcmc<models::RangeBearingObservation>, Mcmc<PyObservation>>;

class McmcParticleFilter : public VariantFilter<McmcVariant> {
 public:
  McmcParticleFilter(const py::handle& motion, const py::handle& observation,
                     const core::Gaussian& prior, const smc::McmcParams& params)
      : VariantFilter(make(motion, observation_from(observation), prior, params)) {}


 private:
  static McmcVariant make(const py::handle& motion_obj, Observation observation,
                          const core::Gaussian& prior, const smc::McmcParams& params) {
    Motion motion = motion_from(motion_obj, params.seed);
    if (!std::holds_alternative<LinearTransition>(motion)) {
      throw py::type_error(
          "MCMCParticleFilter needs a built-in motion model (its chains run on the model's "
          "Gaussian noise); a Python propagate() cannot be evaluated as a density");
    }
    LinearTransition m = std::get<LinearTransition>(std::move(motion));
    return std::visit(
        [&](auto& o) -> McmcVariant {
          return Mcmc<std::decay_t<decltype(o)>>(m, std::move(o), prior, params);
        },
        observation);
  }
};

// Scalar or sequence -> per-component standard deviations; dims from the sequence's length.
std::vector<double> sigma_list(const py::handle& sigma) {
  if (py::isinstance<py::float_>(sigma) || py::isinstance<py::int_>(sigma)) {
    return {sigma.cast<double>()};
  }
  auto a = as_vector(sigma, "sigma");
  return std::vector<double>(a.data(), a.data() + a.size());
}

void bind_motion_models(py::module_& m) {
  py::class_<LinearTransition>(m, "LinearTransition", R"doc(
x_k = F x_{k-1} + S eps, eps ~ N(0, I): the form every built-in motion model of the particle
filters takes (S S^T = Q; S has fewer columns than rows when Q is singular).
)doc")
      .def_property_readonly("F", [](const LinearTransition& t) { return t.F(); })
      .def_property_readonly("Q", [](const LinearTransition& t) { return t.Q(); })
      .def_property_readonly("noise_factor", [](const LinearTransition& t) { return t.noise_factor(); },
                             "S with S S^T = Q (dim x noise_dim).")
      .def_property_readonly("dim", &LinearTransition::dim)
      .def_property_readonly("noise_dim", &LinearTransition::noise_dim);

  py::class_<models::RandomWalk, LinearTransition>(m, "RandomWalk", R"doc(
Random walk x_k = x_{k-1} + e, e ~ N(0, diag(sigma^2)) (mb-tbd paper eq. 22's motion). sigma is
one value or one per state component; dims (default: len(sigma), or 1) sets the dimension when
sigma is one value.
)doc")
      .def(py::init([](const py::handle& sigma, std::optional<int> dims) {
             models::RandomWalkParams p;
             p.sigma = sigma_list(sigma);
             p.dims = dims.value_or(0);
             return models::RandomWalk(p);
           }),
           py::arg("sigma") = 1.0, py::arg("dims") = py::none())
      .def_property_readonly("sigma", [](const models::RandomWalk& r) {
        return Eigen::VectorXd(r.noise_factor().diagonal());
      })
      .def("__repr__", [](const models::RandomWalk& r) {
        return "RandomWalk(dims=" + std::to_string(r.dim()) + ")";
      });

  const models::ConstantVelocityParams cv;
  py::class_<models::ConstantVelocity, LinearTransition>(m, "ConstantVelocity", R"doc(
Constant velocity in `axes` dimensions, state [p_1, v_1, p_2, v_2, ...], F = I (x) [[1, T], [0, 1]]
with T = period. noise="continuous": white-noise acceleration of power spectral density q,
Q = q (I (x) [[T^3/3, T^2/2], [T^2/2, T]]); noise="discrete": piecewise-constant acceleration of
variance q per period, Q = q (I (x) g g^T), g = [T^2/2, T] (rgbd-glmb eq. 7 with q = sigma_v^2;
singular, so MCMCParticleFilter(reference="all") refuses it).
)doc")
      .def(py::init([](int axes, double period, double q, const std::string& noise) {
             return models::ConstantVelocity(
                 {axes, period, q, models::parse_acceleration_noise(noise)});
           }),
           py::arg("axes") = cv.axes, py::arg("period") = cv.period, py::arg("q") = cv.q,
           py::arg("noise") = models::to_string(cv.noise))
      .def_property_readonly("axes", [](const models::ConstantVelocity& c) { return c.params().axes; })
      .def_property_readonly("period", [](const models::ConstantVelocity& c) { return c.params().period; })
      .def_property_readonly("q", [](const models::ConstantVelocity& c) { return c.params().q; })
      .def_property_readonly("noise", [](const models::ConstantVelocity& c) {
        return std::string(models::to_string(c.params().noise));
      })
      .def("__repr__", [](const models::ConstantVelocity& c) {
        return "ConstantVelocity(axes=" + std::to_string(c.params().axes) + ", period=" +
               value_text(c.params().period) + ", q=" + value_text(c.params().q) + ", noise='" +
               models::to_string(c.params().noise) + "')";
      });

  py::class_<models::SecondOrderAutoRegressive, LinearTransition>(m, "SecondOrderAutoRegressive", R"doc(
Second-order auto-regressive motion, part-based-graphical-model-pf eq. 13:
X_k = 2 X_{k-1} - X_{k-2} + U_{k-1}, U ~ N(0, diag(sigma^2)). The state carries both X_k and
X_{k-1}: [X_k, X_{k-1}] (2 dims components), so a prior and observation models see 2 dims
components, X_k first. sigma is one value or one per component of X.
)doc")
      .def(py::init([](const py::handle& sigma, std::optional<int> dims) {
             models::SecondOrderAutoRegressiveParams p;
             p.sigma = sigma_list(sigma);
             p.dims = dims.value_or(0);
             return models::SecondOrderAutoRegressive(p);
           }),
           py::arg("sigma") = 1.0, py::arg("dims") = py::none())
      .def("__repr__", [](const models::SecondOrderAutoRegressive& s) {
        return "SecondOrderAutoRegressive(dims=" + std::to_string(s.dim() / 2) + ")";
      });

}

void bind_range_bearing(py::module_& m) {
  const models::RangeBearingParams rb;
  py::class_<models::RangeBearingObservation>(m, "RangeBearingObservation", R"doc(
Range and bearing of a point target from a sensor: z = [|p - s|, atan2(p_y - s_y, p_x - s_x)] plus
independent N(0, sigma_range^2) and N(0, sigma_bearing^2) noise, p = (x[position[0]],
x[position[1]]) (default (0, 2): a ConstantVelocity state [p_x, v_x, p_y, v_y]). The bearing
residual is wrapped to (-pi, pi].
)doc")
      .def(py::init([](double sigma_range, double sigma_bearing, std::pair<double, double> sensor,
                       std::pair<int, int> position) {
             return models::RangeBearingObservation(
                 {sigma_range, sigma_bearing, sensor.first, sensor.second, position.first,
                  position.second});
           }),
           py::arg("sigma_range") = rb.sigma_range, py::arg("sigma_bearing") = rb.sigma_bearing,
           py::arg("sensor") = std::make_pair(rb.sensor_x, rb.sensor_y),
           py::arg("position") = std::make_pair(rb.x_index, rb.y_index))
      .def(
          "log_likelihood",
          [](const models::RangeBearingObservation& o, const py::handle& particles,
             const py::handle& z) {
            auto x = as_matrix(particles, "particles");
            if (x.shape(1) < o.min_state_dim()) {
              throw py::value_error("particles need at least " +
                                    std::to_string(o.min_state_dim()) + " columns");
            }
            auto zz = as_vector(z, "z");
            const Eigen::VectorXd measurement = vector_map(zz);
            o.check(measurement);
            const Eigen::MatrixXd states = matrix_map(x);
            Eigen::VectorXd out(states.rows());
            o.log_likelihood(models::StatesView<double>(states), measurement, out.data());
            return out;
          },
          py::arg("particles"), py::arg("z"), "log p(z | x) for each row of particles (N, d).")
      .def_property_readonly("sigma_range", [](const models::RangeBearingObservation& o) { return o.params().sigma_range; })
      .def_property_readonly("sigma_bearing", [](const models::RangeBearingObservation& o) { return o.params().sigma_bearing; })
      .def_property_readonly("sensor", [](const models::RangeBearingObservation& o) {
        return std::make_pair(o.params().sensor_x, o.params().sensor_y);
      })
      .def_property_readonly("position", [](const models::RangeBearingObservation& o) {
        return std::make_pair(o.params().x_index, o.params().y_index);
      })
      .def("__repr__", [](const models::RangeBearingObservation& o) {
        return "RangeBearingObservation(sigma_range=" + value_text(o.params().sigma_range) +
               ", sigma_bearing=" + value_text(o.params().sigma_bearing) + ")";
      });
}

// Properties shared by both filters' bindings.
template <class Cls, class Wrapper>
void common_estimates(Cls& cls) {
  cls.def_property_readonly(
         "mean", [](const Wrapper& w) { return w.visit([](const auto& f) { return Eigen::VectorXd(f.mean()); }); },
         "The weighted mean of the last step (eq. 8), as step() returned it.")
      .def_property_readonly(
          "map_estimate",
          [](const Wrapper& w) { return w.visit([](const auto& f) { return Eigen::VectorXd(f.map_estimate()); }); },
          "The particle of largest weight (MCMC: of largest posterior density) of the last step.")
      .def_property_readonly(
          "acceptance_rate",
          [](const Wrapper& w) { return w.visit([](const auto& f) { return f.acceptance_rate(); }); },
          "Accepted fraction of the last step's Metropolis-Hastings proposals (0 when none).")
      .def_property_readonly(
          "steps", [](const Wrapper& w) { return w.visit([](const auto& f) { return f.steps(); }); });
}

void bind_particle_filter(py::module_& m) {
  py::class_<ParticleFilter> pf(m, "ParticleFilter", R"doc(
Sequential importance resampling particle filter (particle-filters-human-vehicle §1.2,
part-based-graphical-model-pf Section 2) on vtrack's SMC engine.

step(z) propagates every particle with the motion model, weights it by p(z | x) (eqs. 5-6),
returns the weighted mean (eq. 8) and resamples when N_eff <= ess_threshold * N (eq. 7; 1.0:
every step, 0.0: never). `prior` is a Gaussian for x_0, one step before the first measurement
(or an (N, d) array of initial particles). resample_move_steps = k > 0 adds k Metropolis-Hastings
moves per particle after each resampling (a random walk on the particle's process noise, step
move_scale). threads > 1 (or 0: all) runs blocks of particles in parallel with identical results.
dtype="float32" keeps the states in single precision (built-in models only): less memory traffic
and wider vectors for large N; weights, estimates and log_evidence stay float64, and the random
draws are the same as float64's.

motion: RandomWalk, ConstantVelocity, SecondOrderAutoRegressive, LinearGaussianMotion, or an object
with `dim` and a vectorised propagate(particles, rng) -> particles (particles (N, d); rng a
numpy.random.Generator seeded from `seed`). observation: LinearGaussianObservation,
RangeBearingObservation, or an object with a vectorised log_likelihood(particles, z) -> (N,) log
weights. Python models are called once per step on whole arrays (see docs/smc.md for their cost).
If every particle has likelihood zero the update is skipped (weights kept, log_evidence -inf).
)doc");
  pf.def(py::init([](const py::handle& motion, const py::handle& observation,
                     const py::handle& prior, const py::handle& dtype, const py::kwargs& kwargs) {
           const auto name =
               py::module_::import("numpy").attr("dtype")(dtype).attr("name").cast<std::string>();
           if (name != "float64" && name != "float32") {
             throw py::value_error("dtype must be float64 or float32, got " + name);
           }
           return ParticleFilter(motion, observation, prior,
                                 params_from_kwargs<smc::SirParams>(kwargs, "particle filter"),
                                 name == "float32");
         }),
         py::arg("motion"), py::arg("observation"), py::kw_only(), py::arg("prior"),
         py::arg("dtype") = "float64")
      .def("step", &ParticleFilter::step, py::arg("z"),
           "One predict-update(-resample) cycle with measurement z; returns the weighted mean.")
      .def("predict", &ParticleFilter::predict,
           "Propagate without a measurement (weights kept); returns the weighted mean.")
      .def_property_readonly(
          "particles",
          [](const ParticleFilter& w) {
            return w.visit([](const auto& f) {
              using States = std::decay_t<decltype(f.particles().states())>;
              return py::cast(States(f.particles().states()));
            });
          },
          "The particles (N, d) after the last step (a copy, of the filter's dtype; resampled if "
          "the step resampled).")
      .def_property_readonly(
          "weights",
          [](const ParticleFilter& w) {
            return w.visit([](const auto& f) { return Eigen::VectorXd(f.particles().weights()); });
          },
          "Normalised weights of `particles`.")
      .def_property_readonly(
          "log_weights",
          [](const ParticleFilter& w) {
            return w.visit([](const auto& f) { return Eigen::VectorXd(f.particles().log_weights()); });
          },
          "Normalised log weights of `particles` (log-sum-exp = 0).")
      .def_property_readonly(
          "log_evidence",
          [](const ParticleFilter& w) { return w.visit([](const auto& f) { return f.log_evidence(); }); },
          "Sum over steps of the log normalisers log sum_i w_i p(z | x_i): the estimate of "
          "log p(z_1, ..., z_k).")
      .def_property_readonly(
          "ess", [](const ParticleFilter& w) { return w.visit([](const auto& f) { return f.ess(); }); },
          "N_eff = 1 / sum w_i^2 of the last update, before resampling (eq. 7).")
      .def_property_readonly(
          "resampled",
          [](const ParticleFilter& w) { return w.visit([](const auto& f) { return f.resampled(); }); },
          "Whether the last step resampled.")
      .def_property_readonly(
          "n_particles",
          [](const ParticleFilter& w) { return w.visit([](const auto& f) { return static_cast<int>(f.particles().size()); }); })
      .def_property_readonly(
          "dim", [](const ParticleFilter& w) { return w.visit([](const auto& f) { return static_cast<int>(f.particles().dim()); }); });
  common_estimates<decltype(pf), ParticleFilter>(pf);
  def_params<smc::SirParams>(pf, [](const ParticleFilter& w) {
    return w.visit([](const auto& f) { return f.params(); });
  });
}

void bind_mcmc_filter(py::module_& m) {
  py::class_<McmcParticleFilter> mcmc(m, "MCMCParticleFilter", R"doc(
MCMC particle filter (particle-filters-human-vehicle §1.3, §3.3): each step(z) runs one
Metropolis-Hastings chain of burn_in + thinning * n_particles proposals and keeps every
thinning-th state after the burn-in as the n_particles unweighted samples of p(x_k | Z^k).
reference="all" targets p(z|x) sum_i p(x | x_{k-1}^i) (O(N n_particles); needs non-singular
process noise); "random", "map" and "mean" target p(z|x) p(x | x*) with x* a random previous
sample (Khan et al.), the most likely one, or the previous estimate (O(N)). Proposals are a
random walk shaped by the process noise, of scale proposal_scale. step() returns the sample mean.
The motion model must be a built-in one; the observation may be a Python object (called once per
chain step, on one particle).
)doc");
  mcmc.def(py::init([](const py::handle& motion, const py::handle& observation,
                       const core::Gaussian& prior, const py::kwargs& kwargs) {
             return McmcParticleFilter(
                 motion, observation, prior,
                 params_from_kwargs<smc::McmcParams>(kwargs, "MCMC particle filter"));
           }),
           py::arg("motion"), py::arg("observation"), py::kw_only(), py::arg("prior"))
      .def("step", &McmcParticleFilter::step, py::arg("z"),
           "One chain for measurement z; returns the sample mean.")
      .def_property_readonly(
          "particles",
          [](const McmcParticleFilter& w) { return w.visit([](const auto& f) { return Eigen::MatrixXd(f.particles()); }); },
          "The n_particles kept samples (n_particles, d), in chain order.")
      .def_property_readonly(
          "log_target",
          [](const McmcParticleFilter& w) { return w.visit([](const auto& f) { return Eigen::VectorXd(f.log_target()); }); },
          "log of the chain's target density (up to a constant) at each kept sample.")
      .def_property_readonly(
          "proposals",
          [](const McmcParticleFilter& w) { return w.visit([](const auto& f) { return f.proposals(); }); },
          "Proposals made by the last step's chain: burn_in + thinning * n_particles.");
  common_estimates<decltype(mcmc), McmcParticleFilter>(mcmc);
  def_params<smc::McmcParams>(mcmc, [](const McmcParticleFilter& w) {
    return w.visit([](const auto& f) { return f.params(); });
  });
}

}  // namespace

void bind_smc(py::module_& m) {
  bind_motion_models(m);
  bind_range_bearing(m);
  bind_particle_filter(m);
  bind_mcmc_filter(m);
}

}  // namespace vtrack::bindings
