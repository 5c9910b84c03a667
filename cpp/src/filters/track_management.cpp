#include "vtrack/filters/track_management.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/filters/assign.hpp"

namespace vtrack::filters {

const core::ParameterTable<TrackManagementParams>& TrackManagementParams::table() {
  using P = TrackManagementParams;
  static const auto table = core::ParameterTable<P>()
                                .add("confirm_frames", &P::confirm_frames)
                                .add("lost_memory", &P::lost_memory)
                                .add("relabel_overlap", &P::relabel_overlap)
                                .add("relabel_distance", &P::relabel_distance)
                                .add("appearance_rate", &P::appearance_rate)
                                .add("appearance_sigma", &P::appearance_sigma)
                                .add("appearance_distance", &P::appearance_distance);
  return table;
}

void validate(const TrackManagementParams& p) {
  require(p.confirm_frames >= 1, "confirm_frames", p.confirm_frames, ">= 1");
  require(p.lost_memory >= 0, "lost_memory", p.lost_memory, ">= 0");
  require(p.relabel_overlap > 0.0 && p.relabel_overlap <= 1.0, "relabel_overlap",
          p.relabel_overlap, "in (0, 1]");
  require(std::isfinite(p.relabel_distance) && p.relabel_distance >= 0.0, "relabel_distance",
          p.relabel_distance, ">= 0 and finite");
  require(p.appearance_rate >= 0.0 && p.appearance_rate <= 1.0, "appearance_rate",
          p.appearance_rate, "in [0, 1]");
  require(std::isfinite(p.appearance_sigma) && p.appearance_sigma > 0.0, "appearance_sigma",
          p.appearance_sigma, "> 0 and finite");
  require(std::isfinite(p.appearance_distance) && p.appearance_distance >= 0.0,
          "appearance_distance", p.appearance_distance, ">= 0 and finite");
}

double colour_coefficient(const ColourHistogram& p, const ColourHistogram& q) {
  if (p.size() != q.size()) {
    throw InvalidArgument("colour histograms must have the same bins, got " +
                          std::to_string(p.size()) + " and " + std::to_string(q.size()));
  }
  double s = 0.0;
  for (std::size_t u = 0; u < p.size(); ++u) s += std::sqrt(double(p[u]) * double(q[u]));
  return std::min(1.0, s);
}

namespace {

// A box (x, y, w, h) moved on by `steps` steps at `velocity`.
Eigen::Vector4f moved_on(Eigen::Vector4f box, const Eigen::Vector2f& velocity, int steps) {
  box.head<2>() += float(steps) * velocity;
  return box;
}

// Squared distance of a box's centre to another box's, in the other box's width and height
// (infinite when the other box is empty).
double centre_d2(const Eigen::Vector4f& box, const Eigen::Vector4f& to) {
  if (!(to[2] > 0.0f && to[3] > 0.0f)) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2f d = (box.head<2>() + 0.5f * box.tail<2>() - to.head<2>() -
                             0.5f * to.tail<2>()).cwiseQuotient(to.tail<2>());
  return double(d.squaredNorm());
}

// A colour model, and a box of its own from when it was learnt (the cost's motion term).
bool has_model(const TrackRecord& r) {
  return !r.appearance.empty() && r.alone_step >= 0 && r.alone_box[2] > 0.0f && r.alone_box[3] > 0.0f;
}

bool contains(const std::vector<std::uint64_t>& ids, std::uint64_t id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

}  // namespace

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
                             [&](const LostTrack& l) { return step - l.record.last_reported > memory; }),
              lost_.end());
}

std::optional<std::uint64_t> TrackManager::observe(std::uint64_t id, TrackRecord& record,
                                                   const Eigen::Vector4f& box,
                                                   const ColourHistogram& seen) {
  ++record.hits;
  if (id != 0 && record.confirmed) {
    lost_.erase(std::remove_if(lost_.begin(), lost_.end(),
                               [id](const LostTrack& l) { return l.id == id; }),
                lost_.end());
  }
  std::optional<std::uint64_t> taken;
  if (!record.confirmed && !lost_.empty()) {
    auto found = find_lost_by_colour(box, seen);
    if (found == lost_.end()) found = find_lost(box);
    if (found != lost_.end()) {
      taken = found->id;
      record.velocity = found->record.velocity;
      record.appearance = std::move(found->record.appearance);
      record.alone_box = found->record.alone_box;
      record.alone_velocity = found->record.alone_velocity;
      record.alone_step = found->record.alone_step;
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
  for (auto it = lost_.begin(); it != lost_.end(); ++it) {
    const TrackRecord& r = it->record;
    const Eigen::Vector4f predicted = moved_on(r.last_box, r.velocity, step_ - r.last_reported);
    const double iou = box_iou(predicted, box);
    if (iou >= best_iou) {
      best_iou = iou;
      by_iou = it;
    }
    if (params_.relabel_distance > 0.0) {
      const double d2 = centre_d2(box, predicted);
      if (d2 <= best_d2) {
        best_d2 = d2;
        by_distance = it;
      }
    }
  }
  return by_iou != lost_.end() ? by_iou : by_distance;
}

double TrackManager::identity_cost(const Eigen::Vector4f& box, double rho,
                                   const Eigen::Vector4f& from, const Eigen::Vector2f& velocity,
                                   int since) const {
  const double sigma = params_.appearance_sigma;
  return (1.0 - rho) / (2.0 * sigma * sigma) +
         0.5 * centre_d2(box, moved_on(from, velocity, step_ - since));
}

std::vector<TrackManager::LostTrack>::iterator TrackManager::find_lost_by_colour(
    const Eigen::Vector4f& box, const ColourHistogram& seen) {
  auto best = lost_.end();
  if (params_.appearance_rate <= 0.0 || seen.empty()) return best;
  const double gate_d2 = params_.appearance_distance * params_.appearance_distance;
  // Within 2 sigma of eq. 11's Gaussian on the Bhattacharyya distance: 1 - rho <= 4 sigma^2.
  const double gate_rho = 1.0 - 4.0 * params_.appearance_sigma * params_.appearance_sigma;
  double best_cost = std::numeric_limits<double>::infinity();
  for (auto it = lost_.begin(); it != lost_.end(); ++it) {
    const TrackRecord& r = it->record;
    if (r.appearance.empty() || !(r.last_box[2] > 0.0f && r.last_box[3] > 0.0f)) continue;
    const Eigen::Vector4f predicted = moved_on(r.last_box, r.velocity, step_ - r.last_reported);
    if (centre_d2(box, predicted) > gate_d2) continue;
    const double rho = colour_coefficient(seen, r.appearance);
    if (rho < gate_rho) continue;
    const double cost = identity_cost(box, rho, r.last_box, r.velocity, r.last_reported);
    if (cost < best_cost) {
      best_cost = cost;
      best = it;
    }
  }
  return best;
}

void TrackManager::resolve(const std::vector<View>& tracks) {
  if (params_.appearance_rate <= 0.0) return;
  const std::size_t n = tracks.size();
  // Which boxes overlap; confirmed tracks remember the confirmed ones they overlapped.
  std::vector<bool> alone(n, true);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (box_iou(tracks[i].box, tracks[j].box) <= 0.0) continue;  // they do not overlap
      alone[i] = alone[j] = false;
      TrackRecord& a = *tracks[i].record;
      TrackRecord& b = *tracks[j].record;
      if (!a.confirmed || !b.confirmed) continue;
      if (!contains(a.overlapped, *tracks[j].id)) a.overlapped.push_back(*tracks[j].id);
      if (!contains(b.overlapped, *tracks[i].id)) b.overlapped.push_back(*tracks[i].id);
    }
  }
  // Episodes that end: confirmed tracks alone again after overlapping, grouped with the alone
  // tracks whose ids they overlapped.
  std::vector<bool> done(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (done[i] || !alone[i] || !tracks[i].record->confirmed || tracks[i].record->overlapped.empty()) {
      continue;
    }
    std::vector<std::size_t> members{i};
    done[i] = true;
    for (std::size_t q = 0; q < members.size(); ++q) {
      const TrackRecord& r = *tracks[members[q]].record;
      for (std::size_t j = 0; j < n; ++j) {
        if (done[j] || !alone[j] || !tracks[j].record->confirmed) continue;
        if (contains(r.overlapped, *tracks[j].id) || contains(tracks[j].record->overlapped, *tracks[members[q]].id)) {
          members.push_back(j);
          done[j] = true;
        }
      }
    }
    assign_episode(tracks, members);
  }
  // The models of the confirmed tracks that are alone learn their histograms.
  const float a = float(params_.appearance_rate);
  for (std::size_t i = 0; i < n; ++i) {
    TrackRecord& r = *tracks[i].record;
    const ColourHistogram* seen = tracks[i].seen;
    if (!alone[i] || !r.confirmed || seen == nullptr || seen->empty()) continue;
    if (r.appearance.size() != seen->size()) {
      r.appearance = *seen;
    } else {
      for (std::size_t u = 0; u < seen->size(); ++u) {
        r.appearance[u] = (1.0f - a) * r.appearance[u] + a * (*seen)[u];
      }
    }
    r.alone_box = tracks[i].box;
    r.alone_velocity = r.velocity;
    r.alone_step = step_;
  }
}

void TrackManager::assign_episode(const std::vector<View>& tracks,
                                  const std::vector<std::size_t>& members) {
  // The candidate ids: the members' own, and the lost ones they overlapped, each with the record
  // it carries (where it was when last alone, its colour model).
  struct Candidate {
    std::uint64_t id;
    TrackRecord record;
    bool lost;
  };
  std::vector<Candidate> ids;
  std::vector<std::size_t> rows;  // members with a histogram and a model of their own
  for (const std::size_t k : members) {
    TrackRecord& r = *tracks[k].record;
    for (const std::uint64_t other : r.overlapped) {
      const auto it = std::find_if(lost_.begin(), lost_.end(), [&](const LostTrack& l) { return l.id == other; });
      const bool listed = std::any_of(ids.begin(), ids.end(), [&](const Candidate& c) { return c.id == other; });
      if (it != lost_.end() && !listed && has_model(it->record)) ids.push_back({other, it->record, true});
    }
    r.overlapped.clear();
    const bool seen = tracks[k].seen != nullptr && !tracks[k].seen->empty();
    if (seen && has_model(r)) {
      rows.push_back(k);
      ids.push_back({*tracks[k].id, r, false});
    }
  }
  if (rows.empty() || ids.size() < 2) return;
  Eigen::MatrixXd cost(Eigen::Index(rows.size()), Eigen::Index(ids.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const View& v = tracks[rows[i]];
    for (std::size_t j = 0; j < ids.size(); ++j) {
      const TrackRecord& r = ids[j].record;
      cost(Eigen::Index(i), Eigen::Index(j)) =
          identity_cost(v.box, colour_coefficient(*v.seen, r.appearance), r.alone_box,
                        r.alone_velocity, r.alone_step);
    }
  }
  const auto best = assign::linear_assignment(cost);
  std::vector<bool> used(ids.size(), false);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Candidate& c = ids[std::size_t(best.col_of_row[i])];
    used[std::size_t(best.col_of_row[i])] = true;
    const View& v = tracks[rows[i]];
    if (c.id == *v.id) continue;
    // The id and its record (its model and history) move to this track; the hit count and
    // confirmation are the track's own.
    TrackRecord taken = c.record;
    taken.hits = v.record->hits;
    taken.last_box = v.record->last_box;
    taken.last_reported = v.record->last_reported;
    taken.velocity = v.record->velocity;
    *v.id = c.id;
    *v.record = std::move(taken);
    if (c.lost) {
      lost_.erase(std::remove_if(lost_.begin(), lost_.end(), [&](const LostTrack& l) { return l.id == c.id; }),
                  lost_.end());
    }
  }
  // A member's own id that went to nobody is lost (remembered as it was).
  for (std::size_t j = 0; j < ids.size(); ++j) {
    if (!used[j] && !ids[j].lost) end(ids[j].id, ids[j].record);
  }
}

bool TrackManager::report(TrackRecord& record, const Eigen::Vector4f& box) {
  if (!record.confirmed) return false;
  record.last_box = box;
  record.last_reported = step_;
  return true;
}

void TrackManager::end(std::uint64_t id, const TrackRecord& record) {
  if (params_.lost_memory == 0 || !record.confirmed || record.last_reported < 0) return;
  lost_.push_back({id, record});
  lost_.back().record.overlapped.clear();
}

}  // namespace vtrack::filters
