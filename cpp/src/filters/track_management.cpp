#include "vtrack/filters/track_management.hpp"

#include <algorithm>
#include <cmath>

#include "vtrack/core/errors.hpp"

namespace vtrack::filters {

const core::ParameterTable<TrackManagementParams>& TrackManagementParams::table() {
  using P = TrackManagementParams;
  static const auto table = core::ParameterTable<P>()
                                .add("confirm_frames", &P::confirm_frames)
                                .add("lost_memory", &P::lost_memory)
                                .add("relabel_overlap", &P::relabel_overlap);
  return table;
}

void validate(const TrackManagementParams& p) {
  require(p.confirm_frames >= 1, "confirm_frames", p.confirm_frames, ">= 1");
  require(p.lost_memory >= 0, "lost_memory", p.lost_memory, ">= 0");
  require(p.relabel_overlap > 0.0 && p.relabel_overlap <= 1.0, "relabel_overlap",
          p.relabel_overlap, "in (0, 1]");
}

double box_iou(const Eigen::Vector4f& a, const Eigen::Vector4f& b) {
  const double iw = std::min(a[0] + a[2], b[0] + b[2]) - std::max(a[0], b[0]);
  const double ih = std::min(a[1] + a[3], b[1] + b[3]) - std::max(a[1], b[1]);
  if (iw <= 0.0 || ih <= 0.0) return 0.0;
  const double inter = iw * ih;
  const double uni = static_cast<double>(a[2]) * a[3] + static_cast<double>(b[2]) * b[3] - inter;
  return uni > 0.0 ? inter / uni : 0.0;
}

TrackManager::TrackManager(const TrackManagementParams& params) : params_(params) {
  validate(params_);
}

void TrackManager::begin_step(int step) {
  step_ = step;
  const int memory = params_.lost_memory;
  lost_.erase(std::remove_if(lost_.begin(), lost_.end(),
                             [&](const LostTrack& l) { return step - l.step > memory; }),
              lost_.end());
}

std::optional<std::uint64_t> TrackManager::observe(std::uint64_t id, TrackRecord& record,
                                                   const Eigen::Vector4f& box) {
  ++record.hits;
  if (id != 0 && record.confirmed) {
    lost_.erase(std::remove_if(lost_.begin(), lost_.end(),
                               [id](const LostTrack& l) { return l.id == id; }),
                lost_.end());
  }
  std::optional<std::uint64_t> taken;
  if (!record.confirmed && !lost_.empty()) {
    // The lost track whose box, moved on at its velocity, overlaps this estimate most.
    double best = params_.relabel_overlap;
    auto found = lost_.end();
    for (auto it = lost_.begin(); it != lost_.end(); ++it) {
      Eigen::Vector4f predicted = it->box;
      predicted.head<2>() += float(step_ - it->step) * it->velocity;
      const double iou = box_iou(predicted, box);
      if (iou >= best) {
        best = iou;
        found = it;
      }
    }
    if (found != lost_.end()) {
      taken = found->id;
      record.velocity = found->velocity;
      record.confirmed = true;
      lost_.erase(found);
    }
  }
  if (record.hits >= params_.confirm_frames) record.confirmed = true;
  return taken;
}

bool TrackManager::report(TrackRecord& record, const Eigen::Vector4f& box) {
  if (!record.confirmed) return false;
  record.last_box = box;
  record.last_reported = step_;
  return true;
}

void TrackManager::end(std::uint64_t id, const TrackRecord& record) {
  if (params_.lost_memory == 0 || !record.confirmed || record.last_reported < 0) return;
  lost_.push_back({id, record.last_box, record.velocity, record.last_reported});
}

}  // namespace vtrack::filters
