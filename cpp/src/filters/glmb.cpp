#include "vtrack/filters/glmb.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include <Eigen/Cholesky>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/filters/assign.hpp"
#include "vtrack/filters/particle_glmb.hpp"

namespace vtrack::filters {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void require_probability(double p, const char* name, bool allow_one = true) {
  if (!(p > 0.0) || p > 1.0 || (!allow_one && p == 1.0)) {
    throw InvalidArgument(std::string(name) + " must lie in (0, 1" + (allow_one ? "]" : ")") +
                          ", got " + std::to_string(p));
  }
}

}  // namespace

void GaussianTracks::log_detection_likelihoods(const Candidate& c,
                                               const Eigen::Ref<const Eigen::MatrixXd>& z,
                                               double gate,
                                               Eigen::Ref<Eigen::RowVectorXd> out) const {
  for (Eigen::Index j = 0; j < z.cols(); ++j) {
    const double d2 = c.innovation.mahalanobis_squared(z.col(j));
    out[j] = d2 <= gate ? c.innovation.log_likelihood(z.col(j)) : -kInf;
  }
}

template <class Tracks>
GlmbFilter<Tracks>::GlmbFilter(models::LinearGaussianMotion motion,
                               models::LinearGaussianObservation observation,
                               std::vector<GaussianBirth> births, GlmbParams params, Tracks tracks)
    : tracks_model_(std::move(tracks)),
      motion_(std::move(motion)),
      observation_(std::move(observation)),
      births_(std::move(births)),
      params_(params),
      ranking_rng_(params.seed) {
  const Eigen::Index x_dim = motion_.F.rows();
  if (motion_.F.cols() != x_dim || motion_.Q.rows() != x_dim || motion_.Q.cols() != x_dim) {
    throw InvalidArgument("motion model: F and Q must both be square of the state dimension");
  }
  if (observation_.H.cols() != x_dim || observation_.R.rows() != observation_.H.rows() ||
      observation_.R.cols() != observation_.H.rows()) {
    throw InvalidArgument("observation model: H must be z_dim x x_dim and R z_dim x z_dim");
  }
  require_probability(params_.survival_probability, "survival_probability");
  require_probability(params_.detection_probability, "detection_probability");
  if (!(params_.clutter_intensity > 0.0) || !std::isfinite(params_.clutter_intensity)) {
    throw InvalidArgument("clutter_intensity must be positive and finite, got " +
                          std::to_string(params_.clutter_intensity));
  }
  if (params_.hypothesis_budget <= 0) {
    throw InvalidArgument("hypothesis_budget must be > 0, got " +
                          std::to_string(params_.hypothesis_budget));
  }
  if (params_.max_hypotheses <= 0) {
    throw InvalidArgument("max_hypotheses must be > 0, got " +
                          std::to_string(params_.max_hypotheses));
  }
  if (!(params_.prune_threshold >= 0.0) || params_.prune_threshold >= 1.0) {
    throw InvalidArgument("prune_threshold must lie in [0, 1), got " +
                          std::to_string(params_.prune_threshold));
  }
  if (!(params_.gate_threshold > 0.0)) {
    throw InvalidArgument("gate_threshold must be > 0 (or +inf for no gating), got " +
                          std::to_string(params_.gate_threshold));
  }
  for (std::size_t b = 0; b < births_.size(); ++b) {
    require_probability(births_[b].existence, "birth existence");
    const auto& d = births_[b].density;
    if (d.mean.size() != x_dim || d.cov.rows() != x_dim || d.cov.cols() != x_dim) {
      throw InvalidArgument("birth component " + std::to_string(b) +
                            " has the wrong state dimension");
    }
  }
  const auto& fov = params_.field_of_view;
  if (fov.enabled) {
    if (fov.lower.size() != x_dim || fov.upper.size() != x_dim) {
      throw InvalidArgument("field_of_view lower and upper must have " + std::to_string(x_dim) +
                            " components, got " + std::to_string(fov.lower.size()) + " and " +
                            std::to_string(fov.upper.size()));
    }
    if (fov.lower.array().isNaN().any() || fov.upper.array().isNaN().any() ||
        !(fov.lower.array() <= fov.upper.array()).all()) {
      throw InvalidArgument("field_of_view needs lower <= upper in every component (no NaN)");
    }
    require_probability(fov.outside_survival_probability,
                        "field_of_view outside_survival_probability");
    require_probability(fov.outside_detection_probability,
                        "field_of_view outside_detection_probability");
  }
  const auto& adaptive = params_.adaptive_birth;
  if (adaptive.enabled) {
    if (!(adaptive.expected_births > 0.0) || !std::isfinite(adaptive.expected_births)) {
      throw InvalidArgument("adaptive_birth expected_births must be positive and finite, got " +
                            std::to_string(adaptive.expected_births));
    }
    require_probability(adaptive.max_existence, "adaptive_birth max_existence", false);
    if (adaptive.cov.rows() != x_dim || adaptive.cov.cols() != x_dim) {
      throw InvalidArgument("adaptive_birth cov must be " + std::to_string(x_dim) + "x" +
                            std::to_string(x_dim) + ", got " + std::to_string(adaptive.cov.rows()) +
                            "x" + std::to_string(adaptive.cov.cols()));
    }
  }
  hypotheses_.push_back({{}, 0.0});  // no target, probability 1
}

template <class Tracks>
void GlmbFilter<Tracks>::step(const Eigen::Ref<const Eigen::MatrixXd>& detections) {
  if (detections.rows() != observation_.H.rows() && detections.cols() > 0) {
    throw InvalidArgument("detections must have " + std::to_string(observation_.H.rows()) +
                          " rows (one detection per column), got " +
                          std::to_string(detections.rows()));
  }
  if (!detections.allFinite()) throw InvalidArgument("detections contain NaN or inf");
  ++time_;
  const int n_prior = static_cast<int>(tracks_.size());
  const int n_fixed_birth = static_cast<int>(births_.size());
  const int n_birth = n_fixed_birth + static_cast<int>(adaptive_births_.size());
  // Birth component b: the fixed ones, then those proposed by the previous scan's detections.
  auto birth = [&](int b) -> const GaussianBirth& {
    return b < n_fixed_birth ? births_[b] : adaptive_births_[b - n_fixed_birth];
  };
  auto birth_label = [&](int b) {
    return TrackLabel{time_, b < n_fixed_birth
                                 ? b
                                 : n_fixed_birth + adaptive_birth_detections_[b - n_fixed_birth]};
  };
  const int n_rows = n_prior + n_birth;
  const int n_det = static_cast<int>(detections.cols());

  // Per candidate track (surviving prior tracks, then birth components): the predicted density,
  // the log-probabilities of existing / not existing at this scan, log(p_D <p, g(z_j|.)> / kappa)
  // for every detection (-inf outside the gate), and the log missed-detection factor
  // log((1 - p_D) <p, psi_missed>) -- per row, because the switching model's missed branch
  // depends on the track (its depth likelihood). These factors are shared by all hypotheses.
  using Candidate = typename Tracks::Candidate;
  std::vector<Candidate> candidates;
  candidates.reserve(n_rows);
  Eigen::VectorXd log_exists(n_rows), log_absent(n_rows), log_missed(n_rows);
  Eigen::MatrixXd log_detected(n_rows, n_det);
  Eigen::RowVectorXd log_g(n_det);
  const FieldOfView& fov = params_.field_of_view;
  const double log_pd_over_kappa =
      std::log(params_.detection_probability) - std::log(params_.clutter_intensity);
  const double log_miss = std::log1p(-params_.detection_probability);
  // p_D(x) outside the field of view (eq. 8), used by rows whose predicted mean is outside.
  const double log_pd_over_kappa_out =
      std::log(fov.outside_detection_probability) - std::log(params_.clutter_intensity);
  const double log_miss_out = std::log1p(-fov.outside_detection_probability);
  for (int r = 0; r < n_rows; ++r) {
    const bool is_birth = r >= n_prior;
    // p_S(x) at the prior mean (eq. 6); births exist with their own probability.
    double p_exist = is_birth ? birth(r - n_prior).existence : params_.survival_probability;
    if (fov.enabled && !is_birth && !fov.contains(Tracks::moments(tracks_[r].density).mean)) {
      p_exist = fov.outside_survival_probability;
    }
    Density predicted = is_birth ? tracks_model_.birth(birth(r - n_prior).density)
                                 : tracks_model_.predict(tracks_[r].density, motion_);
    // p_D(x) at the predicted mean (eq. 8).
    const bool detectable = !fov.enabled || fov.contains(Tracks::moments(predicted).mean);
    candidates.push_back(tracks_model_.candidate(std::move(predicted), observation_, is_birth));
    log_exists[r] = std::log(p_exist);
    log_absent[r] = std::log1p(-p_exist);
    log_missed[r] = (detectable ? log_miss : log_miss_out) +
                    tracks_model_.log_missed_likelihood(candidates.back());
    tracks_model_.log_detection_likelihoods(candidates.back(), detections,
                                            params_.gate_threshold, log_g);
    const double log_pd_k = detectable ? log_pd_over_kappa : log_pd_over_kappa_out;
    for (int j = 0; j < n_det; ++j) {
      log_detected(r, j) = log_g[j] > -kInf ? log_pd_k + log_g[j] : -kInf;
    }
  }

  // Requested solutions per prior hypothesis, proportional to sqrt(weight).
  Eigen::VectorXd sqrt_w(hypotheses_.size());
  for (std::size_t h = 0; h < hypotheses_.size(); ++h) {
    sqrt_w[h] = std::exp(0.5 * hypotheses_[h].log_weight);
  }
  const double sqrt_total = sqrt_w.sum();

  std::vector<Track> children;
  std::vector<int> child_detection;  // the detection each child took, -1 if missed
  std::map<std::pair<int, int>, int> child_of;  // (candidate row, detection or -1) -> child
  auto child_index = [&](int row, int detection) {
    const auto key = std::make_pair(row, detection);
    const auto found = child_of.find(key);
    if (found != child_of.end()) return found->second;
    Track child;
    child.label = row < n_prior ? tracks_[row].label : birth_label(row - n_prior);
    child.density = detection < 0
                        ? tracks_model_.missed(candidates[row])
                        : tracks_model_.detected(candidates[row], detections.col(detection));
    children.push_back(std::move(child));
    child_detection.push_back(detection);
    child_of.emplace(key, static_cast<int>(children.size()) - 1);
    return static_cast<int>(children.size()) - 1;
  };

  std::map<std::vector<int>, double> posterior;  // track set -> log weight (unnormalised)
  auto add_hypothesis = [&](std::vector<int> tracks, double log_weight) {
    std::sort(tracks.begin(), tracks.end());
    auto [it, inserted] = posterior.emplace(std::move(tracks), log_weight);
    if (!inserted) {  // the same track histories reached from two parents: weights add
      const double hi = std::max(it->second, log_weight);
      it->second = hi + std::log(std::exp(it->second - hi) + std::exp(log_weight - hi));
    }
  };

  std::vector<int> rows, columns;
  for (std::size_t h = 0; h < hypotheses_.size(); ++h) {
    const auto requested =
        static_cast<std::int64_t>(std::round(params_.hypothesis_budget * sqrt_w[h] / sqrt_total));
    if (requested < 1) continue;
    rows.assign(hypotheses_[h].tracks.begin(), hypotheses_[h].tracks.end());
    for (int b = 0; b < n_birth; ++b) rows.push_back(n_prior + b);
    const int n = static_cast<int>(rows.size());
    if (n == 0) {
      add_hypothesis({}, hypotheses_[h].log_weight);
      continue;
    }
    // Only detections some row can take enter the matrix.
    columns.clear();
    for (int j = 0; j < n_det; ++j) {
      for (int r : rows) {
        if (log_detected(r, j) > -kInf) {
          columns.push_back(j);
          break;
        }
      }
    }
    const int m = static_cast<int>(columns.size());
    // Cost = -log of the factor each choice contributes to the posterior weight:
    //   detection j:      p_exist p_D g(z_j|x) / kappa
    //   missed (col m+i): p_exist (1 - p_D) <p, psi_missed>
    //   absent (m+n+i):   1 - p_exist (died, or not born)
    Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(n, m + 2 * n, kInf);
    for (int i = 0; i < n; ++i) {
      const int r = rows[i];
      for (int c = 0; c < m; ++c) cost(i, c) = -(log_exists[r] + log_detected(r, columns[c]));
      cost(i, m + i) = -(log_exists[r] + log_missed[r]);
      cost(i, m + n + i) = -log_absent[r];
    }
    const RankedChoices ranked = rank(cost, requested);
    std::vector<int> tracks;
    for (Eigen::Index s = 0; s < ranked.costs.size(); ++s) {
      tracks.clear();
      for (int i = 0; i < n; ++i) {
        const auto col = static_cast<int>(ranked.assignments(s, i));
        if (col < m) {
          tracks.push_back(child_index(rows[i], columns[col]));
        } else if (col < m + n) {
          tracks.push_back(child_index(rows[i], -1));
        }
      }
      add_hypothesis(tracks, hypotheses_[h].log_weight - ranked.costs[s]);
    }
  }

  // Normalise, prune, cap.
  std::vector<Hypothesis> updated;
  updated.reserve(posterior.size());
  for (auto& [tracks, log_weight] : posterior) updated.push_back({tracks, log_weight});
  if (updated.empty()) {
    // Every hypothesis was infeasible (e.g. p_D = p_S = 1 with fewer detections than tracks):
    // the data contradict the model, so restart from "no targets" rather than produce NaN.
    tracks_.clear();
    hypotheses_.assign(1, {{}, 0.0});
    propose_adaptive_births(detections, Eigen::VectorXd::Zero(n_det));
    return;
  }
  auto normalise = [](std::vector<Hypothesis>& hs) {
    Eigen::VectorXd lw(static_cast<Eigen::Index>(hs.size()));
    for (std::size_t i = 0; i < hs.size(); ++i) lw[static_cast<Eigen::Index>(i)] = hs[i].log_weight;
    const double total = core::log_sum_exp(lw);
    for (auto& h : hs) h.log_weight -= total;
  };
  normalise(updated);
  std::sort(updated.begin(), updated.end(),
            [](const Hypothesis& a, const Hypothesis& b) { return a.log_weight > b.log_weight; });
  const double log_prune = std::log(params_.prune_threshold);
  std::size_t keep = 1;  // the best hypothesis always survives
  while (keep < updated.size() && keep < static_cast<std::size_t>(params_.max_hypotheses) &&
         updated[keep].log_weight >= log_prune) {
    ++keep;
  }
  updated.resize(keep);
  normalise(updated);

  if (params_.adaptive_birth.enabled) {
    // r_U(z_j): the posterior probability that detection j was assigned to a track.
    Eigen::VectorXd assigned = Eigen::VectorXd::Zero(n_det);
    for (const auto& h : updated) {
      for (int t : h.tracks) {
        if (child_detection[t] >= 0) assigned[child_detection[t]] += std::exp(h.log_weight);
      }
    }
    propose_adaptive_births(detections, assigned);
  }

  // Keep only the tracks some hypothesis still uses, renumbered in order.
  std::vector<int> new_index(children.size(), -1);
  tracks_.clear();
  for (auto& h : updated) {
    for (int& t : h.tracks) {
      if (new_index[t] < 0) {
        new_index[t] = static_cast<int>(tracks_.size());
        tracks_.push_back(std::move(children[t]));
      }
      t = new_index[t];
    }
    std::sort(h.tracks.begin(), h.tracks.end());
  }
  hypotheses_ = std::move(updated);
}

template <class Tracks>
typename GlmbFilter<Tracks>::RankedChoices GlmbFilter<Tracks>::rank(const Eigen::MatrixXd& cost,
                                                                    std::int64_t requested) {
  if (params_.ranking == HypothesisRanking::gibbs) {
    assign::SampledAssignments s = assign::gibbs_assignments(cost, requested, ranking_rng_);
    return {std::move(s.assignments), std::move(s.costs)};
  }
  assign::RankedAssignments r = assign::murty(cost, requested);
  return {std::move(r.assignments), std::move(r.costs)};
}

template <class Tracks>
void GlmbFilter<Tracks>::propose_adaptive_births(
    const Eigen::Ref<const Eigen::MatrixXd>& detections, const Eigen::VectorXd& assigned) {
  adaptive_births_.clear();
  adaptive_birth_detections_.clear();
  const auto& adaptive = params_.adaptive_birth;
  if (!adaptive.enabled || detections.cols() == 0) return;
  const Eigen::VectorXd unassigned = (1.0 - assigned.array()).max(0.0).matrix();
  const double total = unassigned.sum();
  if (!(total > 0.0)) return;
  // H^+ = H^T (H H^T)^-1 maps a detection to the least-norm state that predicts it.
  const Eigen::MatrixXd& H = observation_.H;
  const Eigen::LDLT<Eigen::MatrixXd> HHt(H * H.transpose());
  for (Eigen::Index j = 0; j < detections.cols(); ++j) {
    const double r =
        std::min(adaptive.max_existence, adaptive.expected_births * unassigned[j] / total);
    // A detection that tracks explain almost surely would only add a row that stays absent.
    if (r < 1e-12) continue;
    adaptive_births_.push_back(
        {r, {H.transpose() * HHt.solve(Eigen::VectorXd(detections.col(j))), adaptive.cov}});
    adaptive_birth_detections_.push_back(static_cast<int>(j));
  }
}

template <class Tracks>
Eigen::VectorXd GlmbFilter<Tracks>::cardinality_distribution() const {
  std::size_t largest = 0;
  for (const auto& h : hypotheses_) largest = std::max(largest, h.tracks.size());
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(largest) + 1);
  for (const auto& h : hypotheses_) {
    p[static_cast<Eigen::Index>(h.tracks.size())] += std::exp(h.log_weight);
  }
  return p;
}

template <class Tracks>
int GlmbFilter<Tracks>::map_cardinality() const {
  Eigen::Index n = 0;
  cardinality_distribution().maxCoeff(&n);
  return static_cast<int>(n);
}

template <class Tracks>
std::vector<GlmbEstimate> GlmbFilter<Tracks>::estimates() const {
  const std::size_t n = static_cast<std::size_t>(map_cardinality());
  const Hypothesis* best = nullptr;
  for (const auto& h : hypotheses_) {
    if (h.tracks.size() == n && (!best || h.log_weight > best->log_weight)) best = &h;
  }
  std::vector<GlmbEstimate> out;
  if (!best) return out;
  for (int t : best->tracks) {
    models::GaussianDensity m = Tracks::moments(tracks_[t].density);
    out.push_back({tracks_[t].label, std::move(m.mean), std::move(m.cov)});
  }
  return out;
}

template class GlmbFilter<GaussianTracks>;
template class GlmbFilter<ParticleTracks>;

}  // namespace vtrack::filters
