#pragma once
// Track management beyond the filters' own estimates, shared by the multi-Bernoulli tracker and
// the box GLMB: confirmation (a track is reported only after it has been estimated on
// confirm_frames steps) and a lost-track memory (a confirmed track that ends leaves its id, last
// reported box and velocity behind for lost_memory steps; an unconfirmed track whose box overlaps
// a remembered one, moved on at its velocity, by IoU >= relabel_overlap, or, failing that, whose
// centre lies within relabel_distance of the remembered box's moved-on centre (in units of that
// box's width and height), takes that id back and is confirmed at once, so a person keeps one
// identity across a short occlusion). Neither changes what the filter believes, only what it
// reports and under which id.
//
// Each tracker sets its own defaults (MultiBernoulliParams and BoxTrackerParams say why);
// confirm_frames 1 with lost_memory 0 reports every estimate as the filter gives it.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/parameters.hpp"

namespace vtrack::filters {

struct TrackManagementParams {
  int confirm_frames = 1;        // >= 1; steps with an estimate before a track is reported
  int lost_memory = 0;           // >= 0; steps a lost confirmed track is remembered (0 = off)
  double relabel_overlap = 0.3;  // (0, 1]; IoU a new track needs with a remembered one
  // >= 0 (0 = off): else, the largest normalised centre distance d to a remembered box (x, y,
  // w, h) moved on at its velocity, d^2 = (dx / w)^2 + (dy / h)^2, at which a new track takes
  // that id (the nearest such). IoU alone fails where a track is re-founded after a loss of more
  // than a few frames: the new box and the remembered one rarely overlap by then (the lost box
  // was shrinking as its evidence faded, the new one starts at the birth's size, and the
  // velocity's error grows with the gap), though the new track starts within a box of where the
  // lost one was heading.
  double relabel_distance = 0.0;

  static const core::ParameterTable<TrackManagementParams>& table();
};

// InvalidArgument naming the parameter and its value.
void validate(const TrackManagementParams& params);

// The reporting state of one track.
struct TrackRecord {
  int hits = 0;            // steps on which the track had an estimate
  bool confirmed = false;  // reported whenever it has an estimate
  Eigen::Vector2f velocity = Eigen::Vector2f::Zero();  // box centre change per step
  Eigen::Vector4f last_box = Eigen::Vector4f::Zero();  // (x, y, w, h) when last reported
  int last_reported = -1;                               // step of that report
};

// Intersection over union of two boxes (x, y, w, h); 0 when either is empty.
double box_iou(const Eigen::Vector4f& a, const Eigen::Vector4f& b);

class TrackManager {
 public:
  explicit TrackManager(const TrackManagementParams& params = {});

  // Starts step `step` (0, 1, ...): forgets lost tracks older than lost_memory steps.
  void begin_step(int step);
  // Track `id` (0 while it has none) has an estimate `box` at the current step: counts the hit;
  // if the track is not confirmed and a remembered track matches, returns that track's id (the
  // caller takes it over, with the remembered velocity, which `record` receives) and confirms
  // it; confirms after confirm_frames hits. Returns std::nullopt when no id is taken back. A
  // remembered track that is observed again under its own id is no longer lost.
  std::optional<std::uint64_t> observe(std::uint64_t id, TrackRecord& record,
                                       const Eigen::Vector4f& box);
  // Whether the track is reported at this step (confirmed); if so, records the report.
  bool report(TrackRecord& record, const Eigen::Vector4f& box);
  // A track with this id has ended: remembered if it was confirmed and ever reported.
  void end(std::uint64_t id, const TrackRecord& record);

  const TrackManagementParams& params() const { return params_; }
  // Lost tracks currently remembered (0: nothing depends on how many steps pass).
  std::size_t lost_count() const { return lost_.size(); }

 private:
  struct LostTrack {
    std::uint64_t id;
    Eigen::Vector4f box;       // last reported box
    Eigen::Vector2f velocity;  // per step
    int step;                  // step of that report
  };
  // The remembered track an unconfirmed estimate `box` takes the id of (relabel_overlap, then
  // relabel_distance), or lost_.end().
  std::vector<LostTrack>::iterator find_lost(const Eigen::Vector4f& box);

  TrackManagementParams params_;
  std::vector<LostTrack> lost_;
  int step_ = 0;
};

}  // namespace vtrack::filters
