#include "vtrack/filters/assign.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <utility>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"
#include "vtrack/core/weights.hpp"

namespace vtrack::assign {
namespace {

using core::kInf;

std::string shape_string(const Eigen::Ref<const Eigen::MatrixXd>& cost) {
  return "(" + std::to_string(cost.rows()) + ", " + std::to_string(cost.cols()) + ")";
}

void check_cost(const Eigen::Ref<const Eigen::MatrixXd>& cost) {
  if (cost.rows() > cost.cols()) {
    throw InvalidArgument("cost must have at most as many rows as columns (n <= m), got shape " +
                          shape_string(cost));
  }
  for (Eigen::Index j = 0; j < cost.cols(); ++j) {
    for (Eigen::Index i = 0; i < cost.rows(); ++i) {
      const double c = cost(i, j);
      if (std::isnan(c) || c == -kInf) {
        throw InvalidArgument(std::string("cost contains ") + (std::isnan(c) ? "NaN" : "-inf") +
                              " at (" + std::to_string(i) + ", " + std::to_string(j) +
                              "); use +inf for forbidden pairs");
      }
    }
  }
}

// The state of one rectangular assignment problem -- a row-major working copy of the costs, a
// (partial) assignment and its duals -- and the shortest augmenting path step of Crouse (2016),
// extended with the "released column" step Murty's subproblems need (below).
class Solver {
 public:
  Solver() = default;
  explicit Solver(const Eigen::Ref<const Eigen::MatrixXd>& cost) {
    reset(cost, nullptr, static_cast<int>(cost.rows()), nullptr, static_cast<int>(cost.cols()));
  }

  // Loads cost(rows, cols) (all rows or columns when null) with nothing assigned and zero duals.
  // The buffers keep their capacity: the GLMB solves thousands of small problems per second.
  void reset(const Eigen::Ref<const Eigen::MatrixXd>& cost, const int* rows, int n_rows,
             const int* cols, int n_cols) {
    n = n_rows;
    m = n_cols;
    original.resize(static_cast<std::size_t>(n) * m);
    for (int i = 0; i < n; ++i) {
      const Eigen::Index r = rows ? rows[i] : i;
      double* out = &original[static_cast<std::size_t>(i) * m];
      for (int j = 0; j < m; ++j) out[j] = cost(r, cols ? cols[j] : j);
    }
    c = original;
    col4row.assign(n, -1);
    row4col.assign(m, -1);
    u.assign(n, 0.0);
    v.assign(m, 0.0);
    excluded.assign(m, 0);
    spc.resize(m);
    path.resize(m);
  }

  double& at(int i, int j) { return c[static_cast<std::size_t>(i) * m + j]; }
  double reduced(int i, int j) { return at(i, j) - u[i] - v[j]; }

  // Assigns the free row `row` along a shortest alternating path in reduced costs, over the
  // columns not `excluded` (those of rows fixed by Murty's partitioning), and updates the duals
  // so that they stay feasible and tight. Returns false, leaving assignment and duals unchanged,
  // when no augmenting path exists (the problem is infeasible).
  //
  // released < 0: the ordinary step; the path may end at any unassigned column (Crouse).
  // released >= 0: Murty's subproblem (Miller, Stone & Cox 1997): `row` has just been unassigned
  //   from column `released`, every other row keeps its parent-optimal column, and the parent's
  //   duals are still feasible. Think of the rectangular problem as the square one with m - n
  //   zero-cost dummy rows owning the unassigned columns (dummy duals 0, which is exactly why v = 0
  //   on unassigned columns). Then `released` is the only free column, and a path may pass from an
  //   unassigned column through its dummy row to any column j at reduced cost -v_j. All dummy rows
  //   are identical, so only the first one reached can shorten any path: it is scanned once and
  //   the other unassigned columns are settled at the same time. Afterwards the duals are
  //   shifted so that the dummy duals are 0 again. One such step solves the subproblem exactly.
  bool augment(int row, int released) {
    remaining.clear();
    for (int j = 0; j < m; ++j) {
      if (!excluded[j]) {
        remaining.push_back(j);
        spc[j] = kInf;
      }
    }
    scanned_rows.clear();
    scanned_cols.clear();
    double min_val = 0.0;
    int i = row;                      // the row to scan next, or kDummy
    int relay = -1;                   // the unassigned column through which the dummy was entered
    double relay_dist = 0.0;
    int sink = -1;
    while (sink < 0) {
      double lowest = kInf;
      const std::size_t best = i != kDummy ? scan_row(i, min_val, released, lowest)
                                           : scan_dummy(min_val, released, lowest);
      if (lowest == kInf) return false;  // nothing reachable: no duals or assignment were touched
      min_val = lowest;
      const int j = remaining[best];
      remaining[best] = remaining.back();
      remaining.pop_back();
      scanned_cols.push_back(j);
      if (is_sink(j, released)) {
        sink = j;
      } else if (row4col[j] >= 0) {
        i = row4col[j];
        scanned_rows.push_back(i);
      } else {  // released >= 0 and j is unassigned: enter the dummy rows
        relay = j;
        relay_dist = min_val;
        i = kDummy;
      }
    }
    update_duals(row, min_val, relay, relay_dist);
    flip_path(row, sink, relay);
    return true;
  }

  bool is_sink(int j, int released) const { return released < 0 ? row4col[j] < 0 : j == released; }

  // Relaxes the remaining columns' path lengths through row i; returns the index (into
  // `remaining`) of the closest column, ties going to a sink (the path ends sooner, Crouse), and
  // its length in `lowest` (kInf when none is reachable).
  std::size_t scan_row(int i, double min_val, int released, double& lowest) {
    // The hot loop: raw pointers, so the compiler need not reload the vectors' data pointers
    // after every store.
    const double* ci = &c[static_cast<std::size_t>(i) * m];
    const double* vv = v.data();
    const int* rem = remaining.data();
    double* sp = spc.data();
    int* pa = path.data();
    const double base = min_val - u[i];
    const std::size_t count = remaining.size();
    std::size_t best = 0;
    for (std::size_t r = 0; r < count; ++r) {
      const int j = rem[r];
      const double d = base + ci[j] - vv[j];
      if (d < sp[j]) {
        sp[j] = d;
        pa[j] = i;
      }
      if (sp[j] < lowest || (sp[j] == lowest && is_sink(j, released))) {
        lowest = sp[j];
        best = r;
      }
    }
    return best;
  }

  // The same through the (first) dummy row of Murty's subproblem; the other unassigned columns
  // are settled at once (their dummy rows add nothing).
  std::size_t scan_dummy(double min_val, int released, double& lowest) {
    std::size_t best = 0;
    for (std::size_t r = 0; r < remaining.size();) {
      const int j = remaining[r];
      const double d = min_val - v[j];
      if (d < spc[j]) {
        spc[j] = d;
        path[j] = kDummy;
      }
      if (row4col[j] < 0 && j != released) {
        scanned_cols.push_back(j);
        remaining[r] = remaining.back();
        remaining.pop_back();
        continue;
      }
      if (spc[j] < lowest || (spc[j] == lowest && is_sink(j, released))) {
        lowest = spc[j];
        best = r;
      }
      ++r;
    }
    return best;
  }

  // Dual update as in Crouse (2016): keeps u_i + v_j <= c_ij, tight on the new path.
  void update_duals(int row, double min_val, int relay, double relay_dist) {
    u[row] += min_val;
    for (int r : scanned_rows) u[r] += min_val - spc[col4row[r]];
    for (int j : scanned_cols) v[j] -= min_val - spc[j];
    if (relay >= 0) {
      // The scanned dummy rows' duals rose by `shift`; move it onto the real rows so that they
      // are 0 again (reduced costs of real pairs unchanged, v = 0 on unassigned columns).
      const double shift = min_val - relay_dist;
      for (double& x : u) x -= shift;
      for (double& x : v) x += shift;
    }
  }

  // Flips the augmenting path, walking back from the sink.
  void flip_path(int row, int sink, int relay) {
    int j = sink;
    while (true) {
      const int r = path[j];
      if (r == kDummy) {  // the dummy took j (now unassigned) and gave up the relay column
        row4col[j] = -1;
        j = relay;
        continue;
      }
      row4col[j] = r;
      std::swap(col4row[r], j);
      if (r == row) break;
    }
  }

  // Solves from scratch (all rows free, duals 0). Returns the first row that cannot be assigned,
  // or -1 on success.
  int solve() {
    for (int i = 0; i < n; ++i) {
      if (!augment(i, -1)) return i;
    }
    return -1;
  }

  // The assignment's cost, summed over the rows in order.
  double total() const {
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += original[static_cast<std::size_t>(i) * m + col4row[i]];
    return s;
  }
  double original_cost(int i, int j) const { return original[static_cast<std::size_t>(i) * m + j]; }

  static constexpr int kDummy = -2;
  int n = 0, m = 0;
  std::vector<double> original, c;  // row-major; c with Murty's forbidden pairs set to inf
  std::vector<int> col4row, row4col;
  std::vector<double> u, v;
  std::vector<char> excluded;

 private:
  std::vector<double> spc;  // shortest path cost to each column (reduced)
  std::vector<int> path;    // the row (or kDummy) the shortest path reaches each column from
  std::vector<int> remaining, scanned_rows, scanned_cols;
};

// Murty's partition tree, stored flat so that a call allocates a few growing arrays rather than
// one set of vectors per node (the GLMB calls this thousands of times on small matrices).
//
// A solved node is a subproblem of the original: rows outside its `free` list are fixed to their
// columns in its solution, and pairs in its `forbidden` list are excluded. Partitioning node P
// with solution a along its free rows in order o_0, o_1, ... gives children t = 0, 1, ...: child
// t fixes o_0..o_{t-1}, forbids (o_t, a(o_t)) and keeps P's other constraints; the children and
// the assignment a partition P's feasible set (Murty 1968). A child is queued with a lower bound
// and solved only when it reaches the front (Miller, Stone & Cox 1997).
class Murty {
 public:
  Murty() = default;
  explicit Murty(const Eigen::Ref<const Eigen::MatrixXd>& cost) {
    reset(cost, nullptr, static_cast<int>(cost.rows()), nullptr, static_cast<int>(cost.cols()));
  }
  // Starts the ranking of cost(rows, cols) (Solver::reset), keeping the buffers' capacity.
  void reset(const Eigen::Ref<const Eigen::MatrixXd>& cost, const int* rows, int n_rows,
             const int* cols, int n_cols) {
    s_.reset(cost, rows, n_rows, cols, n_cols);
    nodes_.clear();
    free_.clear();
    forbidden_.clear();
    col4row_.clear();
    u_.clear();
    v_.clear();
    queue_.clear();
    last_ = -1;
    pops_ = 0;
  }

  // The next best assignment (first call: the optimal one); false once there is none. Its
  // columns are assignment()[0..n), its cost cost(). A node is partitioned only when the next
  // one is asked for, so a caller that stops after k outputs does no work for a (k+1)-th.
  bool next() {
    const int n = s_.n;
    if (last_ < 0) {
      if (last_ == kExhausted) return false;
      last_ = kExhausted;
      if (s_.solve() >= 0) return false;
      std::vector<int> all(n);
      for (int i = 0; i < n; ++i) all[i] = i;
      const int root = store(all.data(), n, nullptr, 0);
      push({nodes_[root].cost, root, -1, true});
    } else {
      partition(last_);
    }
    last_ = kExhausted;
    while (!queue_.empty()) {
      if ((++pops_ & 63) == 0) core::poll_interrupt();  // many outputs may be asked for
      const Entry e = pop();
      int id = e.node;
      if (e.child >= 0) {
        if (!e.solved) {  // a lower bound reached the front: solve, requeue with the exact cost
          const double c = solve_child(e.node, e.child, false);
          if (c < kInf) push({c, e.node, e.child, true});
          continue;
        }
        // Its exact cost reached the front: it is next. Solving again to keep its state costs
        // one augmentation per output, far less than storing every solved child.
        const double c = solve_child(e.node, e.child, true);
        if (c == kInf) continue;  // not reachable: a solved or exact-bound child is feasible
        id = static_cast<int>(nodes_.size()) - 1;
        if (!queue_.empty() && c > queue_.front().key) {
          // An exact bound's key sits a rounding margin below the cost: requeue if that matters.
          push({c, id, -1, true});
          continue;
        }
      }
      last_ = id;
      return true;
    }
    return false;
  }
  const int* assignment() const {
    return col4row_.data() + static_cast<std::ptrdiff_t>(last_) * s_.n;
  }
  double cost() const { return nodes_[last_].cost; }

  RankedAssignments run(std::int64_t k) {
    std::vector<std::int64_t> out;
    std::vector<double> out_costs;
    while (static_cast<std::int64_t>(out_costs.size()) < k && next()) {
      out_costs.push_back(cost());
      out.insert(out.end(), assignment(), assignment() + s_.n);
    }
    RankedAssignments result;
    const auto count = static_cast<Eigen::Index>(out_costs.size());
    result.assignments.resize(count, s_.n);
    std::copy(out.begin(), out.end(), result.assignments.data());
    result.costs = Eigen::Map<const Eigen::VectorXd>(out_costs.data(), count);
    return result;
  }

 private:
  struct Node {
    double cost;
    int free_begin, n_free;      // into free_
    int forbid_begin, n_forbid;  // into forbidden_
  };
  // A queue entry: the stored node `node` (child < 0), or child number `child` of stored node
  // `node`, keyed by its cost when `solved` (computed, or a bound known to be attained) and by a
  // lower bound otherwise. Among equal keys solved entries come first.
  struct Entry {
    double key;
    int node, child;
    bool solved;
    bool operator<(const Entry& o) const {  // std::priority_queue pops the largest
      if (key != o.key) return key > o.key;
      return !solved && o.solved;
    }
  };
  void push(const Entry& e) {
    queue_.push_back(e);
    std::push_heap(queue_.begin(), queue_.end());
  }
  Entry pop() {
    std::pop_heap(queue_.begin(), queue_.end());
    const Entry e = queue_.back();
    queue_.pop_back();
    return e;
  }

  // Appends the solver's current assignment and duals as a new node.
  int store(const int* free_rows, int n_free, const std::pair<int, int>* forbid, int n_forbid) {
    Node node{s_.total(), static_cast<int>(free_.size()), n_free,
              static_cast<int>(forbidden_.size()), n_forbid};
    free_.insert(free_.end(), free_rows, free_rows + n_free);
    forbidden_.insert(forbidden_.end(), forbid, forbid + n_forbid);
    col4row_.insert(col4row_.end(), s_.col4row.begin(), s_.col4row.end());
    u_.insert(u_.end(), s_.u.begin(), s_.u.end());
    v_.insert(v_.end(), s_.v.begin(), s_.v.end());
    nodes_.push_back(node);
    return static_cast<int>(nodes_.size()) - 1;
  }

  // Loads node `id`'s solution and duals into the solver, with the rows outside
  // free_rows[0..n_free) fixed (their columns excluded).
  void load(int id, const int* free_rows, int n_free) {
    const int n = s_.n, m = s_.m;
    std::copy_n(col4row_.begin() + static_cast<std::ptrdiff_t>(id) * n, n, s_.col4row.begin());
    std::copy_n(u_.begin() + static_cast<std::ptrdiff_t>(id) * n, n, s_.u.begin());
    std::copy_n(v_.begin() + static_cast<std::ptrdiff_t>(id) * m, m, s_.v.begin());
    std::fill(s_.row4col.begin(), s_.row4col.end(), -1);
    std::fill(s_.excluded.begin(), s_.excluded.end(), 1);
    for (int i = 0; i < n; ++i) s_.row4col[s_.col4row[i]] = i;
    for (int j = 0; j < m; ++j) {
      if (s_.row4col[j] < 0) s_.excluded[j] = 0;
    }
    for (int t = 0; t < n_free; ++t) s_.excluded[s_.col4row[free_rows[t]]] = 0;
  }

  // Sets (or restores) the forbidden entries of the working matrix.
  void forbid(const std::pair<int, int>* pairs, int count, bool on) {
    for (int q = 0; q < count; ++q) {
      const auto [i, j] = pairs[q];
      s_.at(i, j) = on ? kInf : s_.original_cost(i, j);
    }
  }

  // A lower bound on (child cost - parent cost) for the child that forbids row i its column
  // a = a(i) (after Miller, Stone & Cox). With feasible duals, any assignment costs at
  // least the parent's cost plus the reduced costs of its pairs. The child must give row i another
  // available column (>= the smallest such reduced cost in row i), and column a must either go
  // to one of `rows` (the child's other free rows) or, when n < m, stay unassigned, which gives up
  // its dual v_a <= 0 (>= -v_a). These are two different pairs, so the two minima add up.
  // avail_v_[j] is v_j for an available column and -inf otherwise, so that the row minimum is one
  // branch-free (vectorisable) pass: min_j (c_ij - avail_v_j) - u_i.
  struct Bound {
    double value;
    bool exact;  // an augmenting path of exactly this length exists: it is the child's cost
  };
  Bound bound(int i, const int* rows, int count) {
    const int a = s_.col4row[i];
    const double saved = avail_v_[a];
    avail_v_[a] = -kInf;
    const double* ci = &s_.at(i, 0);
    double raw_min = kInf;
    for (int j = 0; j < s_.m; ++j) {
      const double r = ci[j] - avail_v_[j];
      raw_min = r < raw_min ? r : raw_min;
    }
    const auto row_min_at = [&](int j) { return ci[j] - avail_v_[j] == raw_min; };
    double col_min = s_.n < s_.m ? -s_.v[a] : kInf;
    for (int q = 0; q < count; ++q) {
      if (rows[q] != i) col_min = std::min(col_min, s_.reduced(rows[q], a));
    }
    // The bound is attained when the two minima chain into one augmenting path: row i moves to
    // an unassigned column and a is left unassigned (through a dummy row), or row i takes the
    // column of a row q that takes a. Common in GLMB-shaped problems; it saves a solve.
    bool exact = false;
    if (raw_min < kInf && col_min < kInf) {
      if (s_.n < s_.m && -s_.v[a] == col_min) {
        for (int j = 0; j < s_.m && !exact; ++j) exact = s_.row4col[j] < 0 && row_min_at(j);
      }
      for (int q = 0; q < count && !exact; ++q) {
        const int r = rows[q];
        exact = r != i && s_.reduced(r, a) == col_min && row_min_at(s_.col4row[r]);
      }
    }
    avail_v_[a] = saved;
    // >= 0 up to rounding; inf: infeasible child.
    return {std::max(0.0, raw_min - s_.u[i] + col_min), exact};
  }

  // Partitions node `id` and queues its children with lower bounds. The rows are taken in order
  // of decreasing bound (computed with the parent's constraints only), so the children with
  // small bounds, those likely to be expanded further, come last and carry the most fixed rows,
  // i.e. the smallest subproblems (Miller, Stone & Cox); infeasible children go
  // first. Each child's key is then its bound under its own constraints, which is tighter.
  void partition(int id) {
    const Node node = nodes_[id];
    int* rows = free_.data() + node.free_begin;
    const std::pair<int, int>* forbid_list = forbidden_.data() + node.forbid_begin;
    load(id, rows, node.n_free);
    forbid(forbid_list, node.n_forbid, true);
    avail_v_.resize(s_.m);
    for (int j = 0; j < s_.m; ++j) avail_v_[j] = s_.excluded[j] ? -kInf : s_.v[j];
    bounds_.resize(s_.n);
    for (int t = 0; t < node.n_free; ++t) {
      bounds_[rows[t]] = bound(rows[t], rows, node.n_free).value;
    }
    std::sort(rows, rows + node.n_free, [&](int a, int b) {  // ties by row: deterministic
      return bounds_[a] > bounds_[b] || (bounds_[a] == bounds_[b] && a < b);
    });
    // A margin for rounding in the duals, so that a key never exceeds the child's computed cost.
    const double margin = 1e-9 * (1.0 + std::abs(node.cost));
    for (int t = 0; t < node.n_free; ++t) {
      // Child t also fixes rows[0..t): their columns are not available to it.
      const Bound b = bound(rows[t], rows + t + 1, node.n_free - t - 1);
      if (b.value < kInf) push({node.cost + b.value - margin, id, t, b.exact});
      avail_v_[s_.col4row[rows[t]]] = -kInf;
    }
    forbid(forbid_list, node.n_forbid, false);
  }

  // Solves child t of node `parent` by one augmentation from the parent's solution and duals.
  // Returns its cost (inf if infeasible) and, with `keep`, appends it as a node.
  double solve_child(int parent, int t, bool keep) {
    const Node p = nodes_[parent];
    const int* child_rows = free_.data() + p.free_begin + t;
    const int n_free = p.n_free - t;
    const int row = child_rows[0];
    load(parent, child_rows, n_free);
    const int a = s_.col4row[row];
    // The child's forbidden pairs: the parent's that are on its free rows, and (row, a).
    in_free_.assign(s_.n, 0);
    for (int q = 0; q < n_free; ++q) in_free_[child_rows[q]] = 1;
    child_forbid_.clear();
    for (int q = 0; q < p.n_forbid; ++q) {
      const auto f = forbidden_[p.forbid_begin + q];
      if (in_free_[f.first]) child_forbid_.push_back(f);
    }
    child_forbid_.emplace_back(row, a);
    const int nf = static_cast<int>(child_forbid_.size());
    forbid(child_forbid_.data(), nf, true);
    s_.col4row[row] = -1;
    s_.row4col[a] = -1;
    const bool ok = s_.augment(row, a);
    forbid(child_forbid_.data(), nf, false);
    if (!ok) return kInf;
    if (!keep) return s_.total();
    // Copy the rows out first: `store` may reallocate free_.
    child_rows_.assign(child_rows, child_rows + n_free);
    return nodes_[store(child_rows_.data(), n_free, child_forbid_.data(), nf)].cost;
  }

  static constexpr int kExhausted = -2;  // last_ before the first next() is -1
  Solver s_;
  int last_ = -1;            // the node output last, partitioned by the next call
  std::int64_t pops_ = 0;
  std::vector<Node> nodes_;
  std::vector<int> free_;
  std::vector<std::pair<int, int>> forbidden_;
  std::vector<int> col4row_;
  std::vector<double> u_, v_;
  std::vector<Entry> queue_;  // a heap: push() / pop() below, as std::priority_queue
  std::vector<double> bounds_, avail_v_;
  std::vector<char> in_free_;
  std::vector<std::pair<int, int>> child_forbid_;
  std::vector<int> child_rows_;
};

// ---- Independent clusters -----------------------------------------------------------------------
//
// Two rows interact only through a column where both have a finite cost. The connected components
// of that relation ("clusters") are independent assignment problems: an assignment of the whole
// matrix is one assignment per cluster, its cost the sum of theirs. So the k best assignments of
// the whole are the k best sums of the clusters' own rankings -- Murty's k best (equal costs
// apart), found from small problems. In a GLMB update the gates make this the common case: a
// prior hypothesis's matrix has a row per track and per birth with its own missed and absent
// columns, and most rows can take one detection or none (measured on the hard level of
// benchmarks/detections_sim.py: 16 rows in 12 clusters, the largest of 3 rows, on average). The
// GLMB solves about a hundred such matrices per scan, most for k = 1 to 3, so the buffers below
// live in a per-thread Workspace and keep their capacity from call to call.

// The clusters of a matrix, numbered in order of their first rows, with their rows and their
// columns (those where one of their rows is finite), each in increasing order.
struct Clusters {
  int count = 0;
  bool feasible = true;              // false when some row has no finite entry
  std::vector<int> rows, row_begin;  // cluster c's rows: rows[row_begin[c] .. row_begin[c + 1])
  std::vector<int> cols, col_begin;  // and its columns, likewise
};

// A ranked list of a cluster of several rows: Murty's method on its rows and columns, generated
// on demand.
struct MurtyList {
  Murty murty;
  bool feasible = false;
  std::size_t n = 0;
  // Each column's label: its column in the whole matrix (murty), or a choice code (PooledMurty).
  std::vector<int> cols;
  std::vector<double> costs;
  std::vector<int> choices;  // per ranked assignment, each row's index into cols

  // Ranks cost(rows, cluster_cols) (all rows or columns when null), the columns labelled
  // `labels` (cluster_cols when null).
  void reset(const Eigen::Ref<const Eigen::MatrixXd>& cost, const int* rows, int n_rows,
             const int* cluster_cols, int n_cols, const int* labels = nullptr) {
    n = static_cast<std::size_t>(n_rows);
    labels = labels ? labels : cluster_cols;
    cols.assign(labels, labels + n_cols);
    costs.clear();
    choices.clear();
    feasible = n_rows <= n_cols;  // fewer columns than rows: infeasible
    if (feasible) murty.reset(cost, rows, n_rows, cluster_cols, n_cols);
  }
  // Whether there is an r-th best assignment (from 0), generating it if needed.
  bool has(std::size_t r) {
    while (costs.size() <= r) {
      if (!feasible || !murty.next()) return false;
      costs.push_back(murty.cost());
      choices.insert(choices.end(), murty.assignment(), murty.assignment() + n);
    }
    return true;
  }
};

// One level of SumRanking: the ranked sums over clusters 0..level.
struct SumLevel {
  struct Pair {
    double key;             // the sum over clusters 0..level, added in that order
    std::size_t prev, own;  // the entry of level - 1 and of the level's own cluster
    bool operator>(const Pair& o) const {  // ties by indices: deterministic
      if (key != o.key) return key > o.key;
      return prev != o.prev ? prev > o.prev : own > o.own;
    }
  };
  std::vector<Pair> out, queue;  // taken in order; a heap of candidates
  bool started = false, expanded = false;
};

// Buffers reused from call to call (one per thread: calls may run in parallel without the GIL).
struct Workspace {
  Clusters clusters;
  std::vector<int> parent, row_of, col_of, number, next;
  std::vector<std::unique_ptr<MurtyList>> lists;  // the first list_count in use
  std::size_t list_count = 0;
  std::vector<int> list_of;  // per cluster: index into lists, -1 for a single row
  std::vector<SumLevel> levels;
  std::vector<std::pair<double, std::size_t>> totals;
  std::vector<int> col_of_row, out;
  Murty whole;  // a matrix of one cluster
};

// Groups the indices 0..n-1 by their cluster (-1: left out) into `items` / `begin`.
void group(const std::vector<int>& cluster_of, int count, std::vector<int>& items,
           std::vector<int>& begin, std::vector<int>& next) {
  begin.assign(static_cast<std::size_t>(count) + 1, 0);
  for (int c : cluster_of) {
    if (c >= 0) ++begin[static_cast<std::size_t>(c) + 1];
  }
  std::partial_sum(begin.begin(), begin.end(), begin.begin());
  items.resize(static_cast<std::size_t>(begin.back()));
  next.assign(begin.begin(), begin.end() - 1);
  for (std::size_t x = 0; x < cluster_of.size(); ++x) {
    if (cluster_of[x] >= 0) items[static_cast<std::size_t>(next[cluster_of[x]]++)] = static_cast<int>(x);
  }
}

void find_clusters(const Eigen::Ref<const Eigen::MatrixXd>& cost, Workspace& w) {
  const int n = static_cast<int>(cost.rows()), m = static_cast<int>(cost.cols());
  std::vector<int>& parent = w.parent;
  std::vector<int>& row_of = w.row_of;
  std::vector<int>& col_of = w.col_of;
  parent.resize(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  row_of.assign(static_cast<std::size_t>(n), -1);
  col_of.assign(static_cast<std::size_t>(m), -1);
  const auto root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  bool valid = true;  // no NaN or -inf (check_cost's condition, tested in the same pass)
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = cost(i, j);
      valid &= x > -kInf;
      if (x == kInf) continue;
      row_of[i] = 0;  // has a finite entry
      if (col_of[j] < 0) {
        col_of[j] = i;  // the column's first row, for now
        continue;
      }
      const int a = root(col_of[j]), b = root(i);  // the smaller row stays the root
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  if (!valid) check_cost(cost);  // throws, naming the entry
  Clusters& c = w.clusters;
  c.count = 0;
  c.feasible = true;
  w.number.assign(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    if (row_of[i] < 0) {
      c.feasible = false;
      continue;
    }
    const int r = root(i);
    if (w.number[r] < 0) w.number[r] = c.count++;
    row_of[i] = w.number[r];
  }
  for (int j = 0; j < m; ++j) {
    if (col_of[j] >= 0) col_of[j] = row_of[col_of[j]];
  }
  group(row_of, c.count, c.rows, c.row_begin, w.next);
  group(col_of, c.count, c.cols, c.col_begin, w.next);
}

// Every cluster's ranking: a single row's finite entries in increasing cost (its columns sorted
// in place), or a MurtyList.
class ClusterRankings {
 public:
  ClusterRankings(const Eigen::Ref<const Eigen::MatrixXd>& cost, Workspace& w)
      : cost_(cost), w_(w), c_(w.clusters) {
    Clusters& c = w.clusters;
    w.list_of.assign(static_cast<std::size_t>(c.count), -1);
    w.list_count = 0;
    for (int k = 0; k < c.count; ++k) {
      int* cols = c.cols.data() + c.col_begin[k];
      const int m = c.col_begin[k + 1] - c.col_begin[k];
      const int n = c.row_begin[k + 1] - c.row_begin[k];
      if (n == 1) {  // ties by column: deterministic
        const auto row = cost.row(c.rows[c.row_begin[k]]);
        for (int a = 1; a < m; ++a) {  // insertion sort: a row has a few finite entries
          const int col = cols[a];
          int b = a;
          for (; b > 0 && row(col) < row(cols[b - 1]); --b) cols[b] = cols[b - 1];
          cols[b] = col;
        }
        continue;
      }
      if (w.list_count == w.lists.size()) w.lists.push_back(std::make_unique<MurtyList>());
      w.list_of[k] = static_cast<int>(w.list_count);
      w.lists[w.list_count++]->reset(cost, c.rows.data() + c.row_begin[k], n, cols, m);
    }
  }
  int count() const { return c_.count; }
  bool has(int k, std::size_t r) {
    if (w_.list_of[k] >= 0) return w_.lists[w_.list_of[k]]->has(r);
    return r < static_cast<std::size_t>(c_.col_begin[k + 1] - c_.col_begin[k]);
  }
  double cost(int k, std::size_t r) const {
    if (w_.list_of[k] >= 0) return w_.lists[w_.list_of[k]]->costs[r];
    return cost_(c_.rows[c_.row_begin[k]], c_.cols[c_.col_begin[k] + r]);
  }
  // Writes cluster k's r-th assignment into col_of_row.
  void write(int k, std::size_t r, std::vector<int>& col_of_row) const {
    const int first = c_.row_begin[k];
    if (w_.list_of[k] < 0) {
      col_of_row[c_.rows[first]] = c_.cols[c_.col_begin[k] + r];
      return;
    }
    const MurtyList& list = *w_.lists[w_.list_of[k]];
    for (std::size_t q = 0; q < list.n; ++q) {
      col_of_row[c_.rows[first + q]] = list.cols[list.choices[r * list.n + q]];
    }
  }

 private:
  const Eigen::Ref<const Eigen::MatrixXd>& cost_;
  Workspace& w_;
  const Clusters& c_;
};

// The ranked sums of the clusters' rankings, generated lazily level by level: level k ranks the
// assignments of clusters 0..k, as the sums of two ranked lists, level k-1 and cluster k (the pair
// (i, j) is queued when (i, j-1) is taken, and (i, 0) when (i-1, 0) is: each pair once, never
// before one that costs no more). A successor is queued only when the next entry is asked for, so
// an entry of a level or a cluster is computed only when some sum that needs it may be next.
// Rankings: has(k, r), cost(k, r), write(k, r, col_of_row) and count() of the clusters' own
// rankings (ClusterRankings, PoolRankings).
template <class Rankings>
class SumRanking {
 public:
  using Pair = SumLevel::Pair;
  SumRanking(Rankings& clusters, std::vector<SumLevel>& levels)
      : clusters_(clusters), levels_(levels) {
    if (levels_.size() < static_cast<std::size_t>(clusters.count())) levels_.resize(clusters.count());
    for (int k = 0; k < clusters.count(); ++k) {
      SumLevel& l = levels_[static_cast<std::size_t>(k)];
      l.out.clear();
      l.queue.clear();
      l.started = l.expanded = false;
    }
  }

  // Whether level `level` has an r-th best sum (from 0), generating it if needed.
  bool has(int level, std::size_t r) {
    if (level == 0) return clusters_.has(0, r);
    SumLevel& l = levels_[static_cast<std::size_t>(level)];
    if (!l.started) {
      l.started = true;
      if (has(level - 1, 0) && clusters_.has(level, 0)) push(l, level, 0, 0);
    }
    while (l.out.size() <= r) {
      if (!l.out.empty() && !l.expanded) {  // the successors of the entry taken last
        l.expanded = true;
        const Pair p = l.out.back();
        if (clusters_.has(level, p.own + 1)) push(l, level, p.prev, p.own + 1);
        if (p.own == 0 && has(level - 1, p.prev + 1)) push(l, level, p.prev + 1, 0);
      }
      if (l.queue.empty()) return false;
      std::pop_heap(l.queue.begin(), l.queue.end(), std::greater<>());
      l.out.push_back(l.queue.back());
      l.queue.pop_back();
      l.expanded = false;
    }
    return true;
  }

  // The r-th best assignment of the whole matrix (all levels): each row's column.
  void assignment(std::size_t r, std::vector<int>& col_of_row) const {
    for (int level = clusters_.count() - 1; level >= 0; --level) {
      std::size_t own = r;
      if (level > 0) {
        const Pair& p = levels_[static_cast<std::size_t>(level)].out[r];
        own = p.own;
        r = p.prev;
      }
      clusters_.write(level, own, col_of_row);
    }
  }

 private:
  double key(int level, std::size_t r) const {
    return level == 0 ? clusters_.cost(0, r) : levels_[static_cast<std::size_t>(level)].out[r].key;
  }
  void push(SumLevel& l, int level, std::size_t prev, std::size_t own) {
    l.queue.push_back({key(level - 1, prev) + clusters_.cost(level, own), prev, own});
    std::push_heap(l.queue.begin(), l.queue.end(), std::greater<>());
  }

  Rankings& clusters_;
  std::vector<SumLevel>& levels_;
};

// The k best of the clusters' sums (see above) of an n-row matrix, with their costs summed over
// the rows in order (row_cost(i, column of row i)), as Murty's method on the whole matrix sums
// them, ordered by that cost; into `result`.
template <class Rankings, class RowCost>
void ranked_sums(Rankings& clusters, int n, std::int64_t k, Workspace& w, RowCost row_cost,
                 RankedAssignments& result) {
  SumRanking<Rankings> sums(clusters, w.levels);
  w.totals.clear();
  w.out.clear();
  w.col_of_row.resize(static_cast<std::size_t>(n));
  const int top = clusters.count() - 1;
  for (std::size_t r = 0; static_cast<std::int64_t>(r) < k; ++r) {
    if ((r & 63) == 63) core::poll_interrupt();  // k may be large
    bool found = true;
    if (r == 0) {  // the best assignment is each cluster's best: no ranking of sums needed
      for (int q = 0; q <= top && found; ++q) found = clusters.has(q, 0);
      for (int q = 0; q <= top && found; ++q) clusters.write(q, 0, w.col_of_row);
    } else {
      found = sums.has(top, r);
      if (found) sums.assignment(r, w.col_of_row);
    }
    if (!found) break;
    double total = 0.0;
    for (int i = 0; i < n; ++i) total += row_cost(i, w.col_of_row[i]);
    w.totals.emplace_back(total, r);
    w.out.insert(w.out.end(), w.col_of_row.begin(), w.col_of_row.end());
  }
  std::stable_sort(w.totals.begin(), w.totals.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto kept = static_cast<Eigen::Index>(w.totals.size());
  result.assignments.resize(kept, n);
  result.costs.resize(kept);
  for (Eigen::Index s = 0; s < kept; ++s) {
    const auto& [total, r] = w.totals[static_cast<std::size_t>(s)];
    result.costs[s] = total;
    for (int i = 0; i < n; ++i) result.assignments(s, i) = w.out[r * static_cast<std::size_t>(n) + i];
  }
}

// Murty's k best through the clusters, or on the whole matrix when it is one cluster: the same
// list as Murty's on the whole matrix, bit for bit, except for the order of equal costs and which
// of them make the k-th place.
RankedAssignments ranked_by_clusters(const Eigen::Ref<const Eigen::MatrixXd>& cost,
                                     std::int64_t k) {
  thread_local Workspace w;
  find_clusters(cost, w);
  if (!w.clusters.feasible) {  // a row without a finite entry: no feasible assignment
    RankedAssignments result;
    result.assignments.resize(0, cost.rows());
    result.costs.resize(0);
    return result;
  }
  if (w.clusters.count > 1) {
    ClusterRankings clusters(cost, w);
    RankedAssignments result;
    ranked_sums(clusters, static_cast<int>(cost.rows()), k, w,
                [&](int i, int col) { return cost(i, col); }, result);
    return result;
  }
  w.whole.reset(cost, nullptr, static_cast<int>(cost.rows()), nullptr,
                static_cast<int>(cost.cols()));
  return w.whole.run(k);
}


// ---- Pooled rows (PooledMurty) ----------------------------------------------------------------
//
// The pool's rows, each with its entries and its ranking as a cluster of its own.
struct PoolRows {
  int shared = 0, n_private = 0;
  // Row q's shared entries: columns entry_col[entry_begin[q] ..) (increasing) and their costs;
  // its private costs private_cost[q * n_private ..).
  std::vector<int> entry_begin{0}, entry_col;
  std::vector<double> entry_cost, private_cost;
  // Row q's finite entries as choice codes (shared column c >= 0, private p as -1 - p) sorted by
  // cost, ties in the dense matrix's column order (shared increasing, then private 0, 1, ...):
  // the ranking of a cluster of that row alone, as ClusterRankings sorts it.
  std::vector<int> sorted_begin{0}, sorted_code;
  std::vector<double> sorted_cost;

  int size() const { return static_cast<int>(entry_begin.size()) - 1; }
  // The cost of row q at a choice code (a finite entry of it).
  double cost(int q, int code) const {
    if (code < 0) return private_cost[static_cast<std::size_t>(q) * n_private - 1 - code];
    const auto begin = entry_col.begin() + entry_begin[q];
    const auto end = entry_col.begin() + entry_begin[q + 1];
    return entry_cost[static_cast<std::size_t>(std::lower_bound(begin, end, code) -
                                               entry_col.begin())];
  }
};

// The clusters of the problem of pool rows `rows` (positions 0..n-1), as find_clusters finds them
// in its dense matrix; the columns of cluster k are its shared columns (increasing). `taken`
// receives the shared columns some row can take, increasing. first_row_of_col: -1 per shared
// column on entry and on return.
void find_pool_clusters(const PoolRows& pool, const std::vector<int>& rows, Workspace& w,
                        std::vector<int>& first_row_of_col, std::vector<int>& taken) {
  const int n = static_cast<int>(rows.size());
  std::vector<int>& parent = w.parent;
  parent.resize(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  Clusters& c = w.clusters;
  c.feasible = true;
  taken.clear();
  for (int i = 0; i < n; ++i) {
    const int q = rows[static_cast<std::size_t>(i)];
    c.feasible &= pool.sorted_begin[q + 1] > pool.sorted_begin[q];  // some finite entry
    for (int e = pool.entry_begin[q]; e < pool.entry_begin[q + 1]; ++e) {
      int& first = first_row_of_col[static_cast<std::size_t>(pool.entry_col[e])];
      if (first < 0) {
        first = i;
        taken.push_back(pool.entry_col[e]);
        continue;
      }
      const int a = root(first), b = root(i);  // the smaller row stays the root
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::sort(taken.begin(), taken.end());
  c.count = 0;
  w.number.assign(static_cast<std::size_t>(n), -1);
  w.row_of.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {  // numbered by their first rows
    const int r = root(i);
    if (w.number[r] < 0) w.number[r] = c.count++;
    w.row_of[i] = w.number[r];
  }
  w.col_of.resize(taken.size());
  for (std::size_t t = 0; t < taken.size(); ++t) {
    int& first = first_row_of_col[static_cast<std::size_t>(taken[t])];
    w.col_of[t] = w.row_of[first];
    first = -1;
  }
  group(w.row_of, c.count, c.rows, c.row_begin, w.next);
  group(w.col_of, c.count, c.cols, c.col_begin, w.next);  // indices into taken
  for (int& t : c.cols) t = taken[static_cast<std::size_t>(t)];
}

// The pool's clusters' rankings for SumRanking: a single row's sorted entries, or a MurtyList
// (one per cluster of several rows, shared by every problem that has that cluster).
class PoolRankings {
 public:
  PoolRankings(const PoolRows& pool, const std::vector<int>& rows, const Workspace& w,
               const std::vector<MurtyList*>& lists)
      : pool_(pool), rows_(rows), c_(w.clusters), lists_(lists) {}
  int count() const { return c_.count; }
  bool has(int k, std::size_t r) {
    if (lists_[k]) return lists_[k]->has(r);
    const int q = first_row(k);
    return r < static_cast<std::size_t>(pool_.sorted_begin[q + 1] - pool_.sorted_begin[q]);
  }
  double cost(int k, std::size_t r) const {
    if (lists_[k]) return lists_[k]->costs[r];
    return pool_.sorted_cost[static_cast<std::size_t>(pool_.sorted_begin[first_row(k)]) + r];
  }
  // Writes cluster k's r-th assignment (choice codes) into code_of_row.
  void write(int k, std::size_t r, std::vector<int>& code_of_row) const {
    const int first = c_.row_begin[k];
    if (!lists_[k]) {
      code_of_row[c_.rows[first]] =
          pool_.sorted_code[static_cast<std::size_t>(pool_.sorted_begin[first_row(k)]) + r];
      return;
    }
    const MurtyList& list = *lists_[k];
    for (std::size_t q = 0; q < list.n; ++q) {
      code_of_row[c_.rows[first + q]] = list.cols[list.choices[r * list.n + q]];
    }
  }

 private:
  int first_row(int k) const { return rows_[static_cast<std::size_t>(c_.rows[c_.row_begin[k]])]; }

  const PoolRows& pool_;
  const std::vector<int>& rows_;
  const Clusters& c_;
  const std::vector<MurtyList*>& lists_;
};

}  // namespace

// ---- PooledMurty --------------------------------------------------------------------------------

struct PooledMurty::Impl {
  PoolRows pool;
  // Rankings of clusters of several rows, and of whole problems of one cluster (their keys end
  // with kWhole), by their pool rows; lists[0 .. list_count) are in use.
  static constexpr int kWhole = -1;
  std::map<std::vector<int>, MurtyList*> memo;
  std::vector<std::unique_ptr<MurtyList>> lists;
  std::size_t list_count = 0;
  // Scratch of one rank() call.
  Workspace w;
  std::vector<int> first_row_of_col, taken, key, codes;
  std::vector<MurtyList*> cluster_lists;
  Eigen::MatrixXd block;
  RankedAssignments result;

  std::vector<char> in_problem;  // per pool row, during a call's argument check

  MurtyList* list(const std::vector<int>& rows, int k);
  void rank_whole(const std::vector<int>& rows, std::int64_t k);
};

// Murty's ranking of cluster k of the current problem (k < 0: of the whole problem, over the
// taken shared columns and every private column, +inf ones included, as murty() ranks a matrix of
// one cluster; a cluster's matrix has the columns where one of its rows is finite): made at its
// first request in this pool and extended by later problems with the same rows.
MurtyList* PooledMurty::Impl::list(const std::vector<int>& rows, int k) {
  const Clusters& c = w.clusters;
  const bool whole = k < 0;
  const int n = whole ? static_cast<int>(rows.size()) : c.row_begin[k + 1] - c.row_begin[k];
  key.clear();
  for (int i = 0; i < n; ++i) key.push_back(rows[whole ? i : c.rows[c.row_begin[k] + i]]);
  if (whole) key.push_back(kWhole);
  const auto found = memo.find(key);
  if (found != memo.end()) return found->second;
  if (whole) key.pop_back();
  const int* shared = whole ? taken.data() : c.cols.data() + c.col_begin[k];
  const int n_shared = whole ? static_cast<int>(taken.size()) : c.col_begin[k + 1] - c.col_begin[k];
  codes.assign(shared, shared + n_shared);
  const int n_private = pool.n_private;
  for (int p = 0; p < n_private; ++p) {
    for (int q : key) {
      if (whole || pool.private_cost[static_cast<std::size_t>(q) * n_private + p] < kInf) {
        codes.push_back(-1 - p);
      }
    }
  }
  block.setConstant(n, static_cast<Eigen::Index>(codes.size()), kInf);
  for (int i = 0; i < n; ++i) {
    const int q = key[static_cast<std::size_t>(i)];
    for (int e = pool.entry_begin[q]; e < pool.entry_begin[q + 1]; ++e) {
      const auto local = std::lower_bound(shared, shared + n_shared, pool.entry_col[e]) - shared;
      block(i, local) = pool.entry_cost[static_cast<std::size_t>(e)];
    }
  }
  int col = n_shared;
  for (int p = 0; p < n_private; ++p) {
    for (int i = 0; i < n; ++i) {
      const double x =
          pool.private_cost[static_cast<std::size_t>(key[static_cast<std::size_t>(i)]) * n_private + p];
      if (whole || x < kInf) block(i, col++) = x;
    }
  }
  if (list_count == lists.size()) lists.push_back(std::make_unique<MurtyList>());
  MurtyList* l = lists[list_count++].get();
  l->reset(block, nullptr, n, nullptr, static_cast<int>(codes.size()), codes.data());
  if (whole) key.push_back(kWhole);
  memo.emplace(key, l);
  return l;
}

// A problem of one cluster (or none): murty() ranks its dense matrix whole, in Murty's order.
void PooledMurty::Impl::rank_whole(const std::vector<int>& rows, std::int64_t k) {
  MurtyList& l = *list(rows, -1);
  std::size_t count = 0;
  while (static_cast<std::int64_t>(count) < k && l.has(count)) ++count;
  const auto n = static_cast<Eigen::Index>(rows.size());
  result.assignments.resize(static_cast<Eigen::Index>(count), n);
  result.costs.resize(static_cast<Eigen::Index>(count));
  for (std::size_t s = 0; s < count; ++s) {
    result.costs[static_cast<Eigen::Index>(s)] = l.costs[s];
    for (Eigen::Index i = 0; i < n; ++i) {
      result.assignments(static_cast<Eigen::Index>(s), i) =
          l.cols[static_cast<std::size_t>(l.choices[s * l.n + static_cast<std::size_t>(i)])];
    }
  }
}

PooledMurty::PooledMurty() : impl_(std::make_unique<Impl>()) {}
PooledMurty::~PooledMurty() = default;
PooledMurty::PooledMurty(const PooledMurty&) : PooledMurty() {}
PooledMurty& PooledMurty::operator=(const PooledMurty& other) {
  if (this != &other) impl_ = std::make_unique<Impl>();
  return *this;
}
PooledMurty::PooledMurty(PooledMurty&&) noexcept = default;
PooledMurty& PooledMurty::operator=(PooledMurty&&) noexcept = default;

void PooledMurty::reset(int shared_columns, int private_columns) {
  require(shared_columns >= 0, "shared_columns", shared_columns, ">= 0");
  require(private_columns >= 0, "private_columns", private_columns, ">= 0");
  Impl& p = *impl_;
  PoolRows& pool = p.pool;
  pool.shared = shared_columns;
  pool.n_private = private_columns;
  pool.entry_begin.assign(1, 0);
  pool.sorted_begin.assign(1, 0);
  pool.entry_col.clear();
  pool.entry_cost.clear();
  pool.private_cost.clear();
  pool.sorted_code.clear();
  pool.sorted_cost.clear();
  p.memo.clear();
  p.list_count = 0;
  p.first_row_of_col.assign(static_cast<std::size_t>(shared_columns), -1);
}

int PooledMurty::add_row(const int* cols, const double* costs, int count,
                         const double* private_costs) {
  PoolRows& pool = impl_->pool;
  const auto check = [](double x) {
    if (std::isnan(x) || x == -kInf) {
      throw InvalidArgument(std::string("cost contains ") + (std::isnan(x) ? "NaN" : "-inf") +
                            "; use +inf for forbidden pairs");
    }
  };
  for (int e = 0; e < count; ++e) {
    require(cols[e] >= 0 && cols[e] < pool.shared && (e == 0 || cols[e] > cols[e - 1]),
            "cols", cols[e], "increasing shared columns");
    check(costs[e]);
  }
  for (int p = 0; p < pool.n_private; ++p) check(private_costs[p]);
  const auto sorted_start = pool.sorted_code.size();
  const auto insert = [&](int code, double x) {  // insertion sort, ties in column order
    if (x == kInf) return;
    std::size_t b = pool.sorted_code.size();
    pool.sorted_code.push_back(code);
    pool.sorted_cost.push_back(x);
    for (; b > sorted_start && x < pool.sorted_cost[b - 1]; --b) {
      pool.sorted_code[b] = pool.sorted_code[b - 1];
      pool.sorted_cost[b] = pool.sorted_cost[b - 1];
    }
    pool.sorted_code[b] = code;
    pool.sorted_cost[b] = x;
  };
  for (int e = 0; e < count; ++e) {
    if (costs[e] == kInf) continue;
    pool.entry_col.push_back(cols[e]);
    pool.entry_cost.push_back(costs[e]);
    insert(cols[e], costs[e]);
  }
  for (int p = 0; p < pool.n_private; ++p) {
    pool.private_cost.push_back(private_costs[p]);
    insert(-1 - p, private_costs[p]);
  }
  pool.entry_begin.push_back(static_cast<int>(pool.entry_col.size()));
  pool.sorted_begin.push_back(static_cast<int>(pool.sorted_code.size()));
  return pool.size() - 1;
}

int PooledMurty::rows() const { return impl_->pool.size(); }

const RankedAssignments& PooledMurty::rank(const std::vector<int>& rows, std::int64_t k) {
  Impl& p = *impl_;
  if (k <= 0) throw InvalidArgument("k must be >= 1, got " + std::to_string(k));
  p.in_problem.assign(static_cast<std::size_t>(p.pool.size()), 0);
  for (int q : rows) {
    require(q >= 0 && q < p.pool.size() && !p.in_problem[static_cast<std::size_t>(q)], "rows", q,
            "distinct rows of the pool");
    p.in_problem[static_cast<std::size_t>(q)] = 1;
  }
  find_pool_clusters(p.pool, rows, p.w, p.first_row_of_col, p.taken);
  const int n = static_cast<int>(rows.size());
  const Clusters& c = p.w.clusters;
  if (!c.feasible || n > static_cast<int>(p.taken.size()) + p.pool.n_private * n) {
    p.result.assignments.resize(0, n);
    p.result.costs.resize(0);
    return p.result;
  }
  if (c.count <= 1) {
    p.rank_whole(rows, k);
    return p.result;
  }
  p.cluster_lists.assign(static_cast<std::size_t>(c.count), nullptr);
  for (int q = 0; q < c.count; ++q) {
    if (c.row_begin[q + 1] - c.row_begin[q] > 1) p.cluster_lists[q] = p.list(rows, q);
  }
  PoolRankings rankings(p.pool, rows, p.w, p.cluster_lists);
  ranked_sums(rankings, n, k, p.w,
              [&](int i, int code) { return p.pool.cost(rows[static_cast<std::size_t>(i)], code); },
              p.result);
  return p.result;
}

LinearAssignment linear_assignment(const Eigen::Ref<const Eigen::MatrixXd>& cost) {
  check_cost(cost);
  Solver s(cost);
  const int failed = s.solve();
  if (failed >= 0) {
    throw InvalidArgument("cost " + shape_string(cost) +
                          " has no feasible assignment: rows 0.." + std::to_string(failed) +
                          " cannot all get distinct columns with finite cost");
  }
  LinearAssignment result;
  result.col_of_row = s.col4row;
  result.cost = s.total();
  result.row_dual = Eigen::Map<const Eigen::VectorXd>(s.u.data(), s.n);
  result.col_dual = Eigen::Map<const Eigen::VectorXd>(s.v.data(), s.m);
  return result;
}

RankedAssignments murty(const Eigen::Ref<const Eigen::MatrixXd>& cost, std::int64_t k) {
  if (cost.rows() > cost.cols()) check_cost(cost);  // throws; NaN and -inf: find_clusters
  if (k <= 0) {
    check_cost(cost);  // a bad matrix is named first
    throw InvalidArgument("k must be >= 1, got " + std::to_string(k));
  }
  return ranked_by_clusters(cost, k);
}

SampledAssignments gibbs_assignments(const Eigen::Ref<const Eigen::MatrixXd>& cost,
                                     std::int64_t sweeps, core::Rng& rng) {
  check_cost(cost);
  if (sweeps <= 0) throw InvalidArgument("sweeps must be >= 1, got " + std::to_string(sweeps));
  const auto n = static_cast<int>(cost.rows());
  const auto m = static_cast<int>(cost.cols());
  SampledAssignments result;
  Solver start(cost);
  if (start.solve() >= 0) {  // infeasible: nothing to sample
    result.assignments.resize(0, n);
    result.costs.resize(0);
    result.visits.resize(0);
    return result;
  }
  // Row-major copy: each conditional reads one row.
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c = cost;
  std::vector<int> state = start.col4row;
  std::vector<int> row_of_col(static_cast<std::size_t>(m), -1);
  for (int i = 0; i < n; ++i) row_of_col[static_cast<std::size_t>(state[i])] = i;

  std::map<std::vector<int>, std::int64_t> visits;
  std::vector<double> weight(static_cast<std::size_t>(m));
  for (std::int64_t sweep = 0; sweep < sweeps; ++sweep) {
    if ((sweep & 63) == 0) core::poll_interrupt();  // sweeps may be large
    if (sweep > 0) {
      for (int i = 0; i < n; ++i) {
        // Conditional of row i given the others: its own column or any free one. The current
        // column is always allowed and finite, so the conditional is never empty.
        double lowest = kInf;
        for (int j = 0; j < m; ++j) {
          const int holder = row_of_col[static_cast<std::size_t>(j)];
          if (holder < 0 || holder == i) lowest = std::min(lowest, c(i, j));
        }
        double total = 0.0;
        for (int j = 0; j < m; ++j) {
          const int holder = row_of_col[static_cast<std::size_t>(j)];
          const double w = (holder < 0 || holder == i) ? std::exp(lowest - c(i, j)) : 0.0;
          weight[static_cast<std::size_t>(j)] = w;
          total += w;
        }
        const double target = rng.uniform() * total;
        int chosen = state[i];
        double running = 0.0;
        for (int j = 0; j < m; ++j) {
          const double w = weight[static_cast<std::size_t>(j)];
          running += w;
          if (w > 0.0 && target < running) {
            chosen = j;
            break;
          }
        }
        row_of_col[static_cast<std::size_t>(state[i])] = -1;
        row_of_col[static_cast<std::size_t>(chosen)] = i;
        state[i] = chosen;
      }
    }
    ++visits[state];
  }

  std::vector<std::pair<double, const std::pair<const std::vector<int>, std::int64_t>*>> order;
  order.reserve(visits.size());
  for (const auto& entry : visits) {
    double total = 0.0;
    for (int i = 0; i < n; ++i) total += c(i, entry.first[static_cast<std::size_t>(i)]);
    order.emplace_back(total, &entry);
  }
  // Ties keep the map's (lexicographic) order, so the result does not depend on the sort's
  // implementation.
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto k = static_cast<Eigen::Index>(order.size());
  result.assignments.resize(k, n);
  result.costs.resize(k);
  result.visits.resize(k);
  for (Eigen::Index r = 0; r < k; ++r) {
    result.costs[r] = order[static_cast<std::size_t>(r)].first;
    result.visits[r] = order[static_cast<std::size_t>(r)].second->second;
    const auto& a = order[static_cast<std::size_t>(r)].second->first;
    for (int i = 0; i < n; ++i) result.assignments(r, i) = a[static_cast<std::size_t>(i)];
  }
  return result;
}

}  // namespace vtrack::assign
