#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/filters/assign.hpp"

using namespace vtrack;
using namespace vtrack::assign;

namespace {

using vtrack::core::kInf;

// Costs of every feasible assignment (each row a distinct column, no +inf), sorted: the
// independent reference Murty must reproduce.
std::vector<double> brute_force_costs(const Eigen::MatrixXd& c) {
  const int n = static_cast<int>(c.rows()), m = static_cast<int>(c.cols());
  std::vector<double> costs;
  std::vector<int> cols(n);
  std::vector<char> used(m, 0);
  std::function<void(int, double)> rec = [&](int i, double sum) {
    if (i == n) {
      costs.push_back(sum);
      return;
    }
    for (int j = 0; j < m; ++j) {
      if (used[j] || c(i, j) == kInf) continue;
      used[j] = 1;
      rec(i + 1, sum + c(i, j));
      used[j] = 0;
    }
  };
  rec(0, 0.0);
  std::sort(costs.begin(), costs.end());
  return costs;
}

// Random n x m matrix: integer costs in [-4, 5] (many ties) or uniform reals, with a fraction of
// +inf entries.
Eigen::MatrixXd random_cost(core::Rng& rng, int n, int m, bool integer, double p_inf) {
  Eigen::MatrixXd c(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double x = rng.uniform();
      c(i, j) = integer ? std::floor(10.0 * x) - 4.0 : 20.0 * x - 10.0;
      if (rng.uniform() < p_inf) c(i, j) = kInf;
    }
  }
  return c;
}

void expect_matches_brute_force(const Eigen::MatrixXd& c, int k) {
  const auto expected = brute_force_costs(c);
  const auto got = murty(c, k);
  const auto want = std::min<std::size_t>(expected.size(), k);
  ASSERT_EQ(static_cast<std::size_t>(got.costs.size()), want) << c;
  std::set<std::vector<std::int64_t>> distinct;
  for (Eigen::Index r = 0; r < got.costs.size(); ++r) {
    EXPECT_NEAR(got.costs[r], expected[r], 1e-9) << "rank " << r << "\n" << c;
    if (r > 0) {
      EXPECT_GE(got.costs[r], got.costs[r - 1]);
    }
    std::vector<std::int64_t> a(got.assignments.row(r).begin(), got.assignments.row(r).end());
    double sum = 0.0;
    std::set<std::int64_t> cols(a.begin(), a.end());
    EXPECT_EQ(cols.size(), a.size());
    for (std::size_t i = 0; i < a.size(); ++i) sum += c(static_cast<Eigen::Index>(i), a[i]);
    EXPECT_NEAR(sum, got.costs[r], 1e-9);
    distinct.insert(a);
  }
  EXPECT_EQ(distinct.size(), want);
}

}  // namespace

TEST(LinearAssignment, SolvesASmallSquareProblem) {
  Eigen::MatrixXd c(3, 3);
  c << 4, 1, 3,
       2, 0, 5,
       3, 2, 2;
  const auto s = linear_assignment(c);
  EXPECT_EQ(s.col_of_row, (std::vector<int>{1, 0, 2}));
  EXPECT_DOUBLE_EQ(s.cost, 5.0);
}

TEST(LinearAssignment, DualsCertifyOptimality) {
  // u_i + v_j <= c_ij everywhere, equality on assigned pairs, v <= 0 and v = 0 on unassigned
  // columns: then sum(u) + sum(v) = cost is the LP dual bound.
  core::Rng rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::MatrixXd c = random_cost(rng, 6, 9, false, 0.2);
    LinearAssignment s;
    try {
      s = linear_assignment(c);
    } catch (const InvalidArgument&) {
      continue;  // infeasible draw
    }
    std::vector<char> used(c.cols(), 0);
    for (int i = 0; i < c.rows(); ++i) {
      used[s.col_of_row[i]] = 1;
      EXPECT_NEAR(c(i, s.col_of_row[i]), s.row_dual[i] + s.col_dual[s.col_of_row[i]], 1e-9);
      for (int j = 0; j < c.cols(); ++j) EXPECT_LE(s.row_dual[i] + s.col_dual[j], c(i, j) + 1e-9);
    }
    for (int j = 0; j < c.cols(); ++j) {
      EXPECT_LE(s.col_dual[j], 1e-12);
      if (!used[j]) {
        EXPECT_EQ(s.col_dual[j], 0.0);
      }
    }
    EXPECT_NEAR(s.row_dual.sum() + s.col_dual.sum(), s.cost, 1e-9);
    EXPECT_NEAR(s.cost, brute_force_costs(c).front(), 1e-9);
  }
}

TEST(LinearAssignment, InfeasibleMatrixIsAClearError) {
  Eigen::MatrixXd c(2, 3);
  c << 1, kInf, kInf,
       2, kInf, kInf;  // both rows can only use column 0
  EXPECT_THROW(linear_assignment(c), InvalidArgument);
  Eigen::MatrixXd empty_row = Eigen::MatrixXd::Constant(2, 2, kInf);
  empty_row(0, 0) = 1.0;
  EXPECT_THROW(linear_assignment(empty_row), InvalidArgument);
}

TEST(LinearAssignment, EmptyProblemHasCostZero) {
  const auto s = linear_assignment(Eigen::MatrixXd(0, 4));
  EXPECT_TRUE(s.col_of_row.empty());
  EXPECT_EQ(s.cost, 0.0);
}

TEST(Assign, BadInputNamesTheArgument) {
  const auto message = [](auto f) {
    try {
      f();
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Eigen::MatrixXd tall = Eigen::MatrixXd::Zero(3, 2);
  EXPECT_NE(message([&] { linear_assignment(tall); }).find("cost"), std::string::npos);
  EXPECT_NE(message([&] { murty(tall, 3); }).find("(3, 2)"), std::string::npos);
  Eigen::MatrixXd with_nan = Eigen::MatrixXd::Zero(2, 2);
  with_nan(1, 0) = std::nan("");
  EXPECT_NE(message([&] { murty(with_nan, 1); }).find("cost contains NaN at (1, 0)"),
            std::string::npos);
  with_nan(1, 0) = -kInf;
  EXPECT_NE(message([&] { linear_assignment(with_nan); }).find("-inf"), std::string::npos);
  EXPECT_NE(message([&] { murty(Eigen::MatrixXd::Zero(2, 2), 0); }).find("k must be >= 1, got 0"),
            std::string::npos);
  EXPECT_NE(message([&] { murty(Eigen::MatrixXd::Zero(2, 2), -3); }).find("-3"),
            std::string::npos);
}

TEST(Murty, MatchesBruteForceOnRandomMatrices) {
  core::Rng rng(17);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + static_cast<int>(rng.uniform() * 5);             // 1..5
    const int m = n + static_cast<int>(rng.uniform() * 3);             // n..n+2
    const bool integer = trial % 2 == 0;                               // ties
    const double p_inf = (trial % 3) * 0.2;                            // 0, 0.2, 0.4
    const Eigen::MatrixXd c = random_cost(rng, n, m, integer, p_inf);
    expect_matches_brute_force(c, 1 + static_cast<int>(rng.uniform() * 150));
  }
}

TEST(Murty, ReturnsAllAssignmentsWhenKExceedsTheFeasibleCount) {
  core::Rng rng(5);
  const Eigen::MatrixXd c = random_cost(rng, 4, 5, true, 0.3);
  expect_matches_brute_force(c, 100000);
  // All-equal costs: every one of the 5!/1! = 120 assignments, distinct.
  expect_matches_brute_force(Eigen::MatrixXd::Ones(4, 5), 1000);
}

TEST(Murty, GlmbShapedMatrix) {
  // n tracks x (m detections + n missed-detection columns), missed column i allowed only for
  // track i: the shape the GLMB update ranks.
  core::Rng rng(9);
  const int n = 4, m = 3;
  Eigen::MatrixXd c = Eigen::MatrixXd::Constant(n, m + n, kInf);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) c(i, j) = 5.0 * rng.uniform() - 4.0;
    c(i, m + i) = rng.uniform();
  }
  expect_matches_brute_force(c, 1000);
}

TEST(Murty, InfeasibleMatrixGivesNoAssignments) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Constant(2, 3, kInf);
  c(0, 1) = 1.0;
  c(1, 1) = 2.0;
  const auto r = murty(c, 5);
  EXPECT_EQ(r.costs.size(), 0);
  EXPECT_EQ(r.assignments.rows(), 0);
  EXPECT_EQ(r.assignments.cols(), 2);
}

TEST(Murty, FirstEqualsLinearAssignmentOnLargerMatrices) {
  core::Rng rng(23);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::MatrixXd c = random_cost(rng, 30, 30 + trial, false, 0.1);
    const auto s = linear_assignment(c);
    const auto r = murty(c, 50);
    ASSERT_EQ(r.costs.size(), 50);
    EXPECT_NEAR(r.costs[0], s.cost, 1e-9);
    for (int q = 1; q < 50; ++q) EXPECT_GE(r.costs[q], r.costs[q - 1]);
  }
}

// GLMB-shaped matrices (a few detection columns, then each row's own missed and absent columns)
// whose sparse gates split the rows into independent clusters: ranked per cluster and merged, the
// k best must still be the brute force's, including ties (integer costs) and the costs summed
// over the rows in order.
TEST(Murty, IndependentClustersMatchBruteForce) {
  core::Rng rng(41);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + static_cast<int>(rng.uniform() * 6), d = static_cast<int>(rng.uniform() * 4);
    const bool integer = trial % 2 == 0;
    Eigen::MatrixXd c = Eigen::MatrixXd::Constant(n, d + 2 * n, kInf);
    const Eigen::MatrixXd values = random_cost(rng, n, d + 2, integer, 0.0);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < d; ++j) {
        if (rng.uniform() < 0.3) c(i, j) = values(i, j);
      }
      c(i, d + i) = values(i, d);
      c(i, d + n + i) = values(i, d + 1);
    }
    expect_matches_brute_force(c, 1 + static_cast<int>(rng.uniform() * 40));
  }
}

TEST(Murty, ClusterWithTooFewColumnsIsInfeasible) {
  // Rows 0-1 share the one column they can take; row 2 is on its own.
  Eigen::MatrixXd c = Eigen::MatrixXd::Constant(3, 4, kInf);
  c(0, 0) = 1.0;
  c(1, 0) = 2.0;
  c(2, 1) = 0.5;
  c(2, 2) = 0.7;
  EXPECT_EQ(murty(c, 3).costs.size(), 0);
  c(1, 3) = 4.0;  // now row 1 has a column of its own: two assignments of rows 0-1, two of row 2
  const auto r = murty(c, 10);
  ASSERT_EQ(r.costs.size(), 2);  // row 0 must take column 0, row 1 column 3
  EXPECT_EQ(r.costs[0], 1.0 + 4.0 + 0.5);
  EXPECT_EQ(r.costs[1], 1.0 + 4.0 + 0.7);
}

TEST(Murty, ClusteredMatrixStillRejectsNaN) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Constant(2, 4, kInf);
  c(0, 0) = 1.0;
  c(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(murty(c, 2), InvalidArgument);
  c(1, 1) = -kInf;
  EXPECT_THROW(murty(c, 2), InvalidArgument);
}

TEST(Murty, EmptyProblemHasOneAssignment) {
  const auto r = murty(Eigen::MatrixXd(0, 3), 4);
  ASSERT_EQ(r.costs.size(), 1);
  EXPECT_EQ(r.costs[0], 0.0);
  EXPECT_EQ(r.assignments.cols(), 0);
}

// --- Pooled rows --------------------------------------------------------------------------------

namespace {

// A pool row: its finite shared entries (column -> cost) and its private costs.
struct PoolRow {
  std::map<int, double> shared;
  std::vector<double> own;
};

// The dense matrix PooledMurty::rank documents for the problem of pool rows `rows`, and each of
// its columns' choice code (shared column c, or -1 - p).
Eigen::MatrixXd dense_problem(const std::vector<PoolRow>& pool, const std::vector<int>& rows,
                              int n_private, std::vector<int>& codes) {
  std::set<int> taken;
  for (int q : rows) {
    for (const auto& [c, x] : pool[q].shared) taken.insert(c);
  }
  codes.assign(taken.begin(), taken.end());
  for (int p = 0; p < n_private; ++p) codes.insert(codes.end(), rows.size(), -1 - p);
  const int n = static_cast<int>(rows.size()), t = static_cast<int>(taken.size());
  Eigen::MatrixXd c = Eigen::MatrixXd::Constant(n, static_cast<Eigen::Index>(codes.size()), kInf);
  for (int i = 0; i < n; ++i) {
    const PoolRow& row = pool[rows[i]];
    for (int j = 0; j < t; ++j) {
      const auto found = row.shared.find(codes[j]);
      if (found != row.shared.end()) c(i, j) = found->second;
    }
    for (int p = 0; p < n_private; ++p) c(i, t + p * n + i) = row.own[p];
  }
  return c;
}

// Random pool rows over `shared` columns: each column finite with probability `density`, integer
// costs (ties) or reals; private costs +inf with probability 0.15.
std::vector<PoolRow> random_pool(core::Rng& rng, int size, int shared, int n_private,
                                 double density, bool integer) {
  std::vector<PoolRow> pool(static_cast<std::size_t>(size));
  for (auto& row : pool) {
    for (int c = 0; c < shared; ++c) {
      if (rng.uniform() < density) {
        row.shared[c] = integer ? std::floor(10.0 * rng.uniform()) - 4.0 : 20.0 * rng.uniform() - 10.0;
      }
    }
    for (int p = 0; p < n_private; ++p) {
      const double x = integer ? std::floor(6.0 * rng.uniform()) : 10.0 * rng.uniform();
      row.own.push_back(rng.uniform() < 0.15 ? kInf : x);
    }
  }
  return pool;
}

void load(PooledMurty& ranking, const std::vector<PoolRow>& pool, int shared, int n_private) {
  ranking.reset(shared, n_private);
  for (const PoolRow& row : pool) {
    std::vector<int> cols;
    std::vector<double> costs;
    for (const auto& [c, x] : row.shared) {
      cols.push_back(c);
      costs.push_back(x);
    }
    ranking.add_row(cols.data(), costs.data(), static_cast<int>(cols.size()), row.own.data());
  }
}

}  // namespace

// The pool's ranking of a problem is murty() of its dense matrix, assignment for assignment, in
// the same order (equal integer costs included), however the problems of one pool share rows and
// clusters and in whatever order they ask for more of a cluster's ranking; and murty() itself is
// the brute force's (expect_matches_brute_force).
TEST(PooledMurty, IsMurtyOfTheDenseMatrixOfEveryProblem) {
  core::Rng rng(77);
  PooledMurty ranking;
  int compared = 0, clustered = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const int shared = static_cast<int>(rng.uniform() * 7), n_private = trial % 3;
    const int size = 1 + static_cast<int>(rng.uniform() * 9);
    const auto pool = random_pool(rng, size, shared, n_private, 0.1 + 0.3 * rng.uniform(),
                                  trial % 2 == 0);
    load(ranking, pool, shared, n_private);
    ASSERT_EQ(ranking.rows(), size);
    for (int problem = 0; problem < 8; ++problem) {
      std::vector<int> rows;
      for (int q = 0; q < size; ++q) {
        if (rng.uniform() < 0.6) rows.push_back(q);
      }
      if (problem % 3 == 2) std::reverse(rows.begin(), rows.end());  // any row order
      std::vector<int> codes;
      const Eigen::MatrixXd dense = dense_problem(pool, rows, n_private, codes);
      const int k = 1 + static_cast<int>(rng.uniform() * 30);
      if (dense.rows() > dense.cols()) continue;  // murty() rejects it; the pool gives none
      const auto want = murty(dense, k);
      const auto& got = ranking.rank(rows, k);
      ASSERT_EQ(got.costs.size(), want.costs.size()) << dense;
      ASSERT_EQ(got.assignments.cols(), static_cast<Eigen::Index>(rows.size()));
      for (Eigen::Index s = 0; s < want.costs.size(); ++s) {
        EXPECT_EQ(got.costs[s], want.costs[s]) << "rank " << s << "\n" << dense;
        for (Eigen::Index i = 0; i < dense.rows(); ++i) {
          EXPECT_EQ(got.assignments(s, i), codes[static_cast<std::size_t>(want.assignments(s, i))])
              << "rank " << s << " row " << i << "\n" << dense;
        }
      }
      if (problem == 0 && dense.rows() <= 7) expect_matches_brute_force(dense, k);
      ++compared;
      clustered += want.costs.size() > 1;
    }
  }
  EXPECT_GT(compared, 600);
  EXPECT_GT(clustered, 300);
}

TEST(PooledMurty, EmptyInfeasibleAndBadInput) {
  PooledMurty ranking;
  ranking.reset(2, 1);
  const int cols[] = {0, 1};
  const double costs[] = {1.0, 2.0}, own[] = {kInf}, own_finite[] = {3.0};
  ranking.add_row(cols, costs, 1, own);            // row 0: column 0 only
  ranking.add_row(cols, costs, 1, own);            // row 1: column 0 only
  ranking.add_row(nullptr, nullptr, 0, own);       // row 2: nothing finite
  ranking.add_row(cols + 1, costs + 1, 1, own_finite);  // row 3: column 1 or its own
  const auto& none = ranking.rank({}, 3);
  ASSERT_EQ(none.costs.size(), 1);  // the empty assignment
  EXPECT_EQ(none.costs[0], 0.0);
  EXPECT_EQ(ranking.rank({0, 1}, 3).costs.size(), 0);  // two rows, one column
  EXPECT_EQ(ranking.rank({2, 3}, 3).costs.size(), 0);  // a row without a finite entry
  const auto& two = ranking.rank({0, 3}, 5);
  ASSERT_EQ(two.costs.size(), 2);
  EXPECT_EQ(two.costs[0], 1.0 + 2.0);
  EXPECT_EQ(two.assignments(1, 1), -1);  // row 3's private column
  EXPECT_THROW(ranking.rank({0, 0}, 1), InvalidArgument);
  EXPECT_THROW(ranking.rank({4}, 1), InvalidArgument);
  EXPECT_THROW(ranking.rank({0}, 0), InvalidArgument);
  const double nan[] = {std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW(ranking.add_row(cols, nan, 1, own), InvalidArgument);
  const double minus_inf[] = {-kInf};
  EXPECT_THROW(ranking.add_row(nullptr, nullptr, 0, minus_inf), InvalidArgument);
  const int decreasing[] = {1, 0};
  EXPECT_THROW(ranking.add_row(decreasing, costs, 2, own), InvalidArgument);
  EXPECT_THROW(ranking.reset(-1, 0), InvalidArgument);
}

// --- Gibbs sampler ---------------------------------------------------------------------------

namespace {

// Every feasible assignment with its probability under pi(g) ~ exp(-cost(g)).
std::map<std::vector<int>, double> brute_force_distribution(const Eigen::MatrixXd& c) {
  const int n = static_cast<int>(c.rows()), m = static_cast<int>(c.cols());
  std::map<std::vector<int>, double> p;
  std::vector<int> cols(n);
  std::vector<char> used(m, 0);
  std::function<void(int, double)> rec = [&](int i, double sum) {
    if (i == n) {
      p[cols] = std::exp(-sum);
      return;
    }
    for (int j = 0; j < m; ++j) {
      if (used[j] || c(i, j) == kInf) continue;
      used[j] = 1;
      cols[i] = j;
      rec(i + 1, sum + c(i, j));
      used[j] = 0;
    }
  };
  rec(0, 0.0);
  double total = 0.0;
  for (const auto& [a, w] : p) total += w;
  for (auto& [a, w] : p) w /= total;
  return p;
}

TEST(GibbsAssignments, VisitFrequenciesConvergeToTheAssignmentWeights) {
  // A 3 x 5 GLMB-like matrix with forbidden pairs: 40 000 sweeps, every feasible assignment's
  // visit frequency within 5 binomial standard deviations (inflated 3x for the chain's
  // autocorrelation) of its exact probability.
  core::Rng rng(7);
  Eigen::MatrixXd c = random_cost(rng, 3, 5, false, 0.2) / 5.0;
  c(0, 4) = c(1, 3) = kInf;
  const auto exact = brute_force_distribution(c);
  const std::int64_t sweeps = 40000;
  const SampledAssignments s = gibbs_assignments(c, sweeps, rng);
  EXPECT_EQ(s.visits.sum(), sweeps);
  std::map<std::vector<int>, std::int64_t> visited;
  for (Eigen::Index r = 0; r < s.costs.size(); ++r) {
    std::vector<int> a(3);
    for (int i = 0; i < 3; ++i) a[i] = static_cast<int>(s.assignments(r, i));
    visited[a] = s.visits[r];
  }
  for (const auto& [a, p] : exact) {
    const double freq = static_cast<double>(visited[a]) / sweeps;
    const double sd = 3.0 * std::sqrt(p * (1.0 - p) / sweeps);
    EXPECT_NEAR(freq, p, 5.0 * sd + 1e-4) << "assignment " << a[0] << a[1] << a[2];
  }
  for (const auto& [a, count] : visited) EXPECT_TRUE(exact.count(a)) << "infeasible state";
}

TEST(GibbsAssignments, DistinctFeasibleSortedAndStartsFromTheOptimum) {
  core::Rng rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 1 + trial % 4;
    const Eigen::MatrixXd c = random_cost(rng, n, n + 3, trial % 2 == 0, 0.2);
    const auto all = brute_force_costs(c);
    const SampledAssignments s = gibbs_assignments(c, 200, rng);
    if (all.empty()) {
      EXPECT_EQ(s.costs.size(), 0);
      continue;
    }
    ASSERT_GE(s.costs.size(), 1);
    EXPECT_NEAR(s.costs[0], all.front(), 1e-9);  // the chain starts at the optimum
    std::set<std::vector<std::int64_t>> seen;
    for (Eigen::Index r = 0; r < s.costs.size(); ++r) {
      if (r > 0) EXPECT_LE(s.costs[r - 1], s.costs[r]);
      std::vector<std::int64_t> a(s.assignments.row(r).data(), s.assignments.row(r).data() + n);
      EXPECT_TRUE(seen.insert(a).second) << "duplicate assignment";
      EXPECT_EQ(std::set<std::int64_t>(a.begin(), a.end()).size(), static_cast<std::size_t>(n));
      double total = 0.0;
      for (int i = 0; i < n; ++i) total += c(i, a[i]);
      EXPECT_NEAR(total, s.costs[r], 1e-9);
      EXPECT_GE(s.visits[r], 1);
    }
    EXPECT_EQ(s.visits.sum(), 200);
  }
}

TEST(GibbsAssignments, SameSeedSameResultAndBadInput) {
  core::Rng a(11), b(11), rng(5);
  const Eigen::MatrixXd c = random_cost(rng, 4, 9, false, 0.1);
  const auto sa = gibbs_assignments(c, 300, a);
  const auto sb = gibbs_assignments(c, 300, b);
  EXPECT_EQ(sa.assignments, sb.assignments);
  EXPECT_EQ(sa.visits, sb.visits);
  EXPECT_THROW(gibbs_assignments(c, 0, a), InvalidArgument);
  Eigen::MatrixXd bad = c;
  bad(1, 2) = std::nan("");
  EXPECT_THROW(gibbs_assignments(bad, 10, a), InvalidArgument);
  EXPECT_THROW(gibbs_assignments(c.transpose(), 10, a), InvalidArgument);
  // Infeasible: two rows that can only take column 0.
  Eigen::MatrixXd infeasible = Eigen::MatrixXd::Constant(2, 3, kInf);
  infeasible(0, 0) = infeasible(1, 0) = 1.0;
  EXPECT_EQ(gibbs_assignments(infeasible, 10, a).costs.size(), 0);
}

}  // namespace
