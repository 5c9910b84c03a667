// Bindings of vtrack::core: random engine, log-domain weights, resampling, Gaussian.
#include <optional>

#include "common.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/core/weights.hpp"

namespace vtrack::bindings {
namespace {

py::ssize_t checked_size(py::ssize_t size, const char* name) {
  if (size < 0) throw py::value_error(std::string(name) + " must be >= 0, got " + std::to_string(size));
  return size;
}

template <typename T, typename Fill>
py::array_t<T> draw(core::Rng& rng, py::ssize_t size, Fill fill) {
  py::array_t<T> out(checked_size(size, "size"));
  {
    py::gil_scoped_release release;
    fill(rng, out.mutable_data(), static_cast<std::size_t>(size));
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
      .def(py::init<std::uint64_t, std::uint64_t>(), py::arg("seed") = 0, py::arg("stream") = 0)
      .def(
          "uniform",
          [](core::Rng& rng, py::ssize_t size) {
            return draw<double>(rng, size, [](core::Rng& r, double* p, std::size_t n) {
              r.fill_uniform(p, n);
            });
          },
          py::arg("size"), "`size` draws uniform on [0, 1) as float64.")
      .def(
          "normal",
          [](core::Rng& rng, py::ssize_t size) {
            return draw<double>(rng, size, [](core::Rng& r, double* p, std::size_t n) {
              r.fill_normal(p, n);
            });
          },
          py::arg("size"), "`size` standard normal draws as float64.")
      .def("next_uint64", &core::Rng::next, "The next raw 64-bit output.")
      .def("jump", &core::Rng::jump, "Advance the state by 2^128 draws.");

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
      [](const py::handle& weights, const py::handle& rng, std::optional<py::ssize_t> count,
         const std::string& method) {
        auto a = as_vector(weights, "weights");
        const auto scheme = core::parse_resampling_scheme(method);
        const py::ssize_t m_count = count ? checked_size(*count, "count") : a.size();
        core::Rng storage;
        core::Rng& engine = rng_from(rng, storage);
        py::array_t<std::int64_t> ancestors(m_count);
        {
          py::gil_scoped_release release;
          core::resample(scheme, vector_map(a), static_cast<std::size_t>(m_count), engine,
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
          [](const core::Gaussian& g, const py::handle& rng, std::optional<py::ssize_t> n)
              -> py::object {
            core::Rng storage;
            core::Rng& engine = rng_from(rng, storage);
            if (!n) return py::cast(Eigen::VectorXd(g.sample(engine)));
            Eigen::MatrixXd xs;
            {
              py::gil_scoped_release release;
              xs = g.sample(engine, checked_size(*n, "n")).transpose();
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
