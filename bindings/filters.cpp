// Bindings of vtrack::assign (linear assignment, Murty) and vtrack::metrics (OSPA family).
#include <vector>

#include <limits>

#include "args.hpp"
#include "common.hpp"
#include "guard.hpp"
#include "vtrack/filters/assign.hpp"
#include "vtrack/filters/metrics.hpp"

namespace vtrack::bindings {
namespace {

// (n_tracks, T, d) float array, NaN rows = absent, as one T x d matrix per track.
std::vector<Eigen::MatrixXd> tracks_from(const py::handle& obj, const char* name) {
  auto a = as_array(obj, name, 3, Nan::Allowed);
  const auto steps = static_cast<Eigen::Index>(a.shape(1)), dim = static_cast<Eigen::Index>(a.shape(2));
  std::vector<Eigen::MatrixXd> tracks;
  tracks.reserve(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t k = 0; k < a.shape(0); ++k) {
    // Not a.data(k, 0, 0): its bounds check raises IndexError when T or d is 0 (a C-ordered
    // array of such a shape is still valid, and the library names the problem).
    tracks.emplace_back(RowMatrixMap(a.data() + k * steps * dim, steps, dim));
  }
  return tracks;
}

}  // namespace

namespace {

void bind_assignment(py::module_& m) {
  m.def(
      "linear_assignment",
      [](const py::handle& cost) {
        auto c = as_matrix(cost, "cost");
        assign::LinearAssignment s;
        {
          py::gil_scoped_release release;
          s = assign::linear_assignment(matrix_map(c));
        }
        const auto n = static_cast<py::ssize_t>(s.col_of_row.size());
        py::array_t<std::int64_t> rows(n), cols(n);
        for (py::ssize_t i = 0; i < n; ++i) {
          rows.mutable_at(i) = i;
          cols.mutable_at(i) = s.col_of_row[static_cast<std::size_t>(i)];
        }
        return py::make_tuple(rows, cols);
      },
      py::arg("cost"), R"doc(
Optimal assignment of an n x m cost matrix with n <= m: every row gets a distinct column and the
sum of the chosen entries is minimal. Entries may be negative; +inf marks a forbidden pair.

Returns (rows, cols), int64 arrays with rows = arange(n) and cols[i] the column of row i, so
cost[rows, cols].sum() is the optimum (as scipy.optimize.linear_sum_assignment, for n <= m).
Shortest augmenting paths (Jonker-Volgenant, in Crouse's rectangular form). Raises ValueError
for NaN or -inf entries, n > m, or a matrix with no feasible assignment; TypeError for a
non-numeric dtype.
)doc");

  m.def(
      "murty",
      [](const py::handle& cost, const py::handle& k_arg) {
        auto c = as_matrix(cost, "cost");
        const std::int64_t k = int_arg(k_arg, "k", 1, std::numeric_limits<std::int64_t>::max());
        assign::RankedAssignments r;
        {
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          r = assign::murty(matrix_map(c), k);
        }
        return py::make_tuple(r.assignments, r.costs);
      },
      py::arg("cost"), py::arg("k"), R"doc(
The k best assignments of an n x m cost matrix (n <= m, +inf = forbidden), by Murty's method with
the Miller-Stone-Cox speed-ups.

Returns (assignments, costs): assignments is a k' x n int64 array whose row r gives each row's
column in the r-th best assignment, costs the k' totals in non-decreasing order. k' < k when
fewer than k feasible assignments exist (k' = 0 if none). Equal costs come in unspecified order;
all assignments are distinct. Raises ValueError for NaN or -inf entries, n > m or k <= 0.
)doc");

  m.def(
      "gibbs_assignments",
      [](const py::handle& cost, const py::handle& sweeps_arg, const py::handle& rng) {
        auto c = as_matrix(cost, "cost");
        const std::int64_t sweeps =
            int_arg(sweeps_arg, "sweeps", 1, std::numeric_limits<std::int64_t>::max());
        RngArg engine(rng);
        assign::SampledAssignments s;
        {
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          s = assign::gibbs_assignments(matrix_map(c), sweeps, engine.get());
        }
        return py::make_tuple(s.assignments, s.costs, s.visits);
      },
      py::arg("cost"), py::arg("sweeps"), py::arg("rng") = 0, R"doc(
Distinct assignments of an n x m cost matrix (n <= m, +inf = forbidden) visited by a Gibbs sampler
whose stationary distribution is proportional to exp(-total cost): the randomised alternative to
Murty of Vo, Vo & Hoang (IEEE TSP 2017, section IV-B). The chain starts at the optimal assignment
and runs `sweeps` states (one sweep resamples every row from its conditional).

Returns (assignments, costs, visits): the k' <= sweeps distinct assignments (k' x n int64, each
row's column), their totals in non-decreasing order, and how many states of the chain equalled
each (visits / sweeps estimates the probabilities). k' = 0 for an infeasible matrix. rng: a
vtrack.Rng (advanced in place) or an int seed. Raises ValueError for NaN or -inf entries, n > m
or sweeps <= 0.
)doc");
}

void bind_metrics(py::module_& m) {
  py::class_<metrics::OspaResult>(m, "OspaResult",
                                  "An OSPA or OSPA(2) distance and its two components.")
      .def_readonly("distance", &metrics::OspaResult::distance)
      .def_readonly("localisation", &metrics::OspaResult::localisation,
                    "((1/n) sum of matched cut-off distances^p)^(1/p)")
      .def_readonly("cardinality", &metrics::OspaResult::cardinality,
                    "((1/n) c^p |n - m|)^(1/p); distance^p is the sum of both p-th powers")
      .def("__float__", [](const metrics::OspaResult& r) { return r.distance; })
      .def("__repr__", [](const metrics::OspaResult& r) {
        return "OspaResult(distance=" + py::repr(py::float_(r.distance)).cast<std::string>() +
               ", localisation=" + py::repr(py::float_(r.localisation)).cast<std::string>() +
               ", cardinality=" + py::repr(py::float_(r.cardinality)).cast<std::string>() + ")";
      });

  py::class_<metrics::GospaResult>(m, "GospaResult",
                                   "A GOSPA distance (alpha = 2) and its decomposition.")
      .def_readonly("distance", &metrics::GospaResult::distance,
                    "(localisation + missed + false_targets)^(1/p)")
      .def_readonly("localisation", &metrics::GospaResult::localisation,
                    "sum of |x - y|^p over the assigned pairs")
      .def_readonly("missed", &metrics::GospaResult::missed, "c^p / 2 per missed truth point")
      .def_readonly("false_targets", &metrics::GospaResult::false_targets,
                    "c^p / 2 per false estimate")
      .def_readonly("n_assigned", &metrics::GospaResult::n_assigned)
      .def_readonly("n_missed", &metrics::GospaResult::n_missed)
      .def_readonly("n_false", &metrics::GospaResult::n_false)
      .def("__float__", [](const metrics::GospaResult& r) { return r.distance; })
      .def("__repr__", [](const metrics::GospaResult& r) {
        return "GospaResult(distance=" + py::repr(py::float_(r.distance)).cast<std::string>() +
               ", n_assigned=" + std::to_string(r.n_assigned) +
               ", n_missed=" + std::to_string(r.n_missed) +
               ", n_false=" + std::to_string(r.n_false) + ")";
      });

  m.def(
      "ospa",
      [](const py::handle& x, const py::handle& y, const py::handle& c_arg, const py::handle& p_arg) {
        const double c = real_arg(c_arg, "c"), p = real_arg(p_arg, "p");
        auto a = as_matrix(x, "x");
        auto b = as_matrix(y, "y");
        py::gil_scoped_release release;
        return metrics::ospa(matrix_map(a), matrix_map(b), c, p);
      },
      py::arg("x"), py::arg("y"), py::arg("c"), py::arg("p") = 1.0, R"doc(
OSPA distance (Schuhmacher, Vo & Vo 2008) between point sets x (N x d) and y (M x d), Euclidean
base distance cut off at c, order p >= 1. Use an (0, d) array for the empty set. Returns an
OspaResult (float() gives the distance): 0 for two empty sets, c when exactly one is empty.
)doc");

  m.def(
      "gospa",
      [](const py::handle& truth, const py::handle& estimates, const py::handle& c_arg,
         const py::handle& p_arg) {
        const double c = real_arg(c_arg, "c"), p = real_arg(p_arg, "p");
        auto a = as_matrix(truth, "truth");
        auto b = as_matrix(estimates, "estimates");
        py::gil_scoped_release release;
        return metrics::gospa(matrix_map(a), matrix_map(b), c, p);
      },
      py::arg("truth"), py::arg("estimates"), py::arg("c"), py::arg("p") = 1.0, R"doc(
GOSPA distance with alpha = 2 (Rahmathullah, Garcia-Fernandez & Svensson 2017) between ground
truth (N x d) and estimates (M x d): assigned pairs cost |x - y|^p, each missed truth point and
each false estimate c^p / 2. Returns a GospaResult with the distance and its decomposition.
)doc");

  m.def(
      "ospa2",
      [](const py::handle& x, const py::handle& y, const py::handle& c_arg, const py::handle& p_arg) {
        const double c = real_arg(c_arg, "c"), p = real_arg(p_arg, "p");
        const auto tx = tracks_from(x, "x");
        const auto ty = tracks_from(y, "y");
        py::gil_scoped_release release;
        return metrics::ospa2(tx, ty, c, p);
      },
      py::arg("x"), py::arg("y"), py::arg("c"), py::arg("p") = 1.0, R"doc(
OSPA(2) track metric (Beard, Vo & Vo 2017/2020) between two sets of tracks over a window of T
steps. x and y are (n_tracks, T, d) arrays; a row of NaN marks a step where the track does not
exist, and tracks that exist at no step are ignored. The distance between two tracks is the
mean, over the steps where either exists, of min(c, |x_t - y_t|) (or c where only one exists);
OSPA(2) is the OSPA of order p, cut-off c between the track sets under that distance. For the
usual sliding-window curve, call it on x[:, k - L + 1 : k + 1] and y[:, k - L + 1 : k + 1].
Returns an OspaResult.
)doc");
}

}  // namespace

void bind_filters(py::module_& m) {
  bind_assignment(m);
  bind_metrics(m);
}

}  // namespace vtrack::bindings
