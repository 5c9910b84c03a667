#include "vtrack/filters/multi_bernoulli.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <opencv2/imgproc.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/core/weights.hpp"

namespace vtrack::filters {
namespace {

void require_probability(const char* name, double v) {
  require(v >= 0.0 && v <= 1.0, name, v, "in [0, 1]");
}

const MultiBernoulliParams& validated(const MultiBernoulliParams& p) {
  validate(p);
  return p;
}

// Components and tracks in label order (older first), which merging and explaining-away rely on.
template <typename T>
void sort_by_label(std::vector<T>& v) {
  std::sort(v.begin(), v.end(), [](const T& a, const T& b) { return a.label < b.label; });
}

}  // namespace

const core::ParameterTable<MultiBernoulliParams>& MultiBernoulliParams::table() {
  using P = MultiBernoulliParams;
  static const auto table =
      core::ParameterTable<P>()
          .include(&P::likelihood)
          .add("survival_probability", &P::survival_probability)
          .include(&P::size)
          .add("width_mean", &P::width_mean)
          .add("size_by_row", &P::size_by_row)
          .add("sigma_xy", &P::sigma_xy)
          .add("sigma_wh", &P::sigma_wh)
          .add("quarter_birth", &P::quarter_birth)
          .add("birth_probability", &P::birth_probability)
          .add("birth_particles", &P::birth_particles)
          .add("cover_existence", &P::cover_existence)
          .add("established_age", &P::established_age)
          .add("adaptive_birth", &P::adaptive_birth)
          .add("adaptive_birth_probability", &P::adaptive_birth_probability)
          .add("adaptive_birth_log_likelihood", &P::adaptive_birth_log_likelihood)
          .add("adaptive_birth_stride", &P::adaptive_birth_stride)
          .add("adaptive_birth_max", &P::adaptive_birth_max)
          .add("min_particles", &P::min_particles)
          .add("max_particles", &P::max_particles)
          .add_choice("resampling", &P::resampling, core::resampling_scheme_names())
          .add("prune_threshold", &P::prune_threshold)
          .add("merge_overlap", &P::merge_overlap)
          .add("estimate_threshold", &P::estimate_threshold)
          .add("max_existence", &P::max_existence)
          .include(&P::management)
          .add("velocity_smoothing", &P::velocity_smoothing)
          .include(&P::box)
          .add("seed", &P::seed);
  return table;
}

void validate(const MultiBernoulliParams& p) {
  models::validate(p.likelihood);
  require(p.survival_probability > 0.0 && p.survival_probability <= 1.0, "survival_probability",
          p.survival_probability, "in (0, 1]");
  validate(p.size);
  // The "row" reward is relative to the person at each row, so the box sizes must be too: with
  // one size range for the whole image, a far box may grow over several far people's areas of
  // faint foreground (PETS09-S2L1, seed 0: MOTA -0.20 on all frames).
  if (p.likelihood.delta_b_reference == models::TbdLikelihoodParams::DeltaBReference::row &&
      !p.size_by_row) {
    throw InvalidArgument(
        "delta_b_reference 'row' (the default) needs size_by_row true, got size_by_row false "
        "(set delta_b_reference 'image' with it)");
  }
  require(std::isfinite(p.width_mean) && p.width_mean >= 0.0, "width_mean", p.width_mean,
          ">= 0 (0: size_aspect x height)");
  require(p.sigma_xy > 0.0 && p.sigma_xy <= 1.0, "sigma_xy", p.sigma_xy, "in (0, 1]");
  require(p.sigma_wh > 0.0 && p.sigma_wh <= 1.0, "sigma_wh", p.sigma_wh, "in (0, 1]");
  require(p.birth_probability > 0.0 && p.birth_probability < 1.0, "birth_probability",
          p.birth_probability, "in (0, 1)");
  require(p.birth_particles >= 1 && p.birth_particles <= core::kMaxParticles, "birth_particles",
          p.birth_particles, "in [1, 1000000]");
  require_probability("cover_existence", p.cover_existence);
  require(p.adaptive_birth_probability > 0.0 && p.adaptive_birth_probability < 1.0,
          "adaptive_birth_probability", p.adaptive_birth_probability, "in (0, 1)");
  require(std::isfinite(p.adaptive_birth_log_likelihood), "adaptive_birth_log_likelihood",
          p.adaptive_birth_log_likelihood, "finite");
  require(p.established_age >= 0, "established_age", p.established_age, ">= 0");
  require(p.adaptive_birth_stride > 0.0 && p.adaptive_birth_stride <= 1.0, "adaptive_birth_stride",
          p.adaptive_birth_stride, "in (0, 1]");
  require(p.adaptive_birth_max >= 0, "adaptive_birth_max", p.adaptive_birth_max, ">= 0");
  require(p.min_particles >= 1, "min_particles", p.min_particles, ">= 1");
  require(p.max_particles <= core::kMaxParticles, "max_particles", p.max_particles,
          "<= 1000000");
  if (p.min_particles > p.max_particles) {
    throw InvalidArgument("min_particles (L_min = " + std::to_string(p.min_particles) +
                          ") must not exceed max_particles (L_max = " +
                          std::to_string(p.max_particles) + ")");
  }
  require(p.prune_threshold >= 0.0 && p.prune_threshold < 1.0, "prune_threshold",
          p.prune_threshold, "in [0, 1)");
  require(p.merge_overlap > 0.0 && p.merge_overlap <= 1.0, "merge_overlap", p.merge_overlap, "in (0, 1]");
  require(p.estimate_threshold >= 0.0 && p.estimate_threshold < 1.0, "estimate_threshold",
          p.estimate_threshold, "in [0, 1)");
  require(p.max_existence > 0.0 && p.max_existence <= 1.0, "max_existence", p.max_existence,
          "in (0, 1]");
  validate(p.management);
  require_probability("velocity_smoothing", p.velocity_smoothing);
  validate(p.box);
}

Eigen::Vector4f BernoulliComponent::mean() const {
  return particles.mean().cast<float>();
}

double box_overlap(const Eigen::Vector4f& a, const Eigen::Vector4f& b) {
  const double iw = std::min(a[0] + a[2], b[0] + b[2]) - std::max(a[0], b[0]);
  const double ih = std::min(a[1] + a[3], b[1] + b[3]) - std::max(a[1], b[1]);
  if (iw <= 0.0 || ih <= 0.0) return 0.0;
  const double smaller = std::min(static_cast<double>(a[2]) * a[3], static_cast<double>(b[2]) * b[3]);
  return smaller > 0.0 ? iw * ih / smaller : 0.0;
}

double updated_existence(double r, double log_rho) {
  // Eq. (23): r rho / (1 - r + r rho) = 1 / (1 + exp(-(logit r + log rho))).
  if (r <= 0.0) return 0.0;
  if (r >= 1.0) return 1.0;
  const double log_odds = std::log(r) - std::log1p(-r) + log_rho;
  return 1.0 / (1.0 + std::exp(-log_odds));
}

PersonSizePrior person_size_prior(const MultiBernoulliParams& p, double width, double height) {
  PersonSizePrior s;
  s.height = height;
  s.width = width > 0.0 ? width : p.size.size_aspect * height;
  s.width_std = p.size.size_std * s.width;
  s.height_std = p.size.size_std * s.height;
  // Sizes of at least one pixel, whatever the scale.
  s.width_min = std::max(1.0, p.size.size_min * s.width);
  s.height_min = std::max(1.0, p.size.size_min * s.height);
  s.width_max = std::max(s.width_min, p.size.size_max * s.width);
  s.height_max = std::max(s.height_min, p.size.size_max * s.height);
  s.sigma_xy = p.sigma_xy * s.height;
  s.sigma_wh = p.sigma_wh * s.height;
  s.birth_stride = std::max(1, static_cast<int>(std::lround(p.adaptive_birth_stride * s.height)));
  return s;
}

MultiBernoulliFilter::MultiBernoulliFilter(int width, int height,
                                           const MultiBernoulliParams& params)
    : params_(validated(params)), width_(width), height_(height), rng_(params.seed),
      likelihood_(params.likelihood),
      person_height_(params.size, height),
      management_(params.management) {
  if (width < 1) throw InvalidArgument("width must be >= 1, got " + std::to_string(width));
  if (height < 1) throw InvalidArgument("height must be >= 1, got " + std::to_string(height));
  person_height_.set_fit_line(
      params_.size_by_row ||
      params_.likelihood.delta_b_reference == models::TbdLikelihoodParams::DeltaBReference::row);
  // A few people in lanes fit a spurious line (models/person_size.hpp).
  person_height_.set_require_well_supported_line(true);
  set_size_prior(person_size_prior(params_, params_.width_mean, person_height_.height()));
}

void MultiBernoulliFilter::set_size_prior(const PersonSizePrior& size) {
  size_ = size;
  likelihood_.set_person_size(size_.width, size_.height);
  // Eq. (22)'s random walk, in pixels of the current prior.
  motion_ = models::RandomWalk(models::RandomWalkParams{
      {size_.sigma_xy, size_.sigma_xy, size_.sigma_wh, size_.sigma_wh}, 4});
}

void MultiBernoulliFilter::update_size_prior() {
  // The closed y the likelihood sees: the components are those the filter's boxes explain. The
  // evidence needed is one person of the current prior.
  if (!person_height_.observe(likelihood_.processed_image(), 0.5f, size_.width * size_.height)) {
    return;
  }
  PersonSizePrior size = person_size_prior(params_, params_.width_mean, person_height_.height());
  size.learnt = true;
  set_size_prior(size);
  line_scale_.clear();
  if (person_height_.by_row()) {  // fitted for size_by_row or the "row" reference
    line_scale_.resize(static_cast<std::size_t>(height_));
    for (int r = 0; r < height_; ++r) {
      line_scale_[static_cast<std::size_t>(r)] = person_height_.height_at_foot(r) / size_.height;
    }
  }
  if (params_.likelihood.delta_b_reference ==
      models::TbdLikelihoodParams::DeltaBReference::row) {
    // a(row) of the "row" reward: the area of the person centred on the row (empty: the constant
    // prior area), no smaller than that of the smallest people the line was fitted on: above
    // their rows (PETS09's top fifth: walls, windows, tree tops) the line's extrapolation would
    // make a speck's pixels worth up to 8 times a mean person's, and the specks became tracks.
    std::vector<double> areas;
    if (!line_scale_.empty()) {
      areas.resize(static_cast<std::size_t>(height_));
      const double smallest = person_height_.smallest_seen() / size_.height;
      for (int r = 0; r < height_; ++r) {
        const double s = std::max(line_centre_scale(r), smallest);
        areas[static_cast<std::size_t>(r)] = size_.width * size_.height * s * s;
      }
    }
    likelihood_.set_row_areas(std::move(areas));
  }
}

double MultiBernoulliFilter::line_scale(double foot_row) const {
  if (line_scale_.empty() || !std::isfinite(foot_row)) return 1.0;
  const auto r = static_cast<std::size_t>(std::clamp(foot_row, 0.0, double(height_ - 1)));
  return line_scale_[r];
}

double MultiBernoulliFilter::line_centre_scale(double cy) const {
  if (line_scale_.empty()) return 1.0;
  return line_scale(cy + 0.5 * size_.height * line_scale(cy + 0.5 * size_.height));
}

double MultiBernoulliFilter::row_scale(double foot_row) const {
  return params_.size_by_row ? line_scale(foot_row) : 1.0;
}

double MultiBernoulliFilter::centre_row_scale(double cy) const {
  return params_.size_by_row ? line_centre_scale(cy) : 1.0;
}

const Tracks& MultiBernoulliFilter::step(const cv::Mat& y, const cv::Mat& frame) {
  if (y.cols != width_ || y.rows != height_) {
    throw InvalidArgument("y must be " + std::to_string(height_) + " x " + std::to_string(width_) +
                          " (height x width), got " + std::to_string(y.rows) + " x " +
                          std::to_string(y.cols));
  }
  if (!frame.empty()) check_colour_frame(frame, y);
  likelihood_.set_image(y);  // validates y before anything changes
  predict();
  // The existing targets, as predicted: what the births avoid and each component's update sees
  // as explained by the others.
  covered_labels_.clear();
  covered_births_.clear();
  covered_.clear();
  for (const auto& c : components_) {
    if (c.existence < params_.cover_existence) continue;
    const Eigen::Vector4f m = c.mean();
    covered_labels_.push_back(c.label);
    covered_births_.push_back(c.birth_frame);
    covered_.push_back(likelihood_.integral().clip(models::box_to_rect(m[0], m[1], m[2], m[3])));
  }
  if (params_.adaptive_birth) add_adaptive_births();
  if (params_.quarter_birth) add_quarter_births();
  update();
  prune_and_merge();
  resample();
  manage_tracks(y, frame);
  // The size prior learnt from this frame's foreground applies from the next frame on.
  update_size_prior();
  ++frame_;
  return tracks_;
}

void MultiBernoulliFilter::manage_tracks(const cv::Mat& y, const cv::Mat& frame) {
  // Beyond the paper (see MultiBernoulliParams): velocity estimates, confirmation, relabelling
  // from the lost memory (and by colour), and the reported box transform. Section 4's estimate is
  // the weighted mean of a component with r > estimate_threshold.
  management_.begin_step(frame_);
  const float alpha = float(params_.velocity_smoothing);
  std::vector<std::size_t> estimated;
  std::vector<Eigen::Vector4f> boxes;
  for (std::size_t k = 0; k < components_.size(); ++k) {
    auto& c = components_[k];
    const Eigen::Vector4f m = c.mean();
    if (c.birth_frame < frame_) {  // not born this step: it has a previous estimate
      const Eigen::Vector2f shift = (m.head<2>() + 0.5f * m.tail<2>()) -
                                    (c.last_mean.head<2>() + 0.5f * c.last_mean.tail<2>());
      c.record.velocity = (1.0f - alpha) * c.record.velocity + alpha * shift;
    }
    c.last_mean = m;
    if (c.existence <= params_.estimate_threshold) continue;
    estimated.push_back(k);
    boxes.push_back(m);
  }
  const bool colour = !frame.empty() && params_.management.appearance_rate > 0.0;
  if (colour) {
    colour_.measure(frame, y, 0.5f, boxes, seen_);
  } else {
    seen_.assign(boxes.size(), {});
  }
  std::vector<TrackManager::View> views;
  for (std::size_t q = 0; q < estimated.size(); ++q) {
    auto& c = components_[estimated[q]];
    if (const auto lost_label = management_.observe(c.label, c.record, boxes[q], seen_[q])) {
      c.label = *lost_label;
    }
    views.push_back({&c.label, &c.record, boxes[q], &seen_[q]});
  }
  if (colour) management_.resolve(views);
  tracks_.clear();
  for (std::size_t q = 0; q < estimated.size(); ++q) {
    auto& c = components_[estimated[q]];
    const Eigen::Vector4f& m = boxes[q];
    if (!management_.report(c.record, m)) continue;
    TrackEstimate t;
    t.id = c.label;
    const double scale = row_scale(m[1] + m[3]);
    if (!set_calibrated_box(params_.box, {m[0], m[1], m[2], m[3]},
                            {size_.width * scale, size_.height * scale}, {width_, height_}, t)) {
      continue;
    }
    t.score = c.existence;
    t.state = m.cast<double>();
    tracks_.push_back(std::move(t));
  }
  // A component that took an old label back is older than its birth suggests: keep components_
  // (and the tracks) in label order, which merging and explaining-away rely on.
  const auto by_label = [](const BernoulliComponent& a, const BernoulliComponent& b) {
    return a.label < b.label;
  };
  if (!std::is_sorted(components_.begin(), components_.end(), by_label)) {
    sort_by_label(components_);
    std::sort(tracks_.begin(), tracks_.end(),
              [](const TrackEstimate& a, const TrackEstimate& b) { return a.id < b.id; });
  }
}

void MultiBernoulliFilter::clamp_sizes(BoxParticles::States& s, float scale) const {
  s.col(2) = s.col(2)
                 .cwiseMax(scale * float(size_.width_min))
                 .cwiseMin(scale * float(size_.width_max));
  s.col(3) = s.col(3)
                 .cwiseMax(scale * float(size_.height_min))
                 .cwiseMin(scale * float(size_.height_max));
}

void MultiBernoulliFilter::predict() {
  // Eq. (22): r <- P_S r; x <- x + e with e ~ N(0, diag(sigma^2)) (motion_, sigmas relative to
  // the size prior); weights unchanged.
  for (auto& c : components_) {
    c.existence *= params_.survival_probability;
    const Eigen::Index n = c.particles.size();
    // The normals are drawn particle by particle (each particle's four in a row), the order this
    // filter has always used, so a seed gives the tracks it gave; the engine's eps is n x 4.
    noise_.resize(4 * static_cast<std::size_t>(n));
    rng_.fill_normal(noise_.data(), noise_.size());
    eps_ = Eigen::Map<const BoxStates>(noise_.data(), 4, n).transpose();
    // size_by_row: the sigmas and the size range of a person centred on the component's estimate
    // (before the move).
    float scale = 1.0f;
    if (prior_by_row()) {
      const Eigen::Vector4f m = c.mean();
      scale = float(centre_row_scale(m[1] + 0.5f * m[3]));
      eps_ *= scale;
    }
    next_.resize(n, 4);
    motion_.propagate(models::StatesView<float>(c.particles.states()),
                      models::StatesView<float>(eps_), models::MutableStatesView<float>(next_));
    std::swap(c.particles.states(), next_);
    // Beyond the paper: the drift v of MultiBernoulliParams::velocity_smoothing (zero when off).
    auto& x = c.particles.states();
    x.col(0).array() += c.record.velocity[0];
    x.col(1).array() += c.record.velocity[1];
    clamp_sizes(x, scale);
  }
}

void MultiBernoulliFilter::add_birth(double existence, double cx_lo, double cx_hi, double cy_lo,
                                     double cy_hi, const Eigen::Vector2d& size,
                                     const Eigen::Vector2d& size_std, bool prior_size) {
  const int n = params_.birth_particles;
  BoxParticles::States x(n, 4);
  // 2n uniforms for the centres, 2n normals for the sizes, drawn in batches.
  std::vector<double> u(2 * static_cast<std::size_t>(n));
  std::vector<double> z(2 * static_cast<std::size_t>(n));
  rng_.fill_uniform(u.data(), u.size());
  rng_.fill_normal(z.data(), z.size());
  for (int j = 0; j < n; ++j) {
    const double cx = cx_lo + (cx_hi - cx_lo) * u[2 * j];
    const double cy = cy_lo + (cy_hi - cy_lo) * u[2 * j + 1];
    // size_by_row: the scale of a person centred on the box's row (see centre_row_scale).
    const double f = centre_row_scale(cy);
    const double k = prior_size ? f : 1.0;
    // Normal size, truncated (by clamping) to the allowed range.
    const double w = std::clamp(k * (size[0] + size_std[0] * z[2 * j]), f * size_.width_min,
                                f * size_.width_max);
    const double h = std::clamp(k * (size[1] + size_std[1] * z[2 * j + 1]), f * size_.height_min,
                                f * size_.height_max);
    x.row(j) << float(cx - 0.5 * w), float(cy - 0.5 * h), float(w), float(h);
  }
  // Equal weights 1/n.
  components_.push_back(
      {next_label_++, frame_, existence, BoxParticles(std::move(x)), {}, Eigen::Vector4f::Zero()});
}

void MultiBernoulliFilter::add_quarter_births() {
  // Section 4: M_Gamma = 4 components, r_Gamma = 0.02 each, location uniform in one quarter of
  // the image, size from the people size prior. "Location" is taken as the box centre, so a
  // birth box may stick out of the image (it is clipped by the likelihood), as an entering
  // person does.
  const double hw = 0.5 * width_;
  const double hh = 0.5 * height_;
  const Eigen::Vector2d size(size_.width, size_.height);
  const Eigen::Vector2d size_std(size_.width_std, size_.height_std);
  for (int q = 0; q < 4; ++q) {
    const double x0 = (q % 2) * hw;
    const double y0 = (q / 2) * hh;
    add_birth(params_.birth_probability, x0, x0 + hw, y0, y0 + hh, size, size_std, true);
  }
}

void MultiBernoulliFilter::add_adaptive_births() {
  if (params_.adaptive_birth_max == 0) return;
  // Windows at three scales of the mean person size (see the header), scored by log g_y (eq. 20) with the
  // existing targets' boxes as background (O(number of targets) per window). Windows may stick
  // out of the image by half their size (entering people) and are scored on their visible part.
  struct Candidate {
    double score;
    Eigen::Vector4f box;
  };
  std::vector<Candidate> candidates;
  // The window's size and the grid's stride at a foot row: the prior's, times the row's scale
  // with size_by_row (1 otherwise, where the rows are those of y = -wh/2, -wh/2 + stride, ...).
  struct Grid {
    int ww, wh, stride;
  };
  auto grid_at = [this](double scale, int foot) {
    const double f = row_scale(foot);
    return Grid{std::max(1, int(std::lround(scale * f * size_.width))),
                std::max(1, int(std::lround(scale * f * size_.height))),
                prior_by_row() ? std::max(1, int(std::lround(params_.adaptive_birth_stride * f *
                                                             size_.height)))
                               : size_.birth_stride};
  };
  for (const double scale : {0.85, 1.0, 1.3}) {
    const Grid first = grid_at(scale, 0);
    for (int foot = first.wh - first.wh / 2;;) {
      const auto [ww, wh, stride] = grid_at(scale, foot);
      const int y = foot - wh;
      if (y > height_ - wh / 2) break;
      foot += stride;
      for (int x = -ww / 2; x <= width_ - ww / 2; x += stride) {
        if (2 * likelihood_.integral().area({x, y, ww, wh}) < static_cast<long long>(ww) * wh) {
          continue;
        }
        // log g_y falls as the sum of y in the box grows, and explained regions only add to it:
        // the score without them is an upper bound, which rejects most windows in O(1).
        const float fx = float(x), fy = float(y), fw = float(ww), fh = float(wh);
        if (likelihood_.log_likelihood(fx, fy, fw, fh) <= params_.adaptive_birth_log_likelihood) {
          continue;
        }
        const double score = likelihood_.log_likelihood(fx, fy, fw, fh, covered_);
        if (score > params_.adaptive_birth_log_likelihood) {
          candidates.push_back({score, Eigen::Vector4f(fx, fy, fw, fh)});
        }
      }
    }
  }
  // Greedy non-maximum suppression: the best windows first, none overlapping a chosen one by
  // more than a quarter of the smaller.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  std::vector<Eigen::Vector4f> chosen;
  for (const auto& cand : candidates) {
    if (static_cast<int>(chosen.size()) >= params_.adaptive_birth_max) break;
    const bool overlaps = std::any_of(chosen.begin(), chosen.end(), [&](const Eigen::Vector4f& o) {
      return box_overlap(o, cand.box) > 0.25;
    });
    if (!overlaps) chosen.push_back(cand.box);
  }
  for (const auto& b : chosen) {
    const double cx = b[0] + 0.5 * b[2];
    const double cy = b[1] + 0.5 * b[3];
    const Eigen::Vector2d size(b[2], b[3]);
    add_birth(params_.adaptive_birth_probability, cx - 0.15 * b[2], cx + 0.15 * b[2],
              cy - 0.15 * b[3], cy + 0.15 * b[3], size, 0.15 * size, false);
  }
}

void MultiBernoulliFilter::update() {
  for (auto& c : components_) {
    // Other existing targets' boxes are background for this component (eq. 13): the older ones,
    // and the younger ones once established (see MultiBernoulliParams::established_age).
    explained_.clear();
    for (std::size_t k = 0; k < covered_.size(); ++k) {
      const bool older = covered_labels_[k] < c.label;
      const bool established = frame_ - covered_births_[k] >= params_.established_age;
      if (covered_labels_[k] != c.label && (older || established)) explained_.push_back(covered_[k]);
    }
    // (The likelihood reads boxes as columns: a 4 x L copy, small next to its per-box sums.)
    likelihood_.log_likelihood(c.particles.states().transpose(), log_g_, explained_);
    // Eq. (24), w_j <- w_j g_y(x_j) / rho, is the engine's reweighting, and its log normaliser
    // is log rho = log sum_j w_j g_y(x_j) of eq. (23). (Should every g_y underflow, rho = 0: the
    // weights are kept and r drops to 0, to be pruned.)
    const double log_rho = c.particles.reweight(log_g_).log_normaliser;
    c.existence = std::min(updated_existence(c.existence, log_rho), params_.max_existence);
  }
}

void merge_overlapping(std::vector<BernoulliComponent>& components, double min_overlap,
                       double max_existence, std::vector<BernoulliComponent>* absorbed) {
  // Components are in label order, so for i < j, i is the older: j is merged into i, and i
  // keeps its label.
  std::vector<Eigen::Vector4f> means;
  means.reserve(components.size());
  for (const auto& c : components) means.push_back(c.mean());
  std::vector<bool> merged(components.size(), false);
  bool relabelled = false;
  for (std::size_t i = 0; i < components.size(); ++i) {
    if (merged[i]) continue;
    for (std::size_t j = i + 1; j < components.size(); ++j) {
      if (merged[j] || box_overlap(means[i], means[j]) <= min_overlap) continue;
      auto& a = components[i];
      auto& b = components[j];
      // Beyond the paper: a confirmed track is not renamed by an unconfirmed one it absorbs
      // (MultiBernoulliParams::management); when only b is confirmed its label and track state
      // carry on. Otherwise the older label survives (Section 4 does not say; the issue asks).
      if (b.record.confirmed && !a.record.confirmed) {
        std::swap(a.label, b.label);
        std::swap(a.birth_frame, b.birth_frame);
        std::swap(a.record, b.record);
        std::swap(a.last_mean, b.last_mean);
        relabelled = true;
      }
      if (absorbed) absorbed->push_back(b);
      // The merged Bernoulli exists if either does: r = 1 - (1 - r_a)(1 - r_b); its density is
      // the r-weighted mixture of the two particle sets.
      const Eigen::Index na = a.particles.size();
      const Eigen::Index nb = b.particles.size();
      BoxParticles::States x(na + nb, 4);
      x << a.particles.states(), b.particles.states();
      Eigen::VectorXd lw(na + nb);
      // (r > 0 unless the prune threshold is 0; the floor keeps the logs finite.)
      lw << a.particles.log_weights().array() + std::log(std::max(a.existence, 1e-300)),
          b.particles.log_weights().array() + std::log(std::max(b.existence, 1e-300));
      a.particles = BoxParticles(std::move(x), lw);  // normalises the weights
      a.existence = std::min(1.0 - (1.0 - a.existence) * (1.0 - b.existence), max_existence);
      means[i] = a.mean();
      merged[j] = true;
    }
  }
  std::size_t k = 0;
  for (std::size_t i = 0; i < components.size(); ++i) {
    if (merged[i]) continue;
    // Not onto itself: a self-move empties the record's vectors (its colour model).
    if (k != i) components[k] = std::move(components[i]);
    ++k;
  }
  components.resize(k);
  if (relabelled) sort_by_label(components);
}

void MultiBernoulliFilter::prune_and_merge() {
  components_.erase(std::remove_if(components_.begin(), components_.end(),
                                   [&](const BernoulliComponent& c) {
                                     if (c.existence >= params_.prune_threshold) return false;
                                     management_.end(c.label, c.record);
                                     return true;
                                   }),
                    components_.end());
  // Births are appended with increasing labels, so components_ is in label order.
  std::vector<BernoulliComponent> absorbed;
  merge_overlapping(components_, params_.merge_overlap, params_.max_existence,
                    params_.management.lost_memory > 0 ? &absorbed : nullptr);
  // A confirmed track absorbed by another (two people in one blob) may reappear when they part.
  for (const auto& c : absorbed) management_.end(c.label, c.record);
}

void MultiBernoulliFilter::resample() {
  // Particle count proportional to r, clamped to [L_min, L_max] (Section 4, as in the MeMBer
  // filter); weights become uniform.
  for (auto& c : components_) {
    const auto count = static_cast<std::size_t>(std::clamp<double>(
        std::ceil(c.existence * params_.max_particles), params_.min_particles,
        params_.max_particles));
    c.particles.resample(params_.resampling, static_cast<Eigen::Index>(count), rng_);
  }
}

}  // namespace vtrack::filters
