#pragma once
// Linear assignment and Murty's k-best ranked assignments (vtrack::assign).
//
// Problem: an n x m cost matrix C with n <= m; assign every row a distinct column, minimising the
// sum of the chosen entries. Entries may be negative (GLMB costs are negative log-likelihood
// ratios); +inf marks a forbidden pair. NaN and -inf are rejected.
//
// The solver is the shortest augmenting path method of Jonker & Volgenant (1987) in the
// rectangular form of Crouse (2016), "On implementing 2D rectangular assignment algorithms", IEEE
// TAES 52(4) (the algorithm SciPy's linear_sum_assignment uses). It keeps dual variables u (rows)
// and v (columns) with u_i + v_j <= C_ij, equality on assigned pairs, v_j <= 0 and v_j = 0 on
// unassigned columns; these certify optimality and let Murty's method warm-start its subproblems.
//
// Murty (1968), "An algorithm for ranking all the assignments in order of increasing cost", with
// the speed-ups of Miller, Stone & Cox (1997), "Optimizing Murty's ranked assignment method",
// IEEE TAES 33(3): each subproblem is solved by a single augmentation from its parent's solution
// and duals, subproblems enter the queue with a dual lower bound and are solved only when they
// reach its front (not at all when the bound is attained by a one- or two-edge path), and rows
// are partitioned in order of decreasing lower bound. A matrix whose finite entries split the rows
// into independent clusters (no column finite for rows of two clusters, as gating makes a GLMB
// update's matrices) is ranked per cluster and the k best sums of the clusters' rankings are
// merged lazily: the same k best, from much smaller problems.
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/random.hpp"

namespace vtrack::assign {

// An optimal assignment with its certificate. `col_of_row[i]` is row i's column; `cost` the sum
// of the assigned entries; `row_dual`, `col_dual` the duals u, v described above.
struct LinearAssignment {
  std::vector<int> col_of_row;
  double cost = 0.0;
  Eigen::VectorXd row_dual;
  Eigen::VectorXd col_dual;
};

// Optimal assignment of an n x m cost matrix (n <= m). Throws InvalidArgument naming `cost` for
// NaN or -inf entries, n > m, or a matrix with no feasible assignment (some set of rows whose
// finite entries span fewer columns than rows). n = 0 gives the empty assignment of cost 0.
LinearAssignment linear_assignment(const Eigen::Ref<const Eigen::MatrixXd>& cost);

// The k' <= k best assignments in non-decreasing cost: row r of `assignments` (k' x n) gives each
// row's column, `costs[r]` its total. k' < k exactly when fewer than k feasible assignments exist
// (k' = 0 for an infeasible matrix). Equal costs appear in unspecified order (which of them make
// the k-th place too) but every assignment is distinct; each cost is summed over the rows in
// order. Throws InvalidArgument for the bad `cost` of linear_assignment (except
// infeasibility) and for k <= 0.
struct RankedAssignments {
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> assignments;
  Eigen::VectorXd costs;
};
RankedAssignments murty(const Eigen::Ref<const Eigen::MatrixXd>& cost, std::int64_t k);

// Murty's k best for many problems whose rows come from one pool, as murty() ranks each.
//
// The GLMB update ranks one matrix per prior hypothesis, with a row per track the hypothesis holds
// and one per birth; the rows recur from hypothesis to hypothesis, and so do the independent
// clusters the gates split them into (most of one row). A pool row has finite costs at a few
// shared columns (detections: a problem gives each to one row at most) and at `private_columns`
// columns of its own (missed, absent). The problem of pool rows r_0 .. r_{n-1} is the dense matrix
//   [the shared columns some r_i can take, increasing | private column 0 of r_0 .. r_{n-1} |
//    private column 1 of r_0 .. r_{n-1} | ...]
// and rank() returns exactly murty() of it -- the same assignments with the same costs in the same
// order, equal costs included -- without forming it: each row's entries are sorted once per pool,
// each cluster of several rows is ranked once per pool (its ranking extended lazily when a later
// problem asks for more), and a problem costs a union-find over its rows' few shared entries plus
// the lazy merge of its clusters' rankings.
class PooledMurty {
 public:
  // A copy starts empty: the pool is the scratch of one batch of problems (the GLMB's scan).
  PooledMurty();
  ~PooledMurty();
  PooledMurty(const PooledMurty&);
  PooledMurty& operator=(const PooledMurty&);
  PooledMurty(PooledMurty&&) noexcept;
  PooledMurty& operator=(PooledMurty&&) noexcept;

  // Empties the pool (keeping its buffers' capacity) for rows over `shared_columns` shared
  // columns, each with `private_columns` columns of its own.
  void reset(int shared_columns, int private_columns);
  // Adds a row and returns its index: cost costs[e] at shared column cols[e] (e < count, columns
  // increasing), +inf at the other shared columns, private_costs[p] at its private column p.
  // +inf entries are forbidden pairs; NaN and -inf are InvalidArgument naming `cost`.
  int add_row(const int* cols, const double* costs, int count, const double* private_costs);
  int rows() const;
  // The k best assignments of the problem of pool rows `rows` (distinct) as murty() ranks its
  // dense matrix (above), k' <= k of them; assignments(s, i) is row i's column: a shared column
  // c >= 0, or -1 - p for its private column p. A matrix with more rows than columns gives none
  // (murty() rejects it). Valid until the next call. InvalidArgument for k <= 0 or a row index
  // outside the pool.
  const RankedAssignments& rank(const std::vector<int>& rows, std::int64_t k);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The randomised alternative to Murty's ranking of Vo, Vo & Hoang (2017), "An efficient
// implementation of the generalized labeled multi-Bernoulli filter", IEEE TSP 65(8), section
// IV-B: a Gibbs sampler whose stationary distribution over the feasible assignments g is
//   pi(g) proportional to exp(-sum_i cost(i, g_i)),
// i.e. the GLMB hypothesis weights themselves, so high-weight assignments are visited first and
// most often. One sweep resamples every row in turn from its conditional: the columns no other
// row holds, with probability proportional to exp(-cost(i, c)). Vo et al. start from the all-
// missed solution; we start from the optimal assignment (linear_assignment), so the best
// assignment is always among the results and the chain starts in its mode.
//
// Runs `sweeps` states of the chain (the start and sweeps - 1 further sweeps) and returns the
// k' <= sweeps distinct assignments visited in non-decreasing cost, with `visits[r]` the number of
// states of the chain equal to assignment r (the visit frequencies estimate pi). Not the k best:
// the cost of Murty's exactness is traded for O(sweeps n m) work. k' = 0 for an infeasible matrix.
// Throws InvalidArgument for the bad `cost` of linear_assignment (except infeasibility) and for
// sweeps <= 0.
struct SampledAssignments {
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> assignments;
  Eigen::VectorXd costs;
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, 1> visits;
};
SampledAssignments gibbs_assignments(const Eigen::Ref<const Eigen::MatrixXd>& cost,
                                     std::int64_t sweeps, core::Rng& rng);

}  // namespace vtrack::assign
