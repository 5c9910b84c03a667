#pragma once
// vtrack's GLMB tracker: the delta-GLMB filter (filters/glmb.hpp) with the track densities its
// parameters ask for -- Gaussian (Kalman) or particles, the latter with the RGB-D switching
// observation model when given a depth model (filters/particle_glmb.hpp) -- and its labelled
// estimates reported as Tracks: ids 1, 2, ... in the order labels are first reported, through
// the shared track management (confirmation, lost-track memory; filters/track_management.hpp).
//
// The choice of densities is made here, once per tracker; every step then dispatches once to the
// chosen filter (never per track or particle).
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/core/parameters.hpp"
#include "vtrack/filters/glmb.hpp"
#include "vtrack/filters/particle_glmb.hpp"
#include "vtrack/filters/track_management.hpp"
#include "vtrack/filters/tracks.hpp"
#include "vtrack/models/depth_likelihood.hpp"

namespace vtrack::filters {

enum class TrackDensities { gaussian, particles };

struct GlmbTrackerParams {
  GlmbParams glmb;
  // "gaussian": one Gaussian per track (Kalman; exact for linear-Gaussian models, deterministic
  // with Murty's ranking). "particles": the paper's particle implementation (n_particles per
  // track, seeded); needed by the depth model's switching observation.
  TrackDensities densities = TrackDensities::gaussian;
  ParticleParams particle;
  TrackManagementParams management;  // every estimate reported at once by default

  static const core::ParameterTable<GlmbTrackerParams>& table();
};

void validate(const GlmbTrackerParams& params);

// Which state components form an image box, so that Tracks carry boxes (and the lost-track
// memory can compare them): the centre, its velocity and the size. Without one, boxes are NaN.
struct BoxLayout {
  int cx = 0, vx = 1, cy = 2, vy = 3, w = 4, h = 5;
};

class GlmbTracker {
 public:
  // InvalidArgument for inconsistent models or parameters, or a depth model with Gaussian
  // densities.
  GlmbTracker(models::LinearGaussianMotion motion, models::LinearGaussianObservation observation,
              std::vector<GaussianBirth> births, const GlmbTrackerParams& params = {},
              std::optional<models::DepthLikelihood> depth_model = std::nullopt,
              std::optional<BoxLayout> box_layout = std::nullopt);

  // One joint prediction-update with the detections of the scan (z_dim x M, M may be 0) and,
  // with a depth model, the scan's background-subtracted metric depth image (nullptr: a
  // detection-only step). Returns the tracks reported at this scan, in id order: score = the
  // label's existence probability, state and covariance = the track density's moments, the
  // GLMB label (birth time, index).
  // `input`: what the caller knows of each detection beyond its position (filters/glmb.hpp).
  const Tracks& step(const Eigen::Ref<const Eigen::MatrixXd>& detections,
                     const cv::Mat* depth = nullptr, const ScanInput& input = {});
  // The last scan's association statistics, and p_D from the next scan on (an online estimate).
  const ScanSummary& summary() const;
  void set_detection_probability(double p_d);

  const Tracks& tracks() const { return tracks_; }
  // The filter's estimates at the last step (all of them, reported or not by the management).
  const std::vector<GlmbEstimate>& estimates() const;
  Eigen::VectorXd cardinality_distribution() const;
  int map_cardinality() const;
  std::size_t hypothesis_count() const;
  std::size_t track_count() const;
  int time() const;
  Eigen::Index z_dim() const;
  bool has_depth_model() const;
  const GlmbTrackerParams& params() const { return params_; }
  const TrackManager& management() const { return management_; }

 private:
  template <class F>
  decltype(auto) visit(F&& f) const {
    return std::visit(std::forward<F>(f), filter_);
  }
  // Reports the filter's estimates through the track management.
  void report(const std::vector<GlmbEstimate>& estimates);

  struct LabelRecord {
    std::uint64_t id = 0;  // 0 until first reported
    TrackRecord record;
    int last_seen = -1;  // scan of the last estimate
  };
  GlmbTrackerParams params_;
  std::variant<GaussianGlmbFilter, ParticleGlmbFilter> filter_;
  std::optional<BoxLayout> box_layout_;
  TrackManager management_;
  std::map<std::pair<int, int>, LabelRecord> labels_;
  Tracks tracks_;
  std::uint64_t next_id_ = 1;
};

}  // namespace vtrack::filters
