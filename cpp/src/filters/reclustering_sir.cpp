#include "vtrack/filters/reclustering_sir.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/core/vmath.hpp"
#include "vtrack/core/weights.hpp"

namespace vtrack::filters {
namespace {

using core::kInf;
constexpr double kPi = 3.14159265358979323846;

const ReclusteringSirParams& validated(const ReclusteringSirParams& p) {
  validate(p);
  return p;
}

// Constant velocity on (x, y, vx, vy), a random walk on (a, b); standard deviations in px.
models::LinearTransition make_motion(double s_xy, double s_v, double s_ab) {
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(6, 6);
  F(0, 2) = 1.0;
  F(1, 3) = 1.0;
  Eigen::VectorXd s(6);
  s << s_xy, s_xy, s_v, s_v, s_ab, s_ab;
  return models::LinearTransition(F, s.asDiagonal().toDenseMatrix());
}

// Normalised squared distance of (x, y) to an ellipse state's centre (1 on its boundary).
inline float ellipse_d2(const Eigen::Matrix<float, 6, 1>& e, float x, float y) {
  const float dx = (x - e[0]) / e[4];
  const float dy = (y - e[1]) / e[5];
  return dx * dx + dy * dy;
}

Eigen::Vector4f ellipse_box(const Eigen::Matrix<float, 6, 1>& e) {
  return {e[0] - e[4], e[1] - e[5], 2.0f * e[4], 2.0f * e[5]};
}

}  // namespace

const core::ParameterTable<ReclusteringSirParams>& ReclusteringSirParams::table() {
  using P = ReclusteringSirParams;
  static const auto table =
      core::ParameterTable<P>()
          .add("n_particles", &P::n_particles)
          .add("budget_objects", &P::budget_objects)
          .add_choice("resampling", &P::resampling, core::resampling_scheme_names())
          .add("rho", &P::rho)
          .add("novelty_sigma", &P::novelty_sigma)
          .add("shape_weight", &P::shape_weight)
          .add("foreground_threshold", &P::foreground_threshold)
          .add("grid_step", &P::grid_step)
          .add("gate", &P::gate)
          .add("novelty_threshold", &P::novelty_threshold)
          .add("inject_fraction", &P::inject_fraction)
          .add("min_object_fraction", &P::min_object_fraction)
          .add("keep_fraction", &P::keep_fraction)
          .add("merge_distance", &P::merge_distance)
          .add("merge_size", &P::merge_size)
          .add("merge_velocity", &P::merge_velocity)
          .add("max_misses", &P::max_misses)
          .include(&P::size)
          .add("size_by_row", &P::size_by_row)
          .add("sigma_xy", &P::sigma_xy)
          .add("sigma_velocity", &P::sigma_velocity)
          .add("sigma_wh", &P::sigma_wh)
          .include(&P::management)
          .include(&P::box)
          .add("seed", &P::seed);
  return table;
}

void validate(const ReclusteringSirParams& p) {
  require(p.n_particles >= 1 && p.n_particles <= core::kMaxParticles, "n_particles",
          p.n_particles, "in [1, 1000000]");
  require(p.budget_objects >= 1, "budget_objects", p.budget_objects, ">= 1");
  require_positive("rho", p.rho);
  require_positive("novelty_sigma", p.novelty_sigma);
  require(std::isfinite(p.shape_weight) && p.shape_weight >= 0.0, "shape_weight", p.shape_weight,
          ">= 0 and finite");
  require(p.foreground_threshold > 0.0 && p.foreground_threshold <= 1.0, "foreground_threshold",
          p.foreground_threshold, "in (0, 1]");
  require(p.grid_step > 0.0 && p.grid_step <= 1.0, "grid_step", p.grid_step, "in (0, 1]");
  require_positive("gate", p.gate);
  require(p.novelty_threshold >= 0.0 && p.novelty_threshold < 1.0, "novelty_threshold",
          p.novelty_threshold, "in [0, 1)");
  require(p.inject_fraction >= 0.0 && p.inject_fraction <= 1.0, "inject_fraction",
          p.inject_fraction, "in [0, 1]");
  require(p.min_object_fraction > 0.0 && p.min_object_fraction <= 10.0, "min_object_fraction",
          p.min_object_fraction, "in (0, 10]");
  require(p.keep_fraction >= 0.0 && p.keep_fraction <= 10.0, "keep_fraction", p.keep_fraction,
          "in [0, 10]");
  require(std::isfinite(p.merge_distance) && p.merge_distance >= 0.0, "merge_distance",
          p.merge_distance, ">= 0 and finite");
  require(std::isfinite(p.merge_size) && p.merge_size >= 0.0, "merge_size", p.merge_size,
          ">= 0 and finite");
  require(std::isfinite(p.merge_velocity) && p.merge_velocity >= 0.0, "merge_velocity",
          p.merge_velocity, ">= 0 and finite");
  require(p.max_misses >= 1, "max_misses", p.max_misses, ">= 1");
  validate(p.size);
  require(p.sigma_xy >= 0.0 && p.sigma_xy <= 1.0, "sigma_xy", p.sigma_xy, "in [0, 1]");
  require(p.sigma_velocity >= 0.0 && p.sigma_velocity <= 1.0, "sigma_velocity",
          p.sigma_velocity, "in [0, 1]");
  require(p.sigma_wh >= 0.0 && p.sigma_wh <= 1.0, "sigma_wh", p.sigma_wh, "in [0, 1]");
  validate(p.management);
  validate(p.box);
}

Eigen::Matrix2Xf grid_measurements(const cv::Mat& y, float threshold, int step) {
  if (y.empty() || y.type() != CV_32FC1) {
    throw InvalidArgument("y must be a non-empty single-channel float32 image");
  }
  if (step < 1) throw InvalidArgument("grid step must be >= 1, got " + std::to_string(step));
  std::vector<float> pts;
  for (int r = 0; r < y.rows; ++r) {
    const float* row = y.ptr<float>(r);
    // Every pixel is checked (a NaN anywhere is an error, not a silent miss); the grid's are kept.
    bool bad = false;
    for (int c = 0; c < y.cols; ++c) bad |= !(row[c] >= 0.0f && row[c] <= 1.0f);
    if (bad) {
      throw InvalidArgument("y must hold values in [0, 1] (row " + std::to_string(r) +
                            " has NaN or a value outside)");
    }
    if ((r - step / 2) % step != 0 || r < step / 2) continue;
    for (int c = step / 2; c < y.cols; c += step) {
      if (row[c] < threshold) {
        pts.push_back(float(c) + 0.5f);
        pts.push_back(float(r) + 0.5f);
      }
    }
  }
  return Eigen::Map<const Eigen::Matrix2Xf>(pts.data(), 2, Eigen::Index(pts.size() / 2));
}

double ellipse_log_likelihood(float cx, float cy, float a, float b,
                              const Eigen::Ref<const Eigen::Matrix2Xf>& z, double rho, float sx,
                              float sy, double shape_power) {
  const Eigen::Index n = z.cols();
  if (n == 0 || !(a > 0.0f) || !(b > 0.0f)) return -kInf;
  const float ia2 = 1.0f / (a * a), ib2 = 1.0f / (b * b);
  const float isx2 = 1.0f / (sx * sx), isy2 = 1.0f / (sy * sy);
  long long n_in = 0;
  double sum = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const float dx = z(0, j) - cx, dy = z(1, j) - cy;
    const float dx2 = dx * dx, dy2 = dy * dy;
    n_in += (dx2 * ia2 + dy2 * ib2 <= 1.0f) ? 1 : 0;
    // log(rho + h(z_j | x)), h the Gaussian of the Mahalanobis distance (§2.1).
    sum += core::vmath::log(rho + core::vmath::exp(-0.5 * double(dx2 * isx2 + dy2 * isy2)));
  }
  if (n_in == 0) return -kInf;
  const double nin = double(n_in);
  return shape_power *
             (std::log(nin / (kPi * double(a) * double(b))) + std::log(nin / double(n))) +
         sum;
}

ReclusteringSir::ReclusteringSir(int width, int height, const ReclusteringSirParams& params)
    : params_(validated(params)), width_(width), height_(height), rng_(params.seed),
      person_height_(params.size, height),
      motion_(make_motion(0, 0, 0)), management_(params.management) {
  if (width < 1) throw InvalidArgument("width must be >= 1, got " + std::to_string(width));
  if (height < 1) throw InvalidArgument("height must be >= 1, got " + std::to_string(height));
  person_height_.set_fit_line(params_.size_by_row);
  set_person_height(person_height_.height());
  initialise();
}

void ReclusteringSir::set_person_height(double h) {
  person_h_ = std::max(h, 2.0);  // axes of at least a pixel whatever the scale
  grid_ = std::max(1, static_cast<int>(std::lround(params_.grid_step * person_h_)));
  row_scale_.clear();
  if (params_.size_by_row && person_height_.by_row()) {
    // The scale of a person centred on row r: h at its foot row r + (half its height there),
    // one fixed-point step (as the multi-Bernoulli tracker's centre_row_scale), no smaller than
    // the smallest people the line was fitted on (above their rows the line's extrapolation would
    // make specks on walls and tree tops person-sized).
    const double smallest = person_height_.smallest_seen() / person_h_;
    const auto at_foot = [&](double row) { return person_height_.height_at_foot(row) / person_h_; };
    row_scale_.resize(std::size_t(height_));
    for (int r = 0; r < height_; ++r) {
      const double half = 0.5 * person_h_;
      const double s = std::max(smallest, at_foot(r + half * at_foot(r + half)));
      row_scale_[std::size_t(r)] = float(s);
    }
  }
  motion_ = make_motion(params_.sigma_xy * person_h_, params_.sigma_velocity * person_h_,
                        0.5 * params_.sigma_wh * person_h_);
}

float ReclusteringSir::gate_d2(const Object& o, float x, float y) const {
  // The estimate's axes, but never below the person size's: an ellipse that has shrunk onto part
  // of a person still gathers the whole person's pixels, the evidence it needs to grow back.
  const Eigen::Vector2f person = half_size(o.estimate[1]);
  const float a = std::max(o.estimate[4], person[0]);
  const float b = std::max(o.estimate[5], person[1]);
  const float dx = (x - o.estimate[0]) / a, dy = (y - o.estimate[1]) / b;
  return dx * dx + dy * dy;
}

double ReclusteringSir::expected_points(float s) const {
  const double hw = 0.5 * params_.size.size_aspect * person_h_, hh = 0.5 * person_h_;
  return kPi * hw * hh * double(s) * double(s) / (double(grid_) * grid_);
}

void ReclusteringSir::initialise() {
  // §2.2: centres uniform over the image, velocities around zero, axes uniform in the expected
  // size range; no object owns them (cluster 0).
  const int n = params_.n_particles;
  const double sv = params_.sigma_velocity * person_h_;
  Particles::States x(n, 6);
  for (int i = 0; i < n; ++i) {
    x(i, 0) = float(rng_.uniform(0.0, width_));
    x(i, 1) = float(rng_.uniform(0.0, height_));
    x(i, 2) = float(sv * rng_.normal());
    x(i, 3) = float(sv * rng_.normal());
    const Eigen::Vector2d half = half_size(x(i, 1)).cast<double>();  // the range at its row
    x(i, 4) = float(rng_.uniform(params_.size.size_min * half[0], params_.size.size_max * half[0]));
    x(i, 5) = float(rng_.uniform(params_.size.size_min * half[1], params_.size.size_max * half[1]));
  }
  particles_ = Particles(std::move(x));
  clusters_.assign(std::size_t(n), 0);
}

void ReclusteringSir::end_object(std::size_t k) { management_.end(objects_[k].label, objects_[k].record); }

const Tracks& ReclusteringSir::step(const cv::Mat& y, const cv::Mat& frame) {
  if (y.cols != width_ || y.rows != height_) {
    throw InvalidArgument("y must be " + std::to_string(height_) + " x " + std::to_string(width_) +
                          " (height x width), got " + std::to_string(y.rows) + " x " +
                          std::to_string(y.cols));
  }
  if (!frame.empty()) check_colour_frame(frame, y);
  z_ = grid_measurements(y, float(params_.foreground_threshold), grid_);  // validates y
  management_.begin_step(frame_);
  tracks_.clear();
  if (z_.cols() == 0) {
    // §2.2: no measurement in the image: every object ends, the particles start afresh.
    for (std::size_t k = 0; k < objects_.size(); ++k) end_object(k);
    objects_.clear();
    initialise();
  } else {
    predict();
    update_estimates();  // the predicted estimates: association sees where people will be
    associate();
    weigh();
    update_estimates();
    inject();
    recluster();
    update_estimates();
    report(y, frame);
    resample();
  }
  // The person size learnt from this frame's foreground applies from the next frame on.
  const double area = params_.size.size_aspect * person_h_ * person_h_;
  if (person_height_.observe(y, float(params_.foreground_threshold), area)) {
    set_person_height(person_height_.height());
  }
  ++frame_;
  return tracks_;
}

void ReclusteringSir::predict() {
  const Eigen::Index n = particles_.size();
  eps_.resize(n, 6);
  rng_.fill_normal(eps_.data(), std::size_t(eps_.size()));
  next_.resize(n, 6);
  motion_.propagate(models::StatesView<float>(particles_.states()),
                    models::StatesView<float>(eps_), models::MutableStatesView<float>(next_));
  std::swap(particles_.states(), next_);
  // The axes stay in the size range of a person at the particle's row.
  auto& x = particles_.states();
  const float lo = float(params_.size.size_min), hi = float(params_.size.size_max);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2f half = half_size(x(i, 1));
    x(i, 4) = std::clamp(x(i, 4), lo * half[0], hi * half[0]);
    x(i, 5) = std::clamp(x(i, 5), lo * half[1], hi * half[1]);
  }
}

void ReclusteringSir::associate() {
  // Nearest object estimate in its own normalised distance, within the gate; else Z^0.
  const Eigen::Index n = z_.cols();
  members_.assign(objects_.size() + 1, {});
  assoc_.assign(std::size_t(n), 0);
  for (Eigen::Index j = 0; j < n; ++j) {
    const int c = nearest_gate(z_(0, j), z_(1, j));
    assoc_[std::size_t(j)] = c;
    members_[std::size_t(c)].push_back(int(j));
  }
  zsets_.resize(members_.size());
  for (std::size_t m = 0; m < members_.size(); ++m) {
    zsets_[m].resize(2, Eigen::Index(members_[m].size()));
    for (std::size_t q = 0; q < members_[m].size(); ++q) zsets_[m].col(Eigen::Index(q)) = z_.col(members_[m][q]);
  }
}

void ReclusteringSir::weigh() {
  const Eigen::Index n = particles_.size();
  const auto& x = particles_.states();
  const float sigma = float(params_.novelty_sigma);
  Eigen::VectorXd log_lik(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& zs = zsets_[std::size_t(clusters_[std::size_t(i)])];
    // C normalises the dimensions of a person at the particle's row.
    const Eigen::Vector2f c = sigma * half_size(x(i, 1));
    // An object without measurements learns nothing this step (its weights are kept).
    // The two external factors of §2.1 raised to 1 + shape_weight N (see the parameter).
    const double power = 1.0 + params_.shape_weight * double(zs.cols());
    log_lik[i] = zs.cols() == 0 ? 0.0
                                : ellipse_log_likelihood(x(i, 0), x(i, 1), x(i, 4), x(i, 5), zs,
                                                         params_.rho, c[0], c[1], power);
  }
  reweight_per_cluster(log_lik);
}

void ReclusteringSir::reweight_per_cluster(Eigen::VectorXd& log_lik) {
  // Within cluster c: log l_i <- log l_i - log sum_{k in c} w_k l_k + log sum_{k in c} w_k, so
  // that the engine's reweight (w_i l_i / sum) leaves every cluster's mass as it was. A cluster
  // whose particles all have l = 0 (no measurement inside any ellipse) keeps its weights.
  const std::size_t m = objects_.size() + 1;
  const Eigen::VectorXd& lw = particles_.log_weights();
  std::vector<double> max_t(m, -kInf), max_w(m, -kInf);
  for (Eigen::Index i = 0; i < lw.size(); ++i) {
    const auto c = std::size_t(clusters_[std::size_t(i)]);
    max_t[c] = std::max(max_t[c], lw[i] + log_lik[i]);
    max_w[c] = std::max(max_w[c], lw[i]);
  }
  std::vector<double> sum_t(m, 0.0), sum_w(m, 0.0);
  for (Eigen::Index i = 0; i < lw.size(); ++i) {
    const auto c = std::size_t(clusters_[std::size_t(i)]);
    if (max_t[c] > -kInf) sum_t[c] += std::exp(lw[i] + log_lik[i] - max_t[c]);
    sum_w[c] += std::exp(lw[i] - max_w[c]);
  }
  for (Eigen::Index i = 0; i < lw.size(); ++i) {
    const auto c = std::size_t(clusters_[std::size_t(i)]);
    if (!(max_t[c] > -kInf)) {
      log_lik[i] = 0.0;
    } else {
      log_lik[i] += (max_w[c] + std::log(sum_w[c])) - (max_t[c] + std::log(sum_t[c]));
    }
  }
  particles_.reweight(log_lik);
}

void ReclusteringSir::update_estimates() {
  // Each object's weighted mean ellipse (part-based eq. 8 within its cluster) and particle count.
  const std::size_t m = objects_.size();
  std::vector<Eigen::Matrix<double, 6, 1>> sums(m, Eigen::Matrix<double, 6, 1>::Zero());
  std::vector<double> mass(m, 0.0);
  for (auto& o : objects_) o.count = 0;
  const Eigen::VectorXd& lw = particles_.log_weights();
  const auto& x = particles_.states();
  // Weights relative to the cluster's largest, so that no cluster's sums underflow.
  std::vector<double> top(m, -kInf);
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const int c = clusters_[std::size_t(i)];
    if (c > 0) top[std::size_t(c - 1)] = std::max(top[std::size_t(c - 1)], lw[i]);
  }
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const int c = clusters_[std::size_t(i)];
    if (c == 0) continue;
    const double w = std::exp(lw[i] - top[std::size_t(c - 1)]);
    sums[std::size_t(c - 1)] += w * x.row(i).transpose().cast<double>();
    mass[std::size_t(c - 1)] += w;
    ++objects_[std::size_t(c - 1)].count;
  }
  for (std::size_t k = 0; k < m; ++k) {
    if (mass[k] > 0.0) objects_[k].estimate = (sums[k] / mass[k]).cast<float>();
  }
}

void ReclusteringSir::novel_measurements(std::vector<int>& novel,
                                         std::vector<double>& novelty) const {
  // The novelty distribution n(z_j) = prod_m (1 - h(z_j | xhat_m)) over the objects' estimates.
  std::vector<Eigen::Vector2f> c;
  for (const auto& o : objects_) c.push_back(float(params_.novelty_sigma) * half_size(o.estimate[1]));
  novel.clear();
  novelty.clear();
  for (Eigen::Index j = 0; j < z_.cols(); ++j) {
    double nz = 1.0;
    for (std::size_t k = 0; k < objects_.size(); ++k) {
      const auto& o = objects_[k];
      const float dx = (z_(0, j) - o.estimate[0]) / c[k][0], dy = (z_(1, j) - o.estimate[1]) / c[k][1];
      nz *= 1.0 - std::exp(-0.5 * double(dx * dx + dy * dy));
    }
    if (nz > params_.novelty_threshold) {
      novel.push_back(int(j));
      novelty.push_back(nz);
    }
  }
}

Eigen::Vector2f ReclusteringSir::novel_centroid(const std::vector<int>& novel,
                                                Eigen::Vector2f centre) const {
  // Two mean-shift steps: the centroid of the novel measurements within a person's ellipse.
  for (int it = 0; it < 2; ++it) {
    const Eigen::Vector2d half = half_size(centre[1]).cast<double>();
    const double hw = half[0], hh = half[1];
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    int count = 0;
    for (const int j : novel) {
      const double dx = (z_(0, j) - centre[0]) / hw, dy = (z_(1, j) - centre[1]) / hh;
      if (dx * dx + dy * dy > 1.0) continue;
      sum += z_.col(j).cast<double>();
      ++count;
    }
    if (count > 0) centre = (sum / count).cast<float>();
  }
  return centre;
}

int ReclusteringSir::nearest_gate(float x, float y) const {
  float best = float(params_.gate * params_.gate);
  int k_best = -1;
  for (std::size_t k = 0; k < objects_.size(); ++k) {
    const float d2 = gate_d2(objects_[k], x, y);
    if (d2 <= best) {
      best = d2;
      k_best = int(k);
    }
  }
  return k_best + 1;
}

int ReclusteringSir::found_object(const State& s, const std::vector<int>& novel) {
  const double min_points =
      std::max(1.0, params_.min_object_fraction * expected_points(count_scale(s[1])));
  int inside = 0;
  for (const int j : novel) inside += ellipse_d2(s, z_(0, j), z_(1, j)) <= 1.0f ? 1 : 0;
  if (double(inside) < min_points) return -1;
  Object o;
  o.label = next_label_++;
  o.birth_frame = frame_;
  o.estimate = s;
  objects_.push_back(o);
  return int(objects_.size());
}

void ReclusteringSir::place_best_free(const Particles::States& x, const Eigen::VectorXd& lw,
                                      const std::vector<int>& novel) {
  Eigen::Index best = -1;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (clusters_[std::size_t(i)] == 0 && (best < 0 || lw[i] > lw[best])) best = i;
  }
  if (best < 0) return;
  const State s = x.row(best).transpose();
  const int gate = nearest_gate(s[0], s[1]);
  const int c = gate > 0 ? gate : found_object(s, novel);
  if (c > 0) clusters_[std::size_t(best)] = c;
}

ReclusteringSir::State ReclusteringSir::injection_state(const Eigen::Vector2f& centre) {
  const Eigen::Vector2d half = half_size(centre[1]).cast<double>();
  const double hw = half[0], hh = half[1];
  const double sxy = params_.sigma_xy * person_h_, sv = params_.sigma_velocity * person_h_;
  const auto axis = [&](double prior) {
    return float(std::clamp(prior * (1.0 + params_.size.size_std * rng_.normal()),
                            params_.size.size_min * prior, params_.size.size_max * prior));
  };
  State s;  // drawn in this order: the same seed gives the same particles
  s[0] = float(centre[0] + sxy * rng_.normal());
  s[1] = float(centre[1] + sxy * rng_.normal());
  s[2] = float(sv * rng_.normal());
  s[3] = float(sv * rng_.normal());
  s[4] = axis(hw);
  s[5] = axis(hh);
  return s;
}

namespace {

// The particles injections replace (Fig. 1): free particles first, then the lowest weighted,
// never an object's last one; at most `limit` of them.
class InjectionSlots {
 public:
  InjectionSlots(const std::vector<int>& clusters, const Eigen::VectorXd& lw,
                 std::size_t n_objects, std::size_t limit)
      : order_(lw.size()), counts_(n_objects + 1, 0), limit_(limit) {
    std::iota(order_.begin(), order_.end(), Eigen::Index(0));
    std::stable_sort(order_.begin(), order_.end(), [&](Eigen::Index a, Eigen::Index b) {
      const bool fa = clusters[std::size_t(a)] == 0, fb = clusters[std::size_t(b)] == 0;
      return fa != fb ? fa : lw[a] < lw[b];
    });
    for (const int c : clusters) ++counts_[std::size_t(c)];
  }

  // Puts state s into the next slot, in cluster c (of n_objects), with weight 1 / N; false when
  // no slot is left.
  template <class State, class States>
  bool take(const State& s, int c, std::size_t n_objects, std::vector<int>& clusters, States& x,
            Eigen::VectorXd& lw) {
    while (next_ < order_.size()) {
      const auto ci = std::size_t(clusters[std::size_t(order_[next_])]);
      if (ci == 0 || counts_[ci] > 1) break;
      ++next_;
    }
    if (next_ == order_.size() || taken_ == limit_) return false;
    ++taken_;
    const Eigen::Index slot = order_[next_++];
    if (counts_.size() < n_objects + 1) counts_.resize(n_objects + 1, 0);
    --counts_[std::size_t(clusters[std::size_t(slot)])];
    ++counts_[std::size_t(c)];
    x.row(slot) = s.transpose();
    clusters[std::size_t(slot)] = c;
    lw[slot] = -std::log(double(lw.size()));
    return true;
  }

 private:
  std::vector<Eigen::Index> order_;
  std::vector<int> counts_;
  std::size_t limit_, next_ = 0, taken_ = 0;
};

}  // namespace

void ReclusteringSir::inject() {
  std::vector<int> novel;
  std::vector<double> novelty;
  novel_measurements(novel, novelty);
  // Enough novel measurements for a person anywhere (found_object checks its row).
  const double min_points = std::max(1.0, params_.min_object_fraction * expected_points());
  if (double(novel.size()) < min_points) return;
  Particles::States x = particles_.states();
  Eigen::VectorXd lw = particles_.log_weights();
  // §2.2's free particles: the most likely one may found an object (the initialisation's path to
  // the first objects; injection is the other).
  place_best_free(x, lw, novel);
  // At most k particles are injected; candidates that neither join nor found an object (drawn
  // on a noise speck) take no slot, so up to kCandidates k are drawn.
  constexpr std::size_t kCandidates = 4;
  const auto k = std::size_t(std::ceil(params_.inject_fraction * double(x.rows())));
  if (k == 0) return;
  std::vector<std::int64_t> drawn(kCandidates * k);
  core::resample(core::ResamplingScheme::Multinomial,
                 Eigen::Map<const Eigen::VectorXd>(novelty.data(), Eigen::Index(novelty.size())),
                 drawn.size(), rng_, drawn.data());
  InjectionSlots slots(clusters_, lw, objects_.size(), k);
  std::vector<State> joins;
  for (const std::int64_t d : drawn) {
    // Near the drawn measurement: at the centroid of the novel measurements within a person's
    // ellipse of it, so that the injections drawn from one person's pixels land near one centre
    // and found one object, not one per body part.
    const State s = injection_state(novel_centroid(novel, z_.col(novel[std::size_t(d)])));
    // Candidates that start objects take slots first, then those joining one: the draws come
    // in measurement (raster) order, and joins into the objects above would otherwise use up
    // the slots before a new person lower in the image is reached.
    if (nearest_gate(s[0], s[1]) > 0) {
      joins.push_back(s);
      continue;
    }
    const int c = found_object(s, novel);
    if (c > 0 && !slots.take(s, c, objects_.size(), clusters_, x, lw)) break;
  }
  for (const State& s : joins) {
    if (!slots.take(s, nearest_gate(s[0], s[1]), objects_.size(), clusters_, x, lw)) break;
  }
  particles_ = Particles(std::move(x), lw);  // normalises the weights
}

void ReclusteringSir::recluster() {
  const std::size_t m = objects_.size();
  // Every particle joins the object whose estimate is nearest among those whose gate holds it.
  const auto& x = particles_.states();
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (const int c = nearest_gate(x(i, 0), x(i, 1))) clusters_[std::size_t(i)] = c;
  }
  std::vector<bool> ended(m, false);
  // Objects whose centres are within merge_distance person half-sizes of each other are one
  // person (two objects that split a silhouette sit about one half height apart) and merge into
  // the older (earlier) one; a confirmed label is not renamed by an unconfirmed one (as
  // merge_overlapping of the multi-Bernoulli filter).
  const float merge2 = float(params_.merge_distance * params_.merge_distance);
  for (std::size_t a = 0; a < m; ++a) {
    if (ended[a]) continue;
    for (std::size_t b = a + 1; b < m; ++b) {
      if (ended[b]) continue;
      // A person's size between the two.
      const Eigen::Vector2f half =
          half_size(0.5f * (objects_[a].estimate[1] + objects_[b].estimate[1]));
      const float hw = half[0], hh = half[1];
      const float dx = (objects_[a].estimate[0] - objects_[b].estimate[0]) / hw;
      const float dy = (objects_[a].estimate[1] - objects_[b].estimate[1]) / hh;
      bool merge = dx * dx + dy * dy <= merge2;
      if (!merge && b + 1 < members_.size() && zsets_[a + 1].cols() > 0 &&
          zsets_[b + 1].cols() > 0) {
        // Their measurements together fit in one person's box (a silhouette split in two).
        const Eigen::Vector2f lo = zsets_[a + 1].rowwise().minCoeff().cwiseMin(
            zsets_[b + 1].rowwise().minCoeff());
        const Eigen::Vector2f hi = zsets_[a + 1].rowwise().maxCoeff().cwiseMax(
            zsets_[b + 1].rowwise().maxCoeff());
        merge = hi[0] - lo[0] <= 2.0f * hw * float(params_.merge_size) &&
                hi[1] - lo[1] <= 2.0f * hh * float(params_.merge_size);
      }
      // Two people crossing come as close as a split silhouette's halves, but move apart: a pair
      // whose velocities differ by more than merge_velocity person heights per step is two people.
      if (merge && params_.merge_velocity > 0.0) {
        const Eigen::Vector2f dv = objects_[a].estimate.segment<2>(2) - objects_[b].estimate.segment<2>(2);
        merge = dv.norm() <= float(params_.merge_velocity) * 2.0f * hh;
      }
      if (!merge) continue;
      if (objects_[b].record.confirmed && !objects_[a].record.confirmed) {
        std::swap(objects_[a].label, objects_[b].label);
        std::swap(objects_[a].birth_frame, objects_[b].birth_frame);
        std::swap(objects_[a].record, objects_[b].record);
      }
      end_object(b);
      ended[b] = true;
      for (int& c : clusters_) {
        if (c == int(b) + 1) c = int(a) + 1;
      }
    }
  }
  // Too few measurements for max_misses steps: the object releases its particles and ends.
  for (std::size_t k = 0; k < m; ++k) {
    const bool old = k + 1 < members_.size();  // existed at the association
    const double min_points =
        params_.keep_fraction * expected_points(count_scale(objects_[k].estimate[1]));
    objects_[k].misses = old && double(members_[k + 1].size()) < min_points
                             ? objects_[k].misses + 1 : 0;
    if (ended[k] || objects_[k].misses < params_.max_misses) continue;
    end_object(k);
    ended[k] = true;
    for (int& c : clusters_) {
      if (c == int(k) + 1) c = 0;
    }
  }
  std::vector<int> counts(m + 1, 0);
  for (const int c : clusters_) ++counts[std::size_t(c)];
  for (std::size_t k = 0; k < m; ++k) {
    if (!ended[k] && counts[k + 1] == 0) {  // its cluster emptied
      end_object(k);
      ended[k] = true;
    }
  }
  remove_ended(ended);
}

void ReclusteringSir::remove_ended(std::vector<bool>& ended) {
  std::vector<int> index(objects_.size(), -1);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < objects_.size(); ++k) {
    if (ended[k]) continue;
    index[k] = int(kept);
    // Not onto itself: a self-move empties the record's vectors (its colour model).
    if (kept != k) objects_[kept] = std::move(objects_[k]);
    ++kept;
  }
  objects_.resize(kept);
  for (int& c : clusters_) {
    if (c > 0) c = index[std::size_t(c - 1)] + 1;  // ended -> -1 + 1 = 0, free
  }
  // Measurement sets follow (by object), for the scores of report().
  std::vector<Eigen::Matrix2Xf> z(kept + 1);
  z[0] = zsets_.empty() ? Eigen::Matrix2Xf() : zsets_[0];
  for (std::size_t k = 0; k < index.size(); ++k) {
    if (index[k] >= 0 && k + 1 < zsets_.size()) z[std::size_t(index[k]) + 1] = zsets_[k + 1];
  }
  zsets_ = std::move(z);
}

void ReclusteringSir::report(const cv::Mat& y, const cv::Mat& frame) {
  // Each object's estimate as its ellipse's bounding box, through the track manager.
  const std::size_t m = objects_.size();
  std::vector<Eigen::Vector4f> boxes(m);
  for (std::size_t k = 0; k < m; ++k) boxes[k] = ellipse_box(objects_[k].estimate);
  const bool colour = !frame.empty() && params_.management.appearance_rate > 0.0;
  if (colour) {
    colour_.measure(frame, y, float(params_.foreground_threshold), boxes, seen_);
  } else {
    seen_.assign(m, {});
  }
  std::vector<TrackManager::View> views;
  for (std::size_t k = 0; k < m; ++k) {
    Object& o = objects_[k];
    o.record.velocity = o.estimate.segment<2>(2);
    const Eigen::Matrix2Xf& zs = zsets_[k + 1];
    int inside = 0;
    for (Eigen::Index j = 0; j < zs.cols(); ++j) {
      inside += ellipse_d2(o.estimate, zs(0, j), zs(1, j)) <= 1.0f ? 1 : 0;
    }
    o.score = zs.cols() > 0 ? double(inside) / double(zs.cols()) : 0.0;
    if (const auto lost = management_.observe(o.label, o.record, boxes[k], seen_[k])) o.label = *lost;
    views.push_back({&o.label, &o.record, boxes[k], &seen_[k]});
  }
  if (colour) management_.resolve(views);
  for (std::size_t k = 0; k < m; ++k) {
    Object& o = objects_[k];
    if (!management_.report(o.record, boxes[k])) continue;
    TrackEstimate t;
    t.id = o.label;
    const Eigen::Vector2f person = 2.0f * half_size(o.estimate[1]);
    if (!set_calibrated_box(params_.box, {boxes[k][0], boxes[k][1], boxes[k][2], boxes[k][3]},
                            {person[0], person[1]}, {width_, height_}, t)) {
      continue;
    }
    t.score = o.score;
    t.state = o.estimate.cast<double>();
    tracks_.push_back(std::move(t));
  }
  std::sort(tracks_.begin(), tracks_.end(),
            [](const TrackEstimate& a, const TrackEstimate& b) { return a.id < b.id; });
}

void ReclusteringSir::resample() {
  const std::size_t m = objects_.size();
  std::vector<std::vector<Eigen::Index>> members(m + 1);
  for (std::size_t i = 0; i < clusters_.size(); ++i) {
    members[std::size_t(clusters_[i])].push_back(Eigen::Index(i));
  }
  std::vector<long long> target(m + 1, 0);
  if (m == 0) {
    if (members[0].empty()) {
      initialise();
      return;
    }
    target[0] = params_.n_particles;  // the §2.2 cloud, until an object is found
  } else {
    // The budget: n_particles per budget_objects objects (§2.2), at least one per object.
    const long long groups = (static_cast<long long>(m) + params_.budget_objects - 1) / params_.budget_objects;
    const long long budget = std::max<long long>(
        static_cast<long long>(m), std::min<long long>(core::kMaxParticles, params_.n_particles * groups));
    const long long share = budget / static_cast<long long>(m);
    long long used = 0;
    std::vector<std::size_t> full;
    for (std::size_t k = 0; k < m; ++k) {
      const long long c = static_cast<long long>(members[k + 1].size());
      if (c < share) {
        target[k + 1] = std::min(share, 2 * c);  // a new object grows, doubling
        used += target[k + 1];
      } else {
        full.push_back(k);
      }
    }
    const long long rest = budget - used;
    for (std::size_t q = 0; q < full.size(); ++q) {
      target[full[q] + 1] =
          rest / static_cast<long long>(full.size()) + (static_cast<long long>(q) < rest % static_cast<long long>(full.size()) ? 1 : 0);
    }
  }
  // Within each cluster, the engine's resampling on the cluster's own weights.
  const Eigen::VectorXd& lw = particles_.log_weights();
  std::vector<std::int64_t> ancestors;
  std::vector<int> clusters;
  std::vector<std::int64_t> local;
  for (std::size_t c = 0; c <= m; ++c) {
    if (target[c] == 0 || members[c].empty()) continue;
    Eigen::VectorXd w(Eigen::Index(members[c].size()));
    double top = -kInf;
    for (const Eigen::Index i : members[c]) top = std::max(top, lw[i]);
    for (std::size_t q = 0; q < members[c].size(); ++q) w[Eigen::Index(q)] = std::exp(lw[members[c][q]] - top);
    local.resize(std::size_t(target[c]));
    core::resample(params_.resampling, w, local.size(), rng_, local.data());
    for (const std::int64_t q : local) {
      ancestors.push_back(members[c][std::size_t(q)]);
      clusters.push_back(int(c));
    }
  }
  smc::gather_rows(particles_.states(), ancestors.data(), Eigen::Index(ancestors.size()), next_);
  std::swap(particles_.states(), next_);
  particles_.set_uniform();
  clusters_ = std::move(clusters);
}

}  // namespace vtrack::filters
