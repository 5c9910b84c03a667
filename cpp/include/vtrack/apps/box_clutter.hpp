#pragma once
// The false boxes of a people detector, as a clutter intensity over box measurements
// z = (cx, cy, w, h), learnt online from the GLMB posterior (filters/detector_learning.hpp):
//
//   kappa(z) = kappa_bg(z) + kappa_dup(z)
//   kappa_bg(z)  = lambda_bg / (W H) * N((log w, log h); m_s, C_s) / (w h)
//   kappa_dup(z) = lambda_dup * sum_t r_t N(delta_t(z); m_d, C_d) / (w_t h_t w h),
//   delta_t(z)   = ((cx - cx_t) / w_t, (cy - cy_t) / h_t, log(w / w_t), log(h / h_t)).
//
// The background part is Poisson clutter centred uniformly in the image with a log-normal density
// over box sizes: a detector's false boxes are person-sized, so a density spread uniformly over
// all sizes up to the image (the former model) was 59-817 times too low at a false box and every
// false box started a track (benchmarks/detections_sim.py). The duplicate part is what real
// detectors add (measured on PETS09 frames 1-397, benchmarks/detections.py): 0.28 (ACF), 0.15
// (Faster R-CNN), 0.06 (HOG) extra boxes per person and frame, shifted by about 0.4 of the
// person's width and wider -- a Poisson number of extra boxes around each track t of the previous
// estimate (r_t its existence, (cx_t, cy_t, w_t, h_t) its box moved on by its velocity), with a
// Gaussian density of the box-relative offset delta. Treating them as target-dependent clutter
// (evaluated at the previous estimate, which keeps the GLMB update in closed form) stops them
// from starting duplicate tracks; the one-detection-per-target model would explain each by a new
// target.
//
// Learning (EM with the GLMB update as the E step): each detection's clutter probability
// P(clutter_j) = 1 - P(j assigned to a track) is split between the two parts in proportion to
// kappa_bg and kappa_dup at z_j; lambda_bg and the size density learn from the background share,
// lambda_dup (per unit of sum_t r_t) and the offset density from the duplicate share (each
// track's part in proportion to its term).
#include <Eigen/Core>

#include "vtrack/filters/detector_learning.hpp"

namespace vtrack::apps {

struct BoxClutterPriors {
  double rate = 1.0;            // lambda_bg, false boxes per frame
  double duplicate_rate = 0.1;  // lambda_dup, extra boxes per person and frame (0: no duplicates)
  filters::Forgetting forgetting;
};

class BoxClutter {
 public:
  BoxClutter(int width, int height, const BoxClutterPriors& priors);

  // The sources of duplicates at the coming scan: boxes (cx, cy, w, h) as columns and their
  // weights r_t.
  void set_sources(Eigen::MatrixXd boxes, Eigen::VectorXd weights);
  // log kappa(z_j) for the columns of z (4 x M); remembers each one's duplicate share for learn().
  Eigen::VectorXd log_intensity(const Eigen::Ref<const Eigen::MatrixXd>& z);
  // One EM step from the scan's P(clutter_j) (the z of the last log_intensity call).
  void learn(const Eigen::Ref<const Eigen::MatrixXd>& z, const Eigen::VectorXd& p_clutter);
  // P(clutter_j) times the background share: the probability that z_j is explained neither by a
  // track nor as one's duplicate.
  Eigen::VectorXd unexplained(const Eigen::VectorXd& p_clutter) const;

  double rate() const { return rate_.rate(); }
  double duplicate_rate() const { return duplicates_ ? duplicate_rate_.rate() : 0.0; }
  const filters::WeightedGaussian& sizes() const { return sizes_; }
  const filters::WeightedGaussian& offsets() const { return offsets_; }

 private:
  // delta_t(z_j) of every (source, detection) pair: 4 x (T M), source-major.
  Eigen::MatrixXd offsets_of(const Eigen::Ref<const Eigen::MatrixXd>& z) const;

  double log_area_;
  bool duplicates_;
  filters::ClutterRate rate_, duplicate_rate_;
  filters::WeightedGaussian sizes_, offsets_;
  Eigen::MatrixXd sources_;
  Eigen::VectorXd source_weights_;
  // From the last log_intensity call: per detection, kappa_dup / kappa; per (source, detection),
  // that source's share of kappa_dup.
  Eigen::VectorXd duplicate_share_;
  Eigen::MatrixXd source_share_;  // T x M
};

}  // namespace vtrack::apps
