#pragma once
// Online estimates of what a detector does -- its clutter rate, its detection probability, how its
// scores differ between people and false boxes, where its false boxes fall -- learnt jointly with
// the tracks from the GLMB filter's own posterior (filters/glmb.hpp ScanSummary), so that a
// tracker needs no per-scene clutter or p_D.
//
// Every estimate is the posterior of a conjugate model whose data are the filter's soft
// association counts, with exponential forgetting (factor f = 1 - 1/memory per scan, so about
// the last `memory` scans count) and a prior that is never forgotten (worth `prior_weight` scans
// of data): with hard counts these are the textbook Gamma-Poisson and Beta-Binomial posteriors;
// with the posterior's expected counts each scan is one EM step of the joint estimate (the E step
// is the GLMB update that produced the counts). This is the "simpler estimator" alternative to
// the robust GLMB of Vo, Vo, Hoseinnezhad & Mahler (2013), whose clutter-generator model needs a
// second labelled population and its own assignment columns; measured against a two-pass
// estimate in benchmarks/detections_sim.py's docstring, and why a two-pass estimate fails on a
// real detector: a tracker's output explains most false boxes by tracks, the posterior does not.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace vtrack::filters {

// Forgetting with a permanent prior: estimate = (prior_weight * prior + data) / (prior_weight +
// weight of data), the data decayed by f = 1 - 1/memory each scan.
struct Forgetting {
  double memory = 100.0;       // scans (>= 1)
  double prior_weight = 10.0;  // scans (> 0)
  double factor() const { return 1.0 - 1.0 / memory; }
};

// A Poisson rate lambda per unit of exposure (per scan: expected false detections per scan;
// per track and scan: a detector's duplicate boxes per person), Gamma prior: each scan adds the
// expected count the posterior attributes to the process, e.g. sum_j P(j is clutter), and the
// exposure (1 scan; the expected number of tracks).
class ClutterRate {
 public:
  ClutterRate(double prior_rate, Forgetting forgetting);
  void update(double expected_count, double exposure = 1.0);
  double rate() const;

 private:
  double prior_rate_;
  Forgetting forgetting_;
  double count_ = 0.0, scans_ = 0.0;
};

// p_D, Beta prior: each scan adds the expected number of detectable tracks that were detected and
// that were missed (ScanSummary::detected, missed). Kept within [lower, upper].
class DetectionProbability {
 public:
  DetectionProbability(double prior, double lower, double upper, Forgetting forgetting);
  void update(double detected, double missed);
  double probability() const;

 private:
  double prior_, lower_, upper_;
  Forgetting forgetting_;
  double detected_ = 0.0, missed_ = 0.0;
};

// A Gaussian density over a feature vector y (d-dimensional), learnt from weighted observations
// with forgetting and a Normal-Wishart-like prior (mean m0, covariance C0, worth prior_weight
// observations): mean = (n0 m0 + sum w y) / (n0 + sum w), covariance likewise about it (pooled
// second moments). Used for the clutter's box sizes (log width, log height) by the box tracker.
class WeightedGaussian {
 public:
  WeightedGaussian(Eigen::VectorXd prior_mean, Eigen::MatrixXd prior_cov, double prior_weight,
                   double memory);
  // Decays the data by f, then adds the observations (columns of y) with weights w.
  void update(const Eigen::Ref<const Eigen::MatrixXd>& y,
              const Eigen::Ref<const Eigen::VectorXd>& w);
  // log N(y; mean, cov) for every column of y.
  Eigen::VectorXd log_density(const Eigen::Ref<const Eigen::MatrixXd>& y) const;
  Eigen::VectorXd mean() const;
  Eigen::MatrixXd covariance() const;

 private:
  Eigen::VectorXd m0_;
  Eigen::MatrixXd c0_;
  double n0_, factor_;
  double weight_ = 0.0;
  Eigen::VectorXd sum_;
  Eigen::MatrixXd sum_sq_;
};

// A detection score as a likelihood ratio: the score s is a feature with density f1 under a target
// and f0 under clutter, so a detection's target-vs-clutter ratio g(z|x) / kappa(z) is multiplied
// by f1(s) / f0(s) (the "amplitude" or feature-aided likelihood of radar tracking). Scores come
// on any monotone scale (probabilities, SVM margins, ACF's unbounded sums), so each is first
// mapped to u = Phi^-1(F(s)), F the empirical distribution of the last `window` scores (mid-ranks
// for ties): u is standard normal over all detections whatever the detector. Under target and
// clutter u is modelled as N(mu1, sigma^2) and N(mu0, sigma^2) (pooled variance: the log ratio is
// linear, hence monotone, in u), learnt from the posterior's soft labels P(target) and
// P(clutter) with forgetting and a prior of prior_weight observations at mu = 0, sigma = 1 for
// each class, so the ratio starts at 1 and moves only as far as the evidence does.
//
// Degrades to a ratio of exactly 1 when every score is equal or missing (all u = 0, both means
// stay 0): the tracker then behaves as without scores.
class ScoreModel {
 public:
  ScoreModel(int window, double prior_weight, double memory);
  // u for each score, from the scores seen before this call.
  Eigen::VectorXd transform(const Eigen::Ref<const Eigen::VectorXd>& scores) const;
  // log f1(u) / f0(u) for each u.
  Eigen::VectorXd log_ratio(const Eigen::Ref<const Eigen::VectorXd>& u) const;
  // Adds one scan's detections: their u, P(target) and P(clutter) (= 1 - P(target)), and their
  // raw scores to the window (at most `window` of them: a scan with more adds an even spread).
  void update(const Eigen::Ref<const Eigen::VectorXd>& scores,
              const Eigen::Ref<const Eigen::VectorXd>& u,
              const Eigen::Ref<const Eigen::VectorXd>& p_target);
  double target_mean() const;
  double clutter_mean() const;
  double sd() const;

 private:
  int window_;
  double n0_, factor_;
  std::vector<double> recent_;  // ring buffer of raw scores
  std::size_t next_ = 0;
  std::vector<double> sorted_;  // recent_, sorted
  // Per class (0 clutter, 1 target): sum of weights, of w u, of w u^2.
  double w_[2] = {0, 0}, wu_[2] = {0, 0}, wuu_[2] = {0, 0};
};

}  // namespace vtrack::filters
