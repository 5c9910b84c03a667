#include "vtrack/apps/box_clutter.hpp"

#include <cmath>
#include <limits>

#include "vtrack/core/errors.hpp"

namespace vtrack::apps {
namespace {

// Person-like boxes relative to the image: a tenth of its height tall, 0.4 times as wide, within
// a factor e either way (log sd 1), height and width correlated -- broad enough for any camera,
// and about 30 times denser at a pedestrian's box than the uniform density over all box sizes.
filters::WeightedGaussian size_prior(int height, const filters::Forgetting& f) {
  Eigen::Vector2d mean(std::log(0.04 * height), std::log(0.1 * height));
  Eigen::Matrix2d cov;
  cov << 1.0, 0.5, 0.5, 1.0;
  return filters::WeightedGaussian(mean, cov, f.prior_weight, f.memory);
}

// Duplicates: centred on the person, a little wider, spread by 0.4 of the width sideways and 0.2
// of the height vertically, sizes within 30 % (about the ACF and Faster R-CNN figures of the
// header comment, broadened).
filters::WeightedGaussian offset_prior(const filters::Forgetting& f) {
  Eigen::Vector4d mean(0.0, 0.0, 0.2, 0.0);
  const Eigen::Vector4d sd(0.4, 0.2, 0.3, 0.3);
  return filters::WeightedGaussian(mean, sd.array().square().matrix().asDiagonal(),
                                   f.prior_weight, f.memory);
}

Eigen::MatrixXd log_sizes(const Eigen::Ref<const Eigen::MatrixXd>& z) {
  return z.bottomRows(2).array().log().matrix();
}

}  // namespace

BoxClutter::BoxClutter(int width, int height, const BoxClutterPriors& priors)
    : log_area_(std::log(static_cast<double>(width) * height)),
      duplicates_(priors.duplicate_rate > 0.0),
      rate_(priors.rate, priors.forgetting),
      duplicate_rate_(duplicates_ ? priors.duplicate_rate : 1.0, priors.forgetting),
      sizes_(size_prior(height, priors.forgetting)),
      offsets_(offset_prior(priors.forgetting)) {}

void BoxClutter::set_sources(Eigen::MatrixXd boxes, Eigen::VectorXd weights) {
  require(boxes.rows() == 4 && boxes.cols() == weights.size(), "duplicate sources",
          static_cast<double>(boxes.cols()), "4 x T boxes with T weights");
  sources_ = std::move(boxes);
  source_weights_ = std::move(weights);
}

Eigen::MatrixXd BoxClutter::offsets_of(const Eigen::Ref<const Eigen::MatrixXd>& z) const {
  const Eigen::Index T = sources_.cols(), M = z.cols();
  Eigen::MatrixXd delta(4, T * M);
  for (Eigen::Index t = 0; t < T; ++t) {
    const Eigen::Vector4d s = sources_.col(t);
    auto block = delta.middleCols(t * M, M);
    block.row(0) = (z.row(0).array() - s[0]) / s[2];
    block.row(1) = (z.row(1).array() - s[1]) / s[3];
    block.row(2) = (z.row(2).array() / s[2]).log();
    block.row(3) = (z.row(3).array() / s[3]).log();
  }
  return delta;
}

Eigen::VectorXd BoxClutter::log_intensity(const Eigen::Ref<const Eigen::MatrixXd>& z) {
  const Eigen::Index M = z.cols();
  const Eigen::MatrixXd y = log_sizes(z);
  const Eigen::ArrayXd log_wh = y.colwise().sum().transpose().array();
  // Background: lambda / (W H) N(y; m, C) / (w h).
  const Eigen::ArrayXd log_bg =
      std::log(rate_.rate()) - log_area_ + sizes_.log_density(y).array() - log_wh;
  duplicate_share_ = Eigen::VectorXd::Zero(M);
  const Eigen::Index T = duplicates_ ? sources_.cols() : 0;
  source_share_ = Eigen::MatrixXd::Zero(T, M);
  if (T == 0 || M == 0) return log_bg.matrix();
  // Duplicates: lambda_dup sum_t r_t N(delta_t; m_d, C_d) / (w_t h_t w h), in the log domain.
  const Eigen::VectorXd log_n = offsets_.log_density(offsets_of(z));
  Eigen::MatrixXd log_terms(T, M);
  for (Eigen::Index t = 0; t < T; ++t) {
    log_terms.row(t) = (log_n.segment(t * M, M).array() + std::log(source_weights_[t]) -
                        std::log(sources_(2, t) * sources_(3, t)))
                           .matrix()
                           .transpose();
  }
  Eigen::VectorXd out(M);
  const double log_rate = std::log(duplicate_rate_.rate());
  for (Eigen::Index j = 0; j < M; ++j) {
    const double hi = log_terms.col(j).maxCoeff();
    const Eigen::ArrayXd e = (log_terms.col(j).array() - hi).exp();
    const double sum = e.sum();
    source_share_.col(j) = (e / sum).matrix();
    const double log_dup = log_rate + hi + std::log(sum) - log_wh[j];
    const double top = std::max(log_dup, log_bg[j]);
    out[j] = top + std::log(std::exp(log_dup - top) + std::exp(log_bg[j] - top));
    duplicate_share_[j] = std::exp(log_dup - out[j]);
  }
  return out;
}

void BoxClutter::learn(const Eigen::Ref<const Eigen::MatrixXd>& z,
                       const Eigen::VectorXd& p_clutter) {
  const Eigen::VectorXd dup = p_clutter.cwiseProduct(duplicate_share_);
  const Eigen::VectorXd bg = p_clutter - dup;
  rate_.update(bg.sum());
  sizes_.update(log_sizes(z), bg);
  if (!duplicates_) return;
  duplicate_rate_.update(dup.sum(), source_weights_.sum());
  const Eigen::Index T = source_share_.rows(), M = z.cols();
  if (T == 0 || M == 0) return;
  Eigen::VectorXd w(T * M);
  for (Eigen::Index t = 0; t < T; ++t) {
    w.segment(t * M, M) = source_share_.row(t).transpose().cwiseProduct(dup);
  }
  offsets_.update(offsets_of(z), w);
}

Eigen::VectorXd BoxClutter::unexplained(const Eigen::VectorXd& p_clutter) const {
  return p_clutter.cwiseProduct((1.0 - duplicate_share_.array()).matrix());
}

}  // namespace vtrack::apps
