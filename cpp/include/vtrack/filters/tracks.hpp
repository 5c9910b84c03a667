#pragma once
// What every multi-object tracker reports at a step: the same value whatever the filter, so one
// writer, one renderer and one evaluation serve them all.
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

namespace vtrack::filters {

struct TrackEstimate {
  // Identity, stable for the track's life: 1, 2, ... in the order tracks are first reported.
  std::uint64_t id = 0;
  // Image box: left, top, width, height (pixels). NaN when the tracker's state is not an image
  // box (a GLMB tracker on a user's state space).
  double x = std::numeric_limits<double>::quiet_NaN();
  double y = std::numeric_limits<double>::quiet_NaN();
  double w = std::numeric_limits<double>::quiet_NaN();
  double h = std::numeric_limits<double>::quiet_NaN();
  // Confidence in [0, 1]: the existence probability where the filter has one (multi-Bernoulli
  // r, a GLMB label's posterior probability of existence).
  double score = 1.0;
  // The filter's own extras: its state estimate and covariance (empty when it has none), and its
  // label as (birth time, birth index) where it has one (GLMB; -1 otherwise).
  Eigen::VectorXd state;
  Eigen::MatrixXd covariance;
  int birth_time = -1;
  int birth_index = -1;
};

// One step's estimates, in id order.
using Tracks = std::vector<TrackEstimate>;

}  // namespace vtrack::filters
