#include "vtrack/filters/detector_learning.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Cholesky>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"

namespace vtrack::filters {
namespace {

void check(const Forgetting& f) {
  require(f.memory >= 1.0 && std::isfinite(f.memory), "memory", f.memory, ">= 1 and finite");
  require(f.prior_weight > 0.0 && std::isfinite(f.prior_weight), "prior_weight", f.prior_weight,
          "> 0 and finite");
}

}  // namespace

ClutterRate::ClutterRate(double prior_rate, Forgetting forgetting)
    : prior_rate_(prior_rate), forgetting_(forgetting) {
  require(prior_rate > 0.0 && std::isfinite(prior_rate), "clutter_rate", prior_rate,
          "> 0 and finite");
  check(forgetting_);
}

void ClutterRate::update(double expected_count, double exposure) {
  const double f = forgetting_.factor();
  count_ = f * count_ + std::max(expected_count, 0.0);
  scans_ = f * scans_ + std::max(exposure, 0.0);
}

double ClutterRate::rate() const {
  const double n0 = forgetting_.prior_weight;
  return (n0 * prior_rate_ + count_) / (n0 + scans_);
}

DetectionProbability::DetectionProbability(double prior, double lower, double upper,
                                           Forgetting forgetting)
    : prior_(prior), lower_(lower), upper_(upper), forgetting_(forgetting) {
  require(lower > 0.0 && lower <= upper && upper < 1.0, "detection_probability bounds", lower,
          "0 < lower <= upper < 1");
  require(prior >= lower && prior <= upper, "detection_probability", prior,
          "within the learning bounds");
  check(forgetting_);
}

void DetectionProbability::update(double detected, double missed) {
  const double f = forgetting_.factor();
  detected_ = f * detected_ + std::max(detected, 0.0);
  missed_ = f * missed_ + std::max(missed, 0.0);
}

double DetectionProbability::probability() const {
  // The prior is worth prior_weight detectable-track observations.
  const double n0 = forgetting_.prior_weight;
  const double p = (n0 * prior_ + detected_) / (n0 + detected_ + missed_);
  return std::clamp(p, lower_, upper_);
}

WeightedGaussian::WeightedGaussian(Eigen::VectorXd prior_mean, Eigen::MatrixXd prior_cov,
                                   double prior_weight, double memory)
    : m0_(std::move(prior_mean)),
      c0_(std::move(prior_cov)),
      n0_(prior_weight),
      factor_(1.0 - 1.0 / memory),
      sum_(Eigen::VectorXd::Zero(m0_.size())),
      sum_sq_(Eigen::MatrixXd::Zero(m0_.size(), m0_.size())) {
  check({memory, prior_weight});
  if (c0_.rows() != m0_.size() || c0_.cols() != m0_.size() ||
      Eigen::LLT<Eigen::MatrixXd>(c0_).info() != Eigen::Success) {
    throw InvalidArgument("WeightedGaussian: the prior covariance must be symmetric positive "
                          "definite of the mean's dimension");
  }
}

void WeightedGaussian::update(const Eigen::Ref<const Eigen::MatrixXd>& y,
                              const Eigen::Ref<const Eigen::VectorXd>& w) {
  weight_ *= factor_;
  sum_ *= factor_;
  sum_sq_ *= factor_;
  weight_ += w.sum();
  sum_ += y * w;
  sum_sq_ += y * w.asDiagonal() * y.transpose();
}

Eigen::VectorXd WeightedGaussian::mean() const { return (n0_ * m0_ + sum_) / (n0_ + weight_); }

Eigen::MatrixXd WeightedGaussian::covariance() const {
  // Second moments of the prior (n0 points with covariance C0 about m0) and of the data, about
  // the pooled mean.
  const Eigen::VectorXd m = mean();
  const Eigen::MatrixXd second = n0_ * (c0_ + m0_ * m0_.transpose()) + sum_sq_;
  Eigen::MatrixXd c = second / (n0_ + weight_) - m * m.transpose();
  return 0.5 * (c + c.transpose());
}

Eigen::VectorXd WeightedGaussian::log_density(const Eigen::Ref<const Eigen::MatrixXd>& y) const {
  // No columns, no densities (Eigen's triangular solve reads coefficient (0, 0) even of an empty
  // right-hand side: UndefinedBehaviorSanitizer's finding on a scan without detections).
  if (y.cols() == 0) return Eigen::VectorXd();
  const Eigen::VectorXd m = mean();
  Eigen::LLT<Eigen::MatrixXd> llt(covariance());
  if (llt.info() != Eigen::Success) llt.compute(c0_);  // round-off only: the prior keeps it PD
  const Eigen::MatrixXd L = llt.matrixL();
  const double log_norm = -0.5 * static_cast<double>(m.size()) * core::kLog2Pi -
                          L.diagonal().array().log().sum();
  const Eigen::MatrixXd white = L.triangularView<Eigen::Lower>().solve(y.colwise() - m);
  return (log_norm - 0.5 * white.colwise().squaredNorm().array()).matrix().transpose();
}

ScoreModel::ScoreModel(int window, double prior_weight, double memory)
    : window_(window), n0_(prior_weight), factor_(1.0 - 1.0 / memory) {
  require(window >= 1, "score_window", window, ">= 1");
  check({memory, prior_weight});
  recent_.reserve(static_cast<std::size_t>(window));
}

Eigen::VectorXd ScoreModel::transform(const Eigen::Ref<const Eigen::VectorXd>& scores) const {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(scores.size());
  const auto n = static_cast<double>(sorted_.size());
  if (sorted_.empty()) return u;
  for (Eigen::Index j = 0; j < scores.size(); ++j) {
    const auto lo = std::lower_bound(sorted_.begin(), sorted_.end(), scores[j]);
    const auto hi = std::upper_bound(lo, sorted_.end(), scores[j]);
    // Mid-rank, kept half an observation away from 0 and 1.
    const double below = static_cast<double>(lo - sorted_.begin());
    const double equal = static_cast<double>(hi - lo);
    const double F = std::clamp((below + 0.5 * equal) / n, 0.5 / n, 1.0 - 0.5 / n);
    u[j] = F == 0.5 ? 0.0 : core::normal_quantile(F);
  }
  return u;
}

double ScoreModel::target_mean() const { return wu_[1] / (n0_ + w_[1]); }
double ScoreModel::clutter_mean() const { return wu_[0] / (n0_ + w_[0]); }

double ScoreModel::sd() const {
  // Pooled: each class's prior is n0 observations at 0 with variance 1.
  double ss = 0.0, n = 0.0;
  const double mean[2] = {clutter_mean(), target_mean()};
  for (int c = 0; c < 2; ++c) {
    ss += n0_ * (1.0 + mean[c] * mean[c]) + wuu_[c] - 2.0 * mean[c] * wu_[c] +
          w_[c] * mean[c] * mean[c];
    n += n0_ + w_[c];
  }
  return std::sqrt(std::max(ss / n, 1e-6));
}

Eigen::VectorXd ScoreModel::log_ratio(const Eigen::Ref<const Eigen::VectorXd>& u) const {
  const double m0 = clutter_mean(), m1 = target_mean(), s = sd();
  return ((u.array() - m0).square() - (u.array() - m1).square()) / (2.0 * s * s);
}

void ScoreModel::update(const Eigen::Ref<const Eigen::VectorXd>& scores,
                        const Eigen::Ref<const Eigen::VectorXd>& u,
                        const Eigen::Ref<const Eigen::VectorXd>& p_target) {
  for (int c = 0; c < 2; ++c) {
    w_[c] *= factor_;
    wu_[c] *= factor_;
    wuu_[c] *= factor_;
  }
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    const double p1 = std::clamp(p_target[j], 0.0, 1.0);
    const double p[2] = {1.0 - p1, p1};
    for (int c = 0; c < 2; ++c) {
      w_[c] += p[c];
      wu_[c] += p[c] * u[j];
      wuu_[c] += p[c] * u[j] * u[j];
    }
  }
  // The window: at most window_ of this scan's scores, evenly spread over them.
  const auto n = static_cast<std::size_t>(scores.size());
  const std::size_t take = std::min(n, static_cast<std::size_t>(window_));
  // sorted_ follows the window by one removal and one insertion per score (a scan adds a few
  // scores to a window of ~1000: cheaper than sorting it again, and the same sorted values).
  for (std::size_t i = 0; i < take; ++i) {
    const double s = scores[static_cast<Eigen::Index>(i * n / take)];
    if (recent_.size() < static_cast<std::size_t>(window_)) {
      recent_.push_back(s);
    } else {
      sorted_.erase(std::lower_bound(sorted_.begin(), sorted_.end(), recent_[next_]));
      recent_[next_] = s;
    }
    sorted_.insert(std::upper_bound(sorted_.begin(), sorted_.end(), s), s);
    next_ = (next_ + 1) % static_cast<std::size_t>(window_);
  }
}

}  // namespace vtrack::filters
