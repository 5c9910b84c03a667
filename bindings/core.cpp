// Bindings of vtrack::core: random engine, log-domain weights, resampling, Gaussian.
#include <optional>

#include <limits>

#include "args.hpp"
#include "common.hpp"
#include "guard.hpp"
#include "params.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/core/weights.hpp"

namespace vtrack::bindings {
namespace {

// A count argument: an int in [0, PY_SSIZE_T_MAX] (TypeError/ValueError naming it).
py::ssize_t count_arg(const py::handle& value, const char* name) {
  return static_cast<py::ssize_t>(int_arg(value, name, 0, std::numeric_limits<py::ssize_t>::max()));
}

// `size` draws filled in chunks of 2^20 (a multiple of the normal sampler's 256-value block, so
// the draws equal one fill's), with Ctrl-C polled between chunks and the Rng's guard held.
template <typename T, typename Fill>
py::array_t<T> draw(core::Rng& rng, const py::handle& size_arg, Fill fill) {
  ObjectGuard guard(&rng);
  const auto size = static_cast<std::size_t>(count_arg(size_arg, "size"));
  check_allocation(static_cast<double>(size) * sizeof(T), "size = " + std::to_string(size) + " draws");
  py::array_t<T> out(static_cast<py::ssize_t>(size));
  PythonInterrupts interrupts;
  py::gil_scoped_release release;
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  for (std::size_t done = 0; done < size; done += kChunk) {
    core::poll_interrupt();
    fill(rng, out.mutable_data() + done, std::min(kChunk, size - done));
  }
  return out;
}

}  // namespace

namespace {

void bind_random_and_weights(py::module_& m) {
  py::class_<core::Rng>(m, "Rng", R"doc(
Seeded random engine (xoshiro256**). The same seed and stream give the same draws on every run
and platform. `stream` selects one of 2^128 non-overlapping sub-sequences of the seed, for
independent generators (one per thread or per tracker) from one seed.
)doc")
      .def(py::init([](const py::handle& seed, const py::handle& stream) {
             const auto as_u64 = [](const py::handle& v, const char* name) {
               return std::get<std::uint64_t>(parameter_from_python(name, core::ParameterKind::seed, 0, v));
             };
             const std::uint64_t s = as_u64(seed, "seed"), k = as_u64(stream, "stream");
             PythonInterrupts interrupts;  // O(stream) jumps
             py::gil_scoped_release release;
             return core::Rng(s, k);
           }),
           py::arg("seed") = 0, py::arg("stream") = 0)
      .def(
          "uniform",
          [](core::Rng& rng, const py::handle& size) {
            return draw<double>(rng, size, [](core::Rng& r, double* p, std::size_t n) {
              r.fill_uniform(p, n);
            });
          },
          py::arg("size"), "`size` draws uniform on [0, 1) as float64.")
      .def(
          "normal",
          [](core::Rng& rng, const py::handle& size) {
            return draw<double>(rng, size, [](core::Rng& r, double* p, std::size_t n) {
              r.fill_normal(p, n);
            });
          },
          py::arg("size"), "`size` standard normal draws as float64.")
      .def("next_uint64", guarded(&core::Rng::next), "The next raw 64-bit output.")
      .def("jump", guarded(&core::Rng::jump), "Advance the state by 2^128 draws.");

  m.def(
      "log_sum_exp",
      [](const py::handle& log_weights) {
        auto a = as_vector(log_weights, "log_weights");
        return core::log_sum_exp(vector_map(a));
      },
      py::arg("log_weights"),
      "log(sum(exp(log_weights))), stable; -inf for empty input or all -inf.");

  m.def(
      "normalize_log_weights",
      [](const py::handle& log_weights) {
        auto a = as_vector(log_weights, "log_weights");
        Eigen::VectorXd weights;
        double total;
        {
          py::gil_scoped_release release;
          total = core::normalize_log_weights(vector_map(a), weights);
        }
        return py::make_tuple(weights, total);
      },
      py::arg("log_weights"),
      "Return (weights, log_total): normalised linear weights and log_sum_exp(log_weights). "
      "All -inf gives uniform weights and log_total = -inf.");

  m.def(
      "effective_sample_size",
      [](const py::handle& weights, bool log) {
        auto a = as_vector(weights, "weights");
        return log ? core::effective_sample_size_log(vector_map(a))
                   : core::effective_sample_size(vector_map(a));
      },
      py::arg("weights"), py::kw_only(), py::arg("log") = false,
      "N_eff = 1 / sum(w^2) of the normalised weights (part-based paper eq. 7); 0 when all "
      "weights vanish. With log=True the input is unnormalised log weights.");

  m.def(
      "resample",
      [](const py::handle& weights, const py::handle& rng, const py::handle& count,
         const py::handle& method) {
        auto a = as_vector(weights, "weights");
        const auto scheme = core::parse_resampling_scheme(str_arg(method, "method"));
        const py::ssize_t m_count = count.is_none() ? a.size() : count_arg(count, "count");
        check_allocation(static_cast<double>(m_count) * 8.0,
                         "count = " + std::to_string(m_count) + " ancestors");
        RngArg engine(rng);
        py::array_t<std::int64_t> ancestors(m_count);
        {
          py::gil_scoped_release release;
          core::resample(scheme, vector_map(a), static_cast<std::size_t>(m_count), engine.get(),
                         ancestors.mutable_data());
        }
        return ancestors;
      },
      py::arg("weights"), py::arg("rng"), py::arg("count") = py::none(),
      py::arg("method") = "systematic",
      "Ancestor indices (int64, sorted) of `count` draws (default len(weights)) by "
      "'multinomial', 'stratified', 'systematic' or 'residual' resampling. Weights must be "
      "finite, non-negative and not all zero; they need not sum to one.");
}

void bind_gaussian(py::module_& m) {
  py::class_<core::Gaussian>(m, "Gaussian", "Multivariate normal N(mean, cov).")
      .def(py::init([](const py::handle& mean, const py::handle& cov) {
             auto mu = as_vector(mean, "mean");
             auto c = as_matrix(cov, "cov");
             return core::Gaussian(vector_map(mu), matrix_map(c));
           }),
           py::arg("mean"), py::arg("cov"))
      .def_property_readonly("dim", &core::Gaussian::dim)
      .def_property_readonly("mean", &core::Gaussian::mean)
      .def_property_readonly("cov", &core::Gaussian::covariance)
      .def_property_readonly("cholesky", &core::Gaussian::cholesky)
      .def(
          "sample",
          [](const core::Gaussian& g, const py::handle& rng, const py::handle& n)
              -> py::object {
            RngArg engine(rng);
            if (n.is_none()) return py::cast(Eigen::VectorXd(g.sample(engine.get())));
            const py::ssize_t count = count_arg(n, "n");
            const std::string what = "n = " + std::to_string(count) + " samples of dimension " +
                                     std::to_string(g.dim());
            check_allocation(3.0 * static_cast<double>(count) * g.dim() * sizeof(double), what);
            Eigen::MatrixXd xs;
            try {
              py::gil_scoped_release release;
              xs = g.sample(engine.get(), count).transpose();
            } catch (const std::bad_alloc&) {
              throw_memory_error(what);
            }
            return py::cast(xs);
          },
          py::arg("rng"), py::arg("n") = py::none(),
          "One sample of shape (dim,), or n samples of shape (n, dim).")
      .def(
          "log_pdf",
          [](const core::Gaussian& g, const py::handle& x) -> py::object {
            py::array a = py::array::ensure(x);
            if (a && a.ndim() == 2) {
              auto xs = as_matrix(x, "x");
              return py::cast(Eigen::VectorXd(g.log_density_columns(matrix_map(xs).transpose())));
            }
            auto v = as_vector(x, "x");
            return py::float_(g.log_density(vector_map(v)));
          },
          py::arg("x"), "Log-density of a point (dim,) or of each row of (n, dim).");
}

}  // namespace

void bind_core(py::module_& m) {
  bind_random_and_weights(m);
  bind_gaussian(m);
}

}  // namespace vtrack::bindings
