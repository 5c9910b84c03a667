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
// Colour appearance (appearance_rate > 0; beyond the papers, issue 12): a tracker that sees the
// frame passes each track's colour histogram (filters/appearance.hpp measures it: the part-based
// paper's HSV histogram over the box's foreground pixels). Each confirmed track keeps a colour
// model q, updated while its box overlaps no other track's box, q <- (1 - a) q + a p with
// a = appearance_rate (Nummiaro et al.'s adaptive template, the part-based paper's ref. [14]).
// Identities are then decided by the cost of an id for a track,
//   c = (1 - rho[p, q]) / (2 sigma^2) + d^2 / 2,
// the negative log of eq. 11's colour likelihood (sigma = appearance_sigma, rho of eq. 10) and of
// a unit Gaussian on the centre distance d from where the id was heading (its box moved on at its
// velocity; d in that box's widths and heights):
//   (1) tracks that come apart after their boxes overlapped (resolve()): the ids of those tracks
//       and of those that ended while overlapping them (lost) go to the tracks by the assignment
//       of least total cost (people who cross are re-labelled by their colours, not by which way
//       the filter's estimates went);
//   (2) a new track (observe()) takes, among the remembered ids within appearance_distance whose
//       colours lie within 2 sigma (sqrt(1 - rho) <= 2 appearance_sigma), the one of least cost,
//       before the overlap and distance rules.
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
  // Colour appearance (file comment): [0, 1], 0 = off; the model's learning rate per step.
  double appearance_rate = 0.0;
  // > 0: sigma of eq. 11 on the Bhattacharyya distance.
  double appearance_sigma = 0.3;
  // >= 0: centre distance (lost box sizes) within which a new track may take a lost id by colour.
  double appearance_distance = 3.0;

  static const core::ParameterTable<TrackManagementParams>& table();
};

// InvalidArgument naming the parameter and its value.
void validate(const TrackManagementParams& params);

// A normalised colour histogram (filters/appearance.hpp); empty: none measured.
using ColourHistogram = std::vector<float>;
// Bhattacharyya coefficient rho[p, q] = sum_u sqrt(p_u q_u) (part-based paper eq. 10) of two
// normalised histograms; InvalidArgument when their sizes differ.
double colour_coefficient(const ColourHistogram& p, const ColourHistogram& q);

// The reporting state of one track (an identity: it moves with the id).
struct TrackRecord {
  int hits = 0;            // steps on which the track had an estimate
  bool confirmed = false;  // reported whenever it has an estimate
  Eigen::Vector2f velocity = Eigen::Vector2f::Zero();  // box centre change per step
  Eigen::Vector4f last_box = Eigen::Vector4f::Zero();  // (x, y, w, h) when last reported
  int last_reported = -1;                               // step of that report
  // Colour appearance (appearance_rate > 0): the model (empty until the track is first seen
  // alone), where the track was, how fast it moved and at which step when last alone, and the
  // confirmed tracks its box has overlapped since.
  ColourHistogram appearance;
  Eigen::Vector4f alone_box = Eigen::Vector4f::Zero();
  Eigen::Vector2f alone_velocity = Eigen::Vector2f::Zero();
  int alone_step = -1;
  std::vector<std::uint64_t> overlapped;
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
  // `seen`: the track's colour histogram at this step (empty: none), for appearance.
  std::optional<std::uint64_t> observe(std::uint64_t id, TrackRecord& record,
                                       const Eigen::Vector4f& box,
                                       const ColourHistogram& seen = {});
  // One step's tracks, after observe(), for appearance (a no-op when appearance_rate is 0).
  struct View {
    std::uint64_t* id;
    TrackRecord* record;
    Eigen::Vector4f box;
    const ColourHistogram* seen;  // nullptr or empty: not measured
  };
  // Finds the boxes that overlap; confirmed tracks that overlapped others and are now alone take
  // the ids of that episode by least cost (file comment; *id and *record are exchanged, an id
  // left over is ended as lost, a lost id taken leaves the memory); then the models of the
  // confirmed tracks that are alone learn their histograms.
  void resolve(const std::vector<View>& tracks);
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
    TrackRecord record;  // last_box, velocity and last_reported: where it was heading
  };
  // The remembered track an unconfirmed estimate `box` takes the id of (relabel_overlap, then
  // relabel_distance), or lost_.end().
  std::vector<LostTrack>::iterator find_lost(const Eigen::Vector4f& box);
  // The same by colour (appearance_distance, appearance_sigma), or lost_.end().
  std::vector<LostTrack>::iterator find_lost_by_colour(const Eigen::Vector4f& box,
                                                       const ColourHistogram& seen);
  // The cost c of the file comment for a track at `box` whose colours have coefficient rho with
  // an id's model, the id last at `from` moving at `velocity` since step `since`.
  double identity_cost(const Eigen::Vector4f& box, double rho, const Eigen::Vector4f& from,
                       const Eigen::Vector2f& velocity, int since) const;
  // resolve() for one episode: the alone tracks `members` (indices into tracks) and the lost
  // ids they overlapped.
  void assign_episode(const std::vector<View>& tracks, const std::vector<std::size_t>& members);

  TrackManagementParams params_;
  std::vector<LostTrack> lost_;
  int step_ = 0;
};

}  // namespace vtrack::filters
