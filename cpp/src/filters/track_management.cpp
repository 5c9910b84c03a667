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
                                .add("relabel_overlap", &P::relabel_overlap)
                                .add("relabel_distance", &P::relabel_distance);
  return table;
}

void validate(const TrackManagementParams& p) {
  require(p.confirm_frames >= 1, "confirm_frames", p.confirm_frames, ">= 1");
  require(p.lost_memory >= 0, "lost_memory", p.lost_memory, ">= 0");
  require(p.relabel_overlap > 0.0 && p.relabel_overlap <= 1.0, "relabel_overlap",
          p.relabel_overlap, "in (0, 1]");
  require(std::isfinite(p.relabel_distance) && p.relabel_distance >= 0.0, "relabel_distance",
          p.relabel_distance, ">= 0 and finite");
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
    const auto found = find_lost(box);
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

std::vector<TrackManager::LostTrack>::iterator TrackManager::find_lost(
    const Eigen::Vector4f& box) {
  // The lost track whose box, moved on at its velocity, overlaps this estimate most; failing
  // that, the nearest within relabel_distance.
  double best_iou = params_.relabel_overlap;
  double best_d2 = params_.relabel_distance * params_.relabel_distance;
  auto by_iou = lost_.end(), by_distance = lost_.end();
  const Eigen::Vector2f centre = box.head<2>() + 0.5f * box.tail<2>();
  for (auto it = lost_.begin(); it != lost_.end(); ++it) {
    Eigen::Vector4f predicted = it->box;
    predicted.head<2>() += float(step_ - it->step) * it->velocity;
    const double iou = box_iou(predicted, box);
    if (iou >= best_iou) {
      best_iou = iou;
      by_iou = it;
    }
    if (params_.relabel_distance > 0.0 && predicted[2] > 0.0f && predicted[3] > 0.0f) {
      const Eigen::Vector2f d = (centre - predicted.head<2>() - 0.5f * predicted.tail<2>())
                                    .cwiseQuotient(predicted.tail<2>());
      if (d.squaredNorm() <= best_d2) {
        best_d2 = d.squaredNorm();
        by_distance = it;
      }
    }
  }
  return by_iou != lost_.end() ? by_iou : by_distance;
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
