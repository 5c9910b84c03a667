#include "vtrack/filters/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/filters/assign.hpp"

namespace vtrack::metrics {
namespace {

void check_parameters(double c, double p) {
  if (!(c > 0.0) || !std::isfinite(c)) {
    throw InvalidArgument("c (cut-off) must be positive and finite, got " + std::to_string(c));
  }
  if (!(p >= 1.0) || !std::isfinite(p)) {
    throw InvalidArgument("p (order) must be >= 1 and finite, got " + std::to_string(p));
  }
}

void check_points(const Eigen::Ref<const Eigen::MatrixXd>& x, const char* name) {
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      if (!std::isfinite(x(i, j))) {
        throw InvalidArgument(std::string(name) + " has a non-finite entry at (" +
                              std::to_string(i) + ", " + std::to_string(j) + ")");
      }
    }
  }
}

// Both sets non-empty must have the same point dimension.
void check_dims(Eigen::Index rows_x, Eigen::Index dim_x, Eigen::Index rows_y, Eigen::Index dim_y,
                const char* x, const char* y) {
  if (rows_x > 0 && rows_y > 0 && dim_x != dim_y) {
    throw InvalidArgument(std::string(x) + " and " + y + " must have the same dimension, got " +
                          std::to_string(dim_x) + " and " + std::to_string(dim_y));
  }
}

// min(c, |x_i - y_j|) for every pair.
Eigen::MatrixXd cut_off_distances(const Eigen::Ref<const Eigen::MatrixXd>& x,
                                  const Eigen::Ref<const Eigen::MatrixXd>& y, double c) {
  Eigen::MatrixXd d(x.rows(), y.rows());
  for (Eigen::Index j = 0; j < y.rows(); ++j) {
    for (Eigen::Index i = 0; i < x.rows(); ++i) d(i, j) = std::min(c, (x.row(i) - y.row(j)).norm());
  }
  return d;
}

// The optimal matching of min(|X|, |Y|) pairs under sum d^p; col_of_row is indexed by the rows of
// `d` (entries -1 for its unmatched rows), whichever side is smaller.
std::vector<int> optimal_matching(const Eigen::MatrixXd& d, double p) {
  std::vector<int> match(d.rows(), -1);
  if (d.rows() == 0 || d.cols() == 0) return match;
  const Eigen::MatrixXd cost = d.array().pow(p);
  if (d.rows() <= d.cols()) return assign::linear_assignment(cost).col_of_row;
  const auto by_col = assign::linear_assignment(cost.transpose()).col_of_row;
  for (std::size_t j = 0; j < by_col.size(); ++j) match[by_col[j]] = static_cast<int>(j);
  return match;
}

// OSPA from the matrix of cut-off base distances (entries in [0, c]) between two sets.
OspaResult ospa_from_distances(const Eigen::MatrixXd& d, double c, double p) {
  const auto n = static_cast<double>(std::max(d.rows(), d.cols()));
  const auto m = static_cast<double>(std::min(d.rows(), d.cols()));
  OspaResult result;
  if (n == 0) return result;
  const auto match = optimal_matching(d, p);
  double localisation = 0.0;
  for (std::size_t i = 0; i < match.size(); ++i) {
    if (match[i] >= 0) localisation += std::pow(d(static_cast<Eigen::Index>(i), match[i]), p);
  }
  const double cardinality = std::pow(c, p) * (n - m);
  result.distance = std::pow((localisation + cardinality) / n, 1.0 / p);
  result.localisation = std::pow(localisation / n, 1.0 / p);
  result.cardinality = std::pow(cardinality / n, 1.0 / p);
  return result;
}

}  // namespace

OspaResult ospa(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::Ref<const Eigen::MatrixXd>& y,
          double c, double p) {
  check_parameters(c, p);
  check_points(x, "x");
  check_points(y, "y");
  check_dims(x.rows(), x.cols(), y.rows(), y.cols(), "x", "y");
  return ospa_from_distances(cut_off_distances(x, y, c), c, p);
}

GospaResult gospa(const Eigen::Ref<const Eigen::MatrixXd>& truth,
            const Eigen::Ref<const Eigen::MatrixXd>& estimates, double c, double p) {
  check_parameters(c, p);
  check_points(truth, "truth");
  check_points(estimates, "estimates");
  check_dims(truth.rows(), truth.cols(), estimates.rows(), estimates.cols(), "truth", "estimates");
  // With alpha = 2, the best partial assignment is an optimal full matching of min(|X|, |Y|)
  // pairs under min(c, d)^p in which the pairs at distance >= c are left unassigned: such a pair
  // costs c^p either way, c^p / 2 as a miss plus c^p / 2 as a false target (Proposition 1).
  const Eigen::MatrixXd d = cut_off_distances(truth, estimates, c);
  const auto match = optimal_matching(d, p);
  GospaResult result;
  for (std::size_t i = 0; i < match.size(); ++i) {
    if (match[i] >= 0 && d(static_cast<Eigen::Index>(i), match[i]) < c) {
      result.localisation += std::pow(d(static_cast<Eigen::Index>(i), match[i]), p);
      ++result.n_assigned;
    }
  }
  result.n_missed = static_cast<int>(truth.rows()) - result.n_assigned;
  result.n_false = static_cast<int>(estimates.rows()) - result.n_assigned;
  const double half = std::pow(c, p) / 2.0;
  result.missed = half * result.n_missed;
  result.false_targets = half * result.n_false;
  result.distance =
      std::pow(result.localisation + result.missed + result.false_targets, 1.0 / p);
  return result;
}

namespace {

// The tracks of `set` that exist somewhere in the window; checks shapes and NaN rows.
std::vector<const Eigen::MatrixXd*> existing_tracks(const std::vector<Eigen::MatrixXd>& set,
                                                    const char* name, Eigen::Index steps,
                                                    Eigen::Index dim) {
  std::vector<const Eigen::MatrixXd*> tracks;
  for (std::size_t k = 0; k < set.size(); ++k) {
    const Eigen::MatrixXd& track = set[k];
    const std::string where = std::string(name) + "[" + std::to_string(k) + "]";
    if (track.rows() != steps || track.cols() != dim) {
      throw InvalidArgument(where + " must be " + std::to_string(steps) + " x " +
                            std::to_string(dim) + " (steps x dimension) like the first track, got " +
                            std::to_string(track.rows()) + " x " + std::to_string(track.cols()));
    }
    bool exists = false;
    for (Eigen::Index t = 0; t < steps; ++t) {
      const auto nan = track.row(t).array().isNaN().count();
      if (nan != 0 && nan != dim) {
        throw InvalidArgument(where + " row " + std::to_string(t) +
                              " is partly NaN; a row is either a state or all NaN (absent)");
      }
      if (nan == 0 && !track.row(t).allFinite()) {
        throw InvalidArgument(where + " row " + std::to_string(t) + " has an infinite entry");
      }
      exists = exists || nan == 0;
    }
    if (exists) tracks.push_back(&track);
  }
  return tracks;
}

// Time-averaged OSPA base distance between two tracks (see the header).
double track_distance(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, double c) {
  double sum = 0.0;
  int steps = 0;
  for (Eigen::Index t = 0; t < x.rows(); ++t) {
    const bool has_x = !std::isnan(x(t, 0)), has_y = !std::isnan(y(t, 0));
    if (!has_x && !has_y) continue;
    ++steps;
    sum += has_x && has_y ? std::min(c, (x.row(t) - y.row(t)).norm()) : c;
  }
  return sum / steps;  // steps > 0: both tracks exist somewhere in the window
}

}  // namespace

OspaResult ospa2(const std::vector<Eigen::MatrixXd>& x, const std::vector<Eigen::MatrixXd>& y,
           double c, double p) {
  check_parameters(c, p);
  if (x.empty() && y.empty()) return OspaResult{};
  const Eigen::MatrixXd& first = x.empty() ? y[0] : x[0];
  if (first.cols() == 0) throw InvalidArgument("tracks must have dimension >= 1, got 0");
  const auto tx = existing_tracks(x, "x", first.rows(), first.cols());
  const auto ty = existing_tracks(y, "y", first.rows(), first.cols());
  Eigen::MatrixXd d(tx.size(), ty.size());
  for (std::size_t j = 0; j < ty.size(); ++j) {
    for (std::size_t i = 0; i < tx.size(); ++i) d(i, j) = track_distance(*tx[i], *ty[j], c);
  }
  return ospa_from_distances(d, c, p);
}

}  // namespace vtrack::metrics
