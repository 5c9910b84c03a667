#pragma once
// Multi-object distances of the OSPA family (vtrack::metrics), with optimal matchings from
// vtrack::assign::linear_assignment. A point set is an N x d matrix, one point per row; the base
// distance between points is Euclidean. N = 0 is the empty set (any d).
//
// Arguments are checked: c > 0 finite, p >= 1 finite, all entries finite (except the NaN rows that
// mark absence in OSPA(2) tracks), equal point dimensions; InvalidArgument names the offender.
#include <vector>

#include <Eigen/Core>

namespace vtrack::metrics {

// OSPA (Schuhmacher, Vo & Vo 2008, "A consistent metric for performance evaluation of
// multi-object filters", IEEE TSP 56(8), eq. 3) with cut-off c and order p: for |X| = m <= n = |Y|,
//   ( (1/n) (min_pi sum_i min(c, |x_i - y_pi(i)|)^p + c^p (n - m)) )^(1/p),
// symmetric in X and Y; 0 when both are empty, c when exactly one is.
struct OspaResult {
  double distance = 0.0;
  double localisation = 0.0;  // ((1/n) min_pi sum_i min(c, d)^p)^(1/p)
  double cardinality = 0.0;   // ((1/n) c^p (n - m))^(1/p); distance^p = the sum of their p-th powers
};
OspaResult ospa(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::Ref<const Eigen::MatrixXd>& y,
          double c, double p);

// GOSPA with alpha = 2 (Rahmathullah, Garcia-Fernandez & Svensson 2017, "Generalized optimal
// sub-pattern assignment metric", FUSION, Proposition 1): for ground truth X and estimates Y,
//   d^p = min over partial assignments gamma of  sum_{(i,j) in gamma} |x_i - y_j|^p
//         + c^p / 2 (|X| - |gamma|) + c^p / 2 (|Y| - |gamma|),
// where only pairs closer than c are worth assigning. Not normalised by the cardinality, so it
// grows with the number of errors. The p-th-power terms are returned separately.
struct GospaResult {
  double distance = 0.0;       // (localisation + missed + false_targets)^(1/p)
  double localisation = 0.0;   // sum of |x - y|^p over the assigned pairs
  double missed = 0.0;         // c^p / 2 per unassigned ground-truth point
  double false_targets = 0.0;  // c^p / 2 per unassigned estimate
  int n_assigned = 0, n_missed = 0, n_false = 0;
};
GospaResult gospa(const Eigen::Ref<const Eigen::MatrixXd>& truth,
            const Eigen::Ref<const Eigen::MatrixXd>& estimates, double c, double p);

// OSPA(2), the OSPA metric between sets of tracks (Beard, Vo & Vo 2017, "OSPA(2): Using the OSPA
// metric to evaluate multi-target tracking performance", ICCAIS; and 2020, "A solution for
// large-scale multi-object tracking", IEEE TSP 68), over a window of T time steps.
//
// A track is a T x d matrix whose row t is its state at step t, or all NaN where the track does
// not exist; a track that exists at no step of the window is ignored. The base distance between
// tracks x and y is the time-averaged OSPA between their (at most one-point) states over the
// steps D where either exists, with the same cut-off c:
//   dt(x, y) = (1/|D|) sum_{t in D} e_t,  e_t = min(c, |x_t - y_t|) if both exist, else c,
// (OSPA of two sets of at most one point does not depend on its order). OSPA(2) is then the OSPA
// of order p with cut-off c between the two track sets under dt, so it lies in [0, c]. For a
// sliding-window curve, call it on each window's slice of the tracks.
OspaResult ospa2(const std::vector<Eigen::MatrixXd>& x, const std::vector<Eigen::MatrixXd>& y,
           double c, double p);

}  // namespace vtrack::metrics
