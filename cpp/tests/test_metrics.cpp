#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/filters/metrics.hpp"

using namespace vtrack;
using namespace vtrack::metrics;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

Eigen::MatrixXd points(std::initializer_list<std::initializer_list<double>> rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()), 2);
  Eigen::Index i = 0;
  for (const auto& r : rows) {
    Eigen::Index j = 0;
    for (double v : r) m(i, j++) = v;
    ++i;
  }
  return m;
}

Eigen::MatrixXd track(std::initializer_list<double> xs) {  // 1-D track, NaN = absent
  Eigen::MatrixXd m(static_cast<Eigen::Index>(xs.size()), 1);
  Eigen::Index t = 0;
  for (double v : xs) m(t++, 0) = v;
  return m;
}

// OSPA by trying every injection of the smaller set into the larger.
double brute_force_ospa(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, double c, double p) {
  const Eigen::MatrixXd& small = x.rows() <= y.rows() ? x : y;
  const Eigen::MatrixXd& large = x.rows() <= y.rows() ? y : x;
  const auto n = large.rows(), m = small.rows();
  if (n == 0) return 0.0;
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {
    double s = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) {
      s += std::pow(std::min(c, (small.row(i) - large.row(perm[i])).norm()), p);
    }
    best = std::min(best, s);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return std::pow((best + std::pow(c, p) * static_cast<double>(n - m)) / static_cast<double>(n),
                  1.0 / p);
}

}  // namespace

TEST(Ospa, HandComputedCases) {
  EXPECT_DOUBLE_EQ(ospa(points({{0, 0}}), points({{3, 4}}), 10.0, 1.0).distance, 5.0);
  EXPECT_DOUBLE_EQ(ospa(points({{0, 0}}), points({{3, 4}}), 2.0, 1.0).distance, 2.0);  // cut off
  // {(0,0), (10,0)} vs {(1,0)}, c = 5, p = 2: match at distance 1, one point unmatched:
  // sqrt((1 + 25) / 2).
  const auto r = ospa(points({{0, 0}, {10, 0}}), points({{1, 0}}), 5.0, 2.0);
  EXPECT_NEAR(r.distance, std::sqrt(13.0), 1e-12);
  EXPECT_NEAR(r.localisation, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(r.cardinality, std::sqrt(12.5), 1e-12);
  // The optimal matching is not the greedy one: greedy pairs (0,0)-(1,0) first (1 + 9 = 10 with
  // p = 1), the optimum crosses ((0,0)-(-2,0), (2,0)-(1,0)): 2 + 1 = 3, over n = 2.
  EXPECT_NEAR(ospa(points({{0, 0}, {2, 0}}), points({{1, 0}, {-2, 0}}), 100.0, 1.0).distance,
              1.5, 1e-12);
}

TEST(Ospa, EmptySets) {
  const Eigen::MatrixXd none(0, 2);
  EXPECT_EQ(ospa(none, none, 3.0, 2.0).distance, 0.0);
  EXPECT_DOUBLE_EQ(ospa(none, points({{1, 1}, {2, 2}}), 3.0, 2.0).distance, 3.0);
  EXPECT_DOUBLE_EQ(ospa(points({{1, 1}}), Eigen::MatrixXd(0, 0), 3.0, 1.0).distance, 3.0);
}

TEST(Ospa, AgreesWithBruteForceAndIsSymmetric) {
  core::Rng rng(31);
  for (int trial = 0; trial < 100; ++trial) {
    const auto nx = static_cast<Eigen::Index>(rng.uniform() * 6);
    const auto ny = static_cast<Eigen::Index>(rng.uniform() * 6);
    Eigen::MatrixXd x(nx, 2), y(ny, 2);
    rng.fill_uniform(x.data(), static_cast<std::size_t>(x.size()));
    rng.fill_uniform(y.data(), static_cast<std::size_t>(y.size()));
    x *= 10.0;
    y *= 10.0;
    const double c = 1.0 + 5.0 * rng.uniform(), p = trial % 2 ? 1.0 : 2.5;
    const double d = ospa(x, y, c, p).distance;
    EXPECT_NEAR(d, brute_force_ospa(x, y, c, p), 1e-10);
    EXPECT_NEAR(d, ospa(y, x, c, p).distance, 1e-10);
    EXPECT_LE(d, c + 1e-12);
  }
}

TEST(Gospa, HandComputedDecomposition) {
  // Truth (0,0) is 1 from estimate (0,1): assigned. Truth (5,0) is 3 >= c from (5,3): better
  // left unassigned. (9,9) is a false target.
  const auto truth = points({{0, 0}, {5, 0}});
  const auto est = points({{0, 1}, {5, 3}, {9, 9}});
  const auto g1 = gospa(truth, est, 2.0, 1.0);
  EXPECT_DOUBLE_EQ(g1.localisation, 1.0);
  EXPECT_DOUBLE_EQ(g1.missed, 1.0);         // one miss at c/2
  EXPECT_DOUBLE_EQ(g1.false_targets, 2.0);  // two false at c/2
  EXPECT_DOUBLE_EQ(g1.distance, 4.0);
  EXPECT_EQ(g1.n_assigned, 1);
  EXPECT_EQ(g1.n_missed, 1);
  EXPECT_EQ(g1.n_false, 2);
  const auto g2 = gospa(truth, est, 2.0, 2.0);  // c^p / 2 = 2 per miss or false
  EXPECT_DOUBLE_EQ(g2.distance, std::sqrt(1.0 + 2.0 + 4.0));
  const auto none = gospa(Eigen::MatrixXd(0, 2), Eigen::MatrixXd(0, 2), 2.0, 1.0);
  EXPECT_EQ(none.distance, 0.0);
  const auto all_missed = gospa(truth, Eigen::MatrixXd(0, 2), 4.0, 1.0);
  EXPECT_DOUBLE_EQ(all_missed.distance, 4.0);
  EXPECT_EQ(all_missed.n_missed, 2);
}

TEST(Ospa2, HandComputedTracks) {
  // x1 and y1 over 4 steps: |0-0|, |1-1|, |2-5| = 3, then only y1 exists (c = 10):
  // (0 + 0 + 3 + 10) / 4 = 3.25. y2 never exists in the window and is ignored.
  const std::vector<Eigen::MatrixXd> x = {track({0, 1, 2, kNan})};
  std::vector<Eigen::MatrixXd> y = {track({0, 1, 5, 3}), track({kNan, kNan, kNan, kNan})};
  EXPECT_DOUBLE_EQ(ospa2(x, y, 10.0, 1.0).distance, 3.25);
  // y3 exists at step 1 only, 99 away from x1; d(x1, y3) = (10 + 10 + 10) / 3 = 10 over steps
  // {0, 1, 2}. x1 still matches y1; y3 adds c to the cardinality term: (3.25 + 10) / 2.
  y.push_back(track({kNan, 100, kNan, kNan}));
  EXPECT_DOUBLE_EQ(ospa2(x, y, 10.0, 1.0).distance, 6.625);
  EXPECT_DOUBLE_EQ(ospa2(x, y, 10.0, 2.0).distance, std::sqrt((3.25 * 3.25 + 100.0) / 2.0));
  EXPECT_DOUBLE_EQ(ospa2(y, x, 10.0, 2.0).distance, ospa2(x, y, 10.0, 2.0).distance);
  EXPECT_EQ(ospa2({}, {}, 10.0, 1.0).distance, 0.0);
  EXPECT_DOUBLE_EQ(ospa2(x, {}, 10.0, 1.0).distance, 10.0);
}

TEST(Metrics, BadInputNamesTheArgument) {
  const auto a = points({{0, 0}});
  EXPECT_THROW(ospa(a, a, 0.0, 1.0), InvalidArgument);
  EXPECT_THROW(ospa(a, a, 1.0, 0.5), InvalidArgument);
  EXPECT_THROW(gospa(a, Eigen::MatrixXd::Zero(1, 3), 1.0, 1.0), InvalidArgument);
  Eigen::MatrixXd bad = a;
  bad(0, 1) = std::numeric_limits<double>::infinity();
  try {
    ospa(a, bad, 1.0, 1.0);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("y has a non-finite entry at (0, 1)"), std::string::npos);
  }
  Eigen::MatrixXd partly(2, 2);
  partly << 0, kNan, 1, 1;
  EXPECT_THROW(ospa2({partly}, {}, 1.0, 1.0), InvalidArgument);
  EXPECT_THROW(ospa2({track({0, 1})}, {track({0, 1, 2})}, 1.0, 1.0), InvalidArgument);
}
