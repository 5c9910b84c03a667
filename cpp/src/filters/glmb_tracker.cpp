#include "vtrack/filters/glmb_tracker.hpp"

#include <algorithm>
#include <limits>

#include "vtrack/core/errors.hpp"

namespace vtrack::filters {
namespace {

std::variant<GaussianGlmbFilter, ParticleGlmbFilter> make_filter(
    models::LinearGaussianMotion motion, models::LinearGaussianObservation observation,
    std::vector<GaussianBirth> births, const GlmbTrackerParams& p,
    std::optional<models::DepthLikelihood> depth_model) {
  if (p.densities == TrackDensities::gaussian) {
    if (depth_model) {
      throw InvalidArgument(
          "a depth model needs densities='particles' (the switching observation model)");
    }
    return GaussianGlmbFilter(std::move(motion), std::move(observation), std::move(births), p.glmb);
  }
  return ParticleGlmbFilter(std::move(motion), std::move(observation), std::move(births), p.glmb,
                            p.particle, std::move(depth_model));
}

}  // namespace

const core::ParameterTable<GlmbTrackerParams>& GlmbTrackerParams::table() {
  using P = GlmbTrackerParams;
  static const auto table =
      core::ParameterTable<P>()
          .include(&P::glmb)
          .add_choice("densities", &P::densities,
                      {{"gaussian", TrackDensities::gaussian},
                       {"particles", TrackDensities::particles}})
          .include(&P::particle)
          .include(&P::management);
  return table;
}

void validate(const GlmbTrackerParams& p) {
  validate(p.glmb);
  validate(p.particle);
  validate(p.management);
}

GlmbTracker::GlmbTracker(models::LinearGaussianMotion motion,
                         models::LinearGaussianObservation observation,
                         std::vector<GaussianBirth> births, const GlmbTrackerParams& params,
                         std::optional<models::DepthLikelihood> depth_model,
                         std::optional<BoxLayout> box_layout)
    : params_((validate(params), params)),
      filter_(make_filter(std::move(motion), std::move(observation), std::move(births), params,
                          std::move(depth_model))),
      box_layout_(box_layout),
      management_(params.management) {}

const Tracks& GlmbTracker::step(const Eigen::Ref<const Eigen::MatrixXd>& detections,
                                const cv::Mat* depth, const ScanInput& input) {
  if (depth && !has_depth_model()) {
    throw InvalidArgument("a depth image needs a tracker built with a depth model");
  }
  std::visit(
      [&](auto& f) {
        if constexpr (std::is_same_v<std::decay_t<decltype(f)>, ParticleGlmbFilter>) {
          f.step(detections, depth, input);
        } else {
          f.step(detections, input);
        }
      },
      filter_);
  report(estimates());
  return tracks_;
}

void GlmbTracker::report(const std::vector<GlmbEstimate>& estimates) {
  const int scan = time();
  management_.begin_step(scan);
  tracks_.clear();
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (const auto& e : estimates) {
    LabelRecord& label = labels_[{e.label.birth_time, e.label.birth_index}];
    label.last_seen = scan;
    Eigen::Vector4f box = Eigen::Vector4f::Constant(kNaN);
    if (box_layout_) {
      const BoxLayout& b = *box_layout_;
      const double w = e.mean(b.w), h = e.mean(b.h);
      box << float(e.mean(b.cx) - w / 2), float(e.mean(b.cy) - h / 2), float(w), float(h);
      label.record.velocity << float(e.mean(b.vx)), float(e.mean(b.vy));
    }
    if (const auto lost_id = management_.observe(label.id, label.record, box)) label.id = *lost_id;
    if (!management_.report(label.record, box)) continue;
    if (label.id == 0) label.id = next_id_++;
    TrackEstimate t;
    t.id = label.id;
    if (box_layout_) {
      const BoxLayout& b = *box_layout_;
      t.w = e.mean(b.w);
      t.h = e.mean(b.h);
      t.x = e.mean(b.cx) - t.w / 2;
      t.y = e.mean(b.cy) - t.h / 2;
    }
    t.score = e.existence;
    t.state = e.mean;
    t.covariance = e.cov;
    t.birth_time = e.label.birth_time;
    t.birth_index = e.label.birth_index;
    tracks_.push_back(std::move(t));
  }
  // Labels no hypothesis holds any more have ended: remembered when confirmed, then forgotten.
  // (A label only missing from this scan's estimate may come back, under its own id.)
  for (auto it = labels_.begin(); it != labels_.end();) {
    const TrackLabel label{it->first.first, it->first.second};
    if (it->second.last_seen == scan || visit([&](const auto& f) { return f.holds(label); })) {
      ++it;
      continue;
    }
    management_.end(it->second.id, it->second.record);
    it = labels_.erase(it);
  }
  std::sort(tracks_.begin(), tracks_.end(),
            [](const TrackEstimate& a, const TrackEstimate& b) { return a.id < b.id; });
}

const std::vector<GlmbEstimate>& GlmbTracker::estimates() const {
  return visit([](const auto& f) -> const std::vector<GlmbEstimate>& { return f.estimates(); });
}

const ScanSummary& GlmbTracker::summary() const {
  return visit([](const auto& f) -> const ScanSummary& { return f.summary(); });
}
void GlmbTracker::set_detection_probability(double p_d) {
  std::visit([p_d](auto& f) { f.set_detection_probability(p_d); }, filter_);
}

Eigen::VectorXd GlmbTracker::cardinality_distribution() const {
  return visit([](const auto& f) { return f.cardinality_distribution(); });
}
int GlmbTracker::map_cardinality() const {
  return visit([](const auto& f) { return f.map_cardinality(); });
}
std::size_t GlmbTracker::hypothesis_count() const {
  return visit([](const auto& f) { return f.hypothesis_count(); });
}
std::size_t GlmbTracker::track_count() const {
  return visit([](const auto& f) { return f.track_count(); });
}
int GlmbTracker::time() const {
  return visit([](const auto& f) { return f.time(); });
}
Eigen::Index GlmbTracker::z_dim() const {
  return visit([](const auto& f) { return f.z_dim(); });
}
bool GlmbTracker::has_depth_model() const {
  const auto* f = std::get_if<ParticleGlmbFilter>(&filter_);
  return f && f->has_depth_model();
}

}  // namespace vtrack::filters
