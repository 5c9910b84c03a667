#pragma once
// Member definitions of GlmbFilter<Tracks> (filters/glmb.hpp). Included only by the translation
// units that instantiate the filter for a track-density policy (glmb.cpp: GaussianTracks,
// particle_glmb.cpp: ParticleTracks), so a new policy is added without editing either.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <Eigen/Cholesky>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"
#include "vtrack/core/weights.hpp"
#include "vtrack/filters/assign.hpp"
#include "vtrack/filters/glmb.hpp"

namespace vtrack::filters {

namespace detail {
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace detail

template <class Tracks>
GlmbFilter<Tracks>::GlmbFilter(models::LinearGaussianMotion motion,
                               models::LinearGaussianObservation observation,
                               std::vector<GaussianBirth> births, GlmbParams params, Tracks tracks)
    : tracks_model_(std::move(tracks)),
      motion_(std::move(motion)),
      observation_(std::move(observation)),
      births_(std::move(births)),
      params_(std::move(params)),
      ranking_rng_(params_.seed) {
  validate(params_);
  check_glmb_dimensions(motion_, observation_, births_, params_);
  hypotheses_.push_back({{}, 0.0});  // no target, probability 1
}

template <class Tracks>
void GlmbFilter<Tracks>::set_detection_probability(double p_d) {
  require(p_d > 0.0 && p_d <= 1.0, "detection_probability", p_d, "in (0, 1]");
  params_.detection_probability = p_d;
  tracks_model_.set_detection_probability(p_d);
}

template <class Tracks>
void GlmbFilter<Tracks>::step(const Eigen::Ref<const Eigen::MatrixXd>& detections,
                              const ScanInput& input) {
  if (detections.rows() != observation_.H.rows() && detections.cols() > 0) {
    throw InvalidArgument("detections must have " + std::to_string(observation_.H.rows()) +
                          " rows (one detection per column), got " +
                          std::to_string(detections.rows()));
  }
  if (!detections.allFinite()) throw InvalidArgument("detections contain NaN or inf");
  const auto n_det = static_cast<Eigen::Index>(detections.cols());
  for (const auto* v : {&input.log_clutter, &input.birth_weight}) {
    if (v->size() != 0 && v->size() != n_det) {
      throw InvalidArgument("ScanInput vectors must have one entry per detection (" +
                            std::to_string(n_det) + "), got " + std::to_string(v->size()));
    }
  }
  if (input.log_clutter.size() > 0 && input.log_clutter.array().isNaN().any()) {
    throw InvalidArgument("ScanInput log_clutter contains NaN");
  }
  if (input.birth_weight.size() > 0 &&
      !(input.birth_weight.array() >= 0.0 && input.birth_weight.array() < detail::kInfinity)
           .all()) {
    throw InvalidArgument("ScanInput birth_weight must be finite and >= 0");
  }
  ++time_;
  const ScanFactors factors = score_candidates(detections, input);
  Posterior posterior = rank_hypotheses(factors, detections);
  const Eigen::VectorXd weight =
      input.birth_weight.size() > 0 ? input.birth_weight : Eigen::VectorXd::Ones(n_det);
  if (posterior.weights.empty()) {
    // Every hypothesis was infeasible (e.g. p_D = p_S = 1 with fewer detections than tracks):
    // the data contradict the model, so restart from "no targets" rather than produce NaN.
    tracks_.clear();
    hypotheses_.assign(1, {{}, 0.0});
    summary_ = ScanSummary{Eigen::VectorXd::Zero(n_det), Eigen::VectorXd::Zero(n_det), 0.0, 0.0,
                           Eigen::VectorXd::Zero(n_det)};
    propose_adaptive_births(detections, Eigen::VectorXd::Zero(n_det), weight);
    estimate();
    return;
  }
  std::vector<Hypothesis> updated = normalise_and_prune(posterior);
  summarise(updated, factors, posterior, n_det);
  // r_U(z_j): the posterior probability that detection j was assigned to a track, or (with
  // missed_tracks) lies on a track that was missed.
  Eigen::VectorXd explained = summary_.to_track + summary_.to_birth;
  if (params_.adaptive_birth.enabled && params_.adaptive_birth.missed_tracks) {
    explained += missed_explanations(updated, factors, posterior, detections);
  }
  propose_adaptive_births(detections, explained, weight);
  summary_.explained = params_.adaptive_birth.enabled ? explained : Eigen::VectorXd::Zero(n_det);
  keep_used_tracks(std::move(updated), posterior);
  estimate();
}

template <class Tracks>
typename GlmbFilter<Tracks>::ScanFactors GlmbFilter<Tracks>::score_candidates(
    const Eigen::Ref<const Eigen::MatrixXd>& detections, const ScanInput& input) {
  // Per candidate track (surviving prior tracks, then birth components): the predicted density,
  // the log-probabilities of existing / not existing at this scan, log(p_D <p, g(z_j|.)> / kappa)
  // for every detection (-inf outside the gate), and the log missed-detection factor
  // log((1 - p_D) <p, psi_missed>) -- per row, because the switching model's missed branch
  // depends on the track (its depth likelihood). These factors are shared by all hypotheses.
  const int n_prior = static_cast<int>(tracks_.size());
  const int n_fixed = static_cast<int>(births_.size());
  const int n_rows = n_prior + n_fixed + static_cast<int>(adaptive_births_.size());
  const int n_det = static_cast<int>(detections.cols());
  ScanFactors f;
  f.candidates.reserve(n_rows);
  f.log_exists.resize(n_rows);
  f.log_absent.resize(n_rows);
  f.log_missed.resize(n_rows);
  f.log_pd.resize(n_rows);
  f.missed_undetectable.resize(n_rows);
  f.missed_detectable.resize(n_rows);
  f.log_detected.resize(n_rows, n_det);
  Eigen::RowVectorXd log_g(n_det);
  const FieldOfView& fov = params_.field_of_view;
  f.log_kappa = input.log_clutter.size() > 0
                    ? Eigen::RowVectorXd(input.log_clutter.transpose())
                    : Eigen::RowVectorXd::Constant(n_det, std::log(params_.clutter_intensity));
  const Eigen::RowVectorXd& log_kappa = f.log_kappa;
  const double stay_hidden = 1.0 - 1.0 / params_.occlusion.length;
  for (int r = 0; r < n_rows; ++r) {
    const bool is_birth = r >= n_prior;
    const int b = r - n_prior;  // birth component: the fixed ones, then the adaptive ones
    const GaussianBirth* birth =
        !is_birth ? nullptr : b < n_fixed ? &births_[b] : &adaptive_births_[b - n_fixed];
    f.labels.push_back(!is_birth     ? tracks_[r].label
                       : b < n_fixed ? TrackLabel{time_, b}
                                     : TrackLabel{time_, n_fixed + adaptive_birth_detections_[b - n_fixed]});
    // p_S(x) at the prior mean (eq. 6); births exist with their own probability.
    double p_exist = is_birth ? birth->existence : params_.survival_probability;
    if (fov.enabled && !is_birth && !fov.contains(Tracks::moments(tracks_[r].density).mean)) {
      p_exist = fov.outside_survival_probability;
    }
    Density predicted = is_birth ? tracks_model_.birth(birth->density)
                                 : tracks_model_.predict(tracks_[r].density, motion_);
    // p_D(x) at the predicted mean (eq. 8), times P(detectable) of the visibility mode.
    const bool detectable = !fov.enabled || fov.contains(Tracks::moments(predicted).mean);
    const double p_d = detectable ? params_.detection_probability
                                  : fov.outside_detection_probability;
    const double o = is_birth || tracks_[r].misses >= params_.occlusion.max_length
                         ? 0.0
                         : tracks_[r].undetectable * stay_hidden +
                               (1.0 - tracks_[r].undetectable) * params_.occlusion.rate;
    const double miss = o + (1.0 - o) * (1.0 - p_d);
    f.missed_undetectable[r] = miss > 0.0 ? o / miss : 0.0;
    f.missed_detectable[r] = is_birth || !detectable ? -1.0 : 1.0 - f.missed_undetectable[r];
    f.candidates.push_back(tracks_model_.candidate(std::move(predicted), observation_,
                                                   f.labels.back(), is_birth));
    f.log_pd[r] = std::log(p_d);
    f.log_exists[r] = std::log(p_exist);
    f.log_absent[r] = std::log1p(-p_exist);
    f.log_missed[r] = std::log(miss) + tracks_model_.log_missed_likelihood(f.candidates.back());
    tracks_model_.log_detection_likelihoods(f.candidates.back(), detections,
                                            params_.gate_threshold, log_g);
    const double log_pd = std::log(p_d * (1.0 - o));
    for (int j = 0; j < n_det; ++j) {
      f.log_detected(r, j) =
          log_g[j] > -detail::kInfinity ? log_pd - log_kappa[j] + log_g[j] : -detail::kInfinity;
    }
  }
  cap_gates(f.log_detected);
  return f;
}

template <class Tracks>
void GlmbFilter<Tracks>::cap_gates(Eigen::MatrixXd& log_detected) const {
  const auto cap = static_cast<Eigen::Index>(params_.gate_max_detections);
  if (log_detected.cols() <= cap) return;
  std::vector<double> gated;
  for (Eigen::Index r = 0; r < log_detected.rows(); ++r) {
    gated.clear();
    for (Eigen::Index j = 0; j < log_detected.cols(); ++j) {
      if (log_detected(r, j) > -detail::kInfinity) gated.push_back(log_detected(r, j));
    }
    if (static_cast<Eigen::Index>(gated.size()) <= cap) continue;
    // The cap-th largest factor; ties at it are all kept (a cap that is exceeded by ties only).
    std::nth_element(gated.begin(), gated.begin() + (cap - 1), gated.end(), std::greater<>());
    const double threshold = gated[static_cast<std::size_t>(cap - 1)];
    for (Eigen::Index j = 0; j < log_detected.cols(); ++j) {
      if (log_detected(r, j) < threshold) log_detected(r, j) = -detail::kInfinity;
    }
  }
}

template <class Tracks>
int GlmbFilter<Tracks>::child_index(const ScanFactors& factors, Posterior& posterior, int row,
                                    int detection,
                                    const Eigen::Ref<const Eigen::MatrixXd>& detections) {
  const auto key = std::make_pair(row, detection);
  const auto found = posterior.child_of.find(key);
  if (found != posterior.child_of.end()) return found->second;
  Track child;
  child.label = factors.labels[row];
  child.density = detection < 0
                      ? tracks_model_.missed(factors.candidates[row])
                      : tracks_model_.detected(factors.candidates[row], detections.col(detection));
  child.undetectable = detection < 0 ? factors.missed_undetectable[row] : 0.0;
  const int n_prior = static_cast<int>(tracks_.size());
  child.misses = detection >= 0 ? 0 : row < n_prior ? tracks_[row].misses + 1 : 1;
  posterior.children.push_back(std::move(child));
  posterior.child_detection.push_back(detection);
  posterior.child_row.push_back(row);
  const int index = static_cast<int>(posterior.children.size()) - 1;
  posterior.child_of.emplace(key, index);
  return index;
}

template <class Tracks>
Eigen::MatrixXd GlmbFilter<Tracks>::cost_matrix(const ScanFactors& f, const std::vector<int>& rows,
                                                std::vector<int>& columns) const {
  constexpr double kInf = detail::kInfinity;
  // Only detections some row can take enter the matrix.
  columns.clear();
  for (Eigen::Index j = 0; j < f.log_detected.cols(); ++j) {
    for (int r : rows) {
      if (f.log_detected(r, j) > -kInf) {
        columns.push_back(static_cast<int>(j));
        break;
      }
    }
  }
  const int n = static_cast<int>(rows.size());
  const int m = static_cast<int>(columns.size());
  // Cost = -log of the factor each choice contributes to the posterior weight:
  //   detection j:      p_exist p_D g(z_j|x) / kappa
  //   missed (col m+i): p_exist (1 - p_D) <p, psi_missed>
  //   absent (m+n+i):   1 - p_exist (died, or not born)
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(n, m + 2 * n, kInf);
  for (int i = 0; i < n; ++i) {
    const int r = rows[i];
    for (int c = 0; c < m; ++c) cost(i, c) = -(f.log_exists[r] + f.log_detected(r, columns[c]));
    cost(i, m + i) = -(f.log_exists[r] + f.log_missed[r]);
    cost(i, m + n + i) = -f.log_absent[r];
  }
  return cost;
}

template <class Tracks>
typename GlmbFilter<Tracks>::Posterior GlmbFilter<Tracks>::rank_hypotheses(
    const ScanFactors& factors, const Eigen::Ref<const Eigen::MatrixXd>& detections) {
  const int n_prior = static_cast<int>(tracks_.size());
  const int n_birth = static_cast<int>(factors.candidates.size()) - n_prior;
  // Requested solutions per prior hypothesis, proportional to sqrt(weight).
  Eigen::VectorXd sqrt_w(hypotheses_.size());
  for (std::size_t h = 0; h < hypotheses_.size(); ++h) {
    sqrt_w[h] = std::exp(0.5 * hypotheses_[h].log_weight);
  }
  const double sqrt_total = sqrt_w.sum();
  Posterior posterior;
  auto add_hypothesis = [&](std::vector<int> tracks, double log_weight) {
    std::sort(tracks.begin(), tracks.end());
    auto [it, inserted] = posterior.weights.emplace(std::move(tracks), log_weight);
    if (!inserted) {  // the same track histories reached from two parents: weights add
      const double hi = std::max(it->second, log_weight);
      it->second = hi + std::log(std::exp(it->second - hi) + std::exp(log_weight - hi));
    }
  };
  const bool pooled = params_.ranking == HypothesisRanking::murty;
  if (pooled) pool_rows(factors);
  std::vector<int> rows, columns, tracks;
  // The posterior hypotheses of one ranking, each row's choice coded as a detection j >= 0, -1
  // missed or -2 absent (assign::PooledMurty's codes).
  auto add_ranked = [&](const auto& assignments, const Eigen::VectorXd& costs, double log_weight,
                        auto code_of) {
    for (Eigen::Index s = 0; s < costs.size(); ++s) {
      tracks.clear();
      for (std::size_t i = 0; i < rows.size(); ++i) {
        const int code = code_of(assignments(s, static_cast<Eigen::Index>(i)));
        if (code >= -1) tracks.push_back(child_index(factors, posterior, rows[i], code, detections));
      }
      add_hypothesis(tracks, log_weight - costs[s]);
    }
  };
  for (std::size_t h = 0; h < hypotheses_.size(); ++h) {
    core::poll_interrupt();  // a step with a large budget can take seconds
    const auto requested =
        static_cast<std::int64_t>(std::round(params_.hypothesis_budget * sqrt_w[h] / sqrt_total));
    if (requested < 1) continue;
    rows.assign(hypotheses_[h].tracks.begin(), hypotheses_[h].tracks.end());
    for (int b = 0; b < n_birth; ++b) rows.push_back(n_prior + b);
    if (rows.empty()) {
      add_hypothesis({}, hypotheses_[h].log_weight);
      continue;
    }
    if (pooled) {
      const assign::RankedAssignments& ranked = ranking_pool_.rank(rows, requested);
      add_ranked(ranked.assignments, ranked.costs, hypotheses_[h].log_weight,
                 [](std::int64_t code) { return static_cast<int>(code); });
      continue;
    }
    const Eigen::MatrixXd cost = cost_matrix(factors, rows, columns);
    const int n = static_cast<int>(rows.size());
    const int m = static_cast<int>(columns.size());
    const RankedChoices ranked = rank(cost, requested);
    add_ranked(ranked.assignments, ranked.costs, hypotheses_[h].log_weight,
               [&](std::int64_t col) {
                 return col < m ? columns[static_cast<std::size_t>(col)] : col < m + n ? -1 : -2;
               });
  }
  return posterior;
}

template <class Tracks>
void GlmbFilter<Tracks>::pool_rows(const ScanFactors& f) {
  const Eigen::Index n_det = f.log_detected.cols();
  ranking_pool_.reset(static_cast<int>(n_det), 2);
  std::vector<int> cols;
  std::vector<double> costs;
  for (Eigen::Index r = 0; r < f.log_detected.rows(); ++r) {
    cols.clear();
    costs.clear();
    for (Eigen::Index j = 0; j < n_det; ++j) {
      if (!(f.log_detected(r, j) > -detail::kInfinity)) continue;
      cols.push_back(static_cast<int>(j));
      costs.push_back(-(f.log_exists[r] + f.log_detected(r, j)));
    }
    const double own[2] = {-(f.log_exists[r] + f.log_missed[r]), -f.log_absent[r]};
    ranking_pool_.add_row(cols.data(), costs.data(), static_cast<int>(cols.size()), own);
  }
}

template <class Tracks>
std::vector<typename GlmbFilter<Tracks>::Hypothesis> GlmbFilter<Tracks>::normalise_and_prune(
    const Posterior& posterior) const {
  std::vector<Hypothesis> updated;
  updated.reserve(posterior.weights.size());
  for (const auto& [tracks, log_weight] : posterior.weights) updated.push_back({tracks, log_weight});
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
  return updated;
}

template <class Tracks>
void GlmbFilter<Tracks>::keep_used_tracks(std::vector<Hypothesis> hypotheses,
                                          Posterior& posterior) {
  std::vector<int> new_index(posterior.children.size(), -1);
  tracks_.clear();
  for (auto& h : hypotheses) {
    for (int& t : h.tracks) {
      if (new_index[t] < 0) {
        new_index[t] = static_cast<int>(tracks_.size());
        tracks_.push_back(std::move(posterior.children[t]));
      }
      t = new_index[t];
    }
    std::sort(h.tracks.begin(), h.tracks.end());
  }
  hypotheses_ = std::move(hypotheses);
}

template <class Tracks>
typename GlmbFilter<Tracks>::RankedChoices GlmbFilter<Tracks>::rank(const Eigen::MatrixXd& cost,
                                                                    std::int64_t requested) {
  // The Gibbs sampler: Murty's ranking goes through ranking_pool_ (rank_hypotheses).
  assign::SampledAssignments s = assign::gibbs_assignments(cost, requested, ranking_rng_);
  return {std::move(s.assignments), std::move(s.costs)};
}

template <class Tracks>
void GlmbFilter<Tracks>::summarise(const std::vector<Hypothesis>& hypotheses,
                                   const ScanFactors& factors, const Posterior& posterior,
                                   Eigen::Index n_det) {
  const int n_prior = static_cast<int>(tracks_.size());
  ScanSummary s{Eigen::VectorXd::Zero(n_det), Eigen::VectorXd::Zero(n_det), 0.0, 0.0, {}};
  for (const auto& h : hypotheses) {
    const double w = std::exp(h.log_weight);
    for (int t : h.tracks) {
      const int j = posterior.child_detection[t];
      const int row = posterior.child_row[t];
      const bool survivor = row < n_prior;
      if (j >= 0) (survivor ? s.to_track : s.to_birth)[j] += w;
      const double detectable = factors.missed_detectable[row];
      if (detectable < 0.0) continue;  // a birth, or outside the field of view
      if (j >= 0) {
        s.detected += w;
      } else {
        s.missed += w * detectable;
      }
    }
  }
  summary_ = std::move(s);
}

template <class Tracks>
Eigen::VectorXd GlmbFilter<Tracks>::missed_explanations(
    const std::vector<Hypothesis>& hypotheses, const ScanFactors& factors,
    const Posterior& posterior, const Eigen::Ref<const Eigen::MatrixXd>& detections) {
  const Eigen::Index n_det = detections.cols();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n_det);
  if (n_det == 0) return out;
  // Per missed child row, log(1 - q_tj) for the detections in its gate (AdaptiveBirthParams):
  // log(1 - q) = -log(1 + L), L = p_D g(z_j | p_t) / kappa(z_j). Computed once per row.
  std::map<int, std::vector<std::pair<int, double>>> free_of_row;
  Eigen::RowVectorXd log_g(n_det);
  auto row_terms = [&](int row) -> const std::vector<std::pair<int, double>>& {
    auto [it, inserted] = free_of_row.try_emplace(row);
    if (!inserted) return it->second;
    tracks_model_.log_missed_likelihoods(factors.candidates[static_cast<std::size_t>(row)],
                                         detections, params_.gate_threshold, log_g);
    for (Eigen::Index j = 0; j < n_det; ++j) {
      if (!(log_g[j] > -detail::kInfinity)) continue;
      const double log_l = factors.log_pd[row] + log_g[j] - factors.log_kappa[j];
      // -log(1 + e^log_l), stable for either sign.
      const double log_free = log_l > 0.0 ? -(log_l + std::log1p(std::exp(-log_l)))
                                          : -std::log1p(std::exp(log_l));
      it->second.emplace_back(static_cast<int>(j), log_free);
    }
    return it->second;
  };
  // Scratch per hypothesis: log prod (1 - q) per detection, the detections touched, and the
  // detections the hypothesis assigns.
  Eigen::VectorXd log_free = Eigen::VectorXd::Zero(n_det);
  std::vector<char> assigned(static_cast<std::size_t>(n_det), 0);
  std::vector<int> touched;
  for (const auto& h : hypotheses) {
    touched.clear();
    for (int t : h.tracks) {
      const int j = posterior.child_detection[static_cast<std::size_t>(t)];
      if (j >= 0) assigned[static_cast<std::size_t>(j)] = 1;
    }
    for (int t : h.tracks) {
      if (posterior.child_detection[static_cast<std::size_t>(t)] >= 0) continue;
      for (const auto& [j, lf] : row_terms(posterior.child_row[static_cast<std::size_t>(t)])) {
        if (log_free[j] == 0.0) touched.push_back(j);
        log_free[j] += lf;
      }
    }
    const double w = std::exp(h.log_weight);
    for (int j : touched) {
      if (!assigned[static_cast<std::size_t>(j)]) out[j] += w * -std::expm1(log_free[j]);
      log_free[j] = 0.0;
    }
    for (int t : h.tracks) {
      const int j = posterior.child_detection[static_cast<std::size_t>(t)];
      if (j >= 0) assigned[static_cast<std::size_t>(j)] = 0;
    }
  }
  return out;
}

template <class Tracks>
void GlmbFilter<Tracks>::propose_adaptive_births(
    const Eigen::Ref<const Eigen::MatrixXd>& detections, const Eigen::VectorXd& assigned,
    const Eigen::VectorXd& weight) {
  adaptive_births_.clear();
  adaptive_birth_detections_.clear();
  const auto& adaptive = params_.adaptive_birth;
  if (!adaptive.enabled || detections.cols() == 0) return;
  const Eigen::VectorXd unassigned =
      ((1.0 - assigned.array()).max(0.0) * weight.array()).matrix();
  const double total = unassigned.sum();
  if (!(total > 0.0)) return;
  // The max_births detections with the largest r_B (a stable order: ties by index).
  std::vector<int> order(static_cast<std::size_t>(detections.cols()));
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = static_cast<int>(j);
  const auto keep =
      std::min<std::size_t>(order.size(), static_cast<std::size_t>(adaptive.max_births));
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep), order.end(),
                    [&](int a, int b) {
                      return unassigned[a] > unassigned[b] ||
                             (unassigned[a] == unassigned[b] && a < b);
                    });
  order.resize(keep);
  std::sort(order.begin(), order.end());
  // H^+ = H^T (H H^T)^-1 maps a detection to the least-norm state that predicts it.
  const Eigen::MatrixXd& H = observation_.H;
  const Eigen::LDLT<Eigen::MatrixXd> HHt(H * H.transpose());
  for (int j : order) {
    const double r =
        std::min(adaptive.max_existence, adaptive.expected_births * unassigned[j] / total);
    // A detection that tracks explain almost surely would only add a row that stays absent.
    if (r < 1e-12) continue;
    adaptive_births_.push_back(
        {r, {H.transpose() * HHt.solve(Eigen::VectorXd(detections.col(j))), adaptive.cov}});
    adaptive_birth_detections_.push_back(j);
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
void GlmbFilter<Tracks>::estimate() {
  const EstimatorParams& e = params_.estimator;
  auto reported = [&](int t) {
    return std::find(reported_.begin(), reported_.end(), tracks_[t].label) != reported_.end();
  };
  const Hypothesis* best = nullptr;
  if (e.estimator == LabelEstimator::map) {
    const std::size_t n = static_cast<std::size_t>(map_cardinality());
    for (const auto& h : hypotheses_) {
      if (h.tracks.size() == n && (!best || h.log_weight > best->log_weight)) best = &h;
    }
  } else {
    // The joint MAP with the previous report (LabelEstimator::consistent).
    double best_score = -detail::kInfinity;
    for (const auto& h : hypotheses_) {
      double score = h.log_weight;
      for (int t : h.tracks) score += reported(t) ? e.keep_bonus : -e.entry_penalty;
      if (score > best_score) {
        best_score = score;
        best = &h;
      }
    }
  }
  estimates_.clear();
  reported_.clear();
  if (!best) return;
  // Each label's existence probability: the weight of the hypotheses that hold it (a hypothesis
  // holds a label at most once).
  std::vector<double> existence(tracks_.size(), 0.0);
  for (const auto& h : hypotheses_) {
    for (int u : h.tracks) existence[static_cast<std::size_t>(u)] += std::exp(h.log_weight);
  }
  for (int t : best->tracks) {
    double r = 0.0;
    for (std::size_t u = 0; u < tracks_.size(); ++u) {
      if (tracks_[u].label == tracks_[t].label) r += existence[u];
    }
    models::GaussianDensity m = Tracks::moments(tracks_[t].density);
    estimates_.push_back({tracks_[t].label, std::move(m.mean), std::move(m.cov), std::min(r, 1.0),
                          tracks_[t].undetectable});
    reported_.push_back(tracks_[t].label);
  }
  if (e.duplicate_gate > 0.0) suppress_duplicates();
}

template <class Tracks>
void GlmbFilter<Tracks>::suppress_duplicates() {
  // Oldest label first (birth time, then index): each estimate is kept unless its predicted
  // detection lies within duplicate_gate (squared Mahalanobis, EstimatorParams) of a kept one's.
  const std::size_t n = estimates_.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const TrackLabel& la = estimates_[a].label;
    const TrackLabel& lb = estimates_[b].label;
    return la.birth_time != lb.birth_time ? la.birth_time < lb.birth_time
                                          : la.birth_index < lb.birth_index;
  });
  const Eigen::MatrixXd& H = observation_.H;
  std::vector<Eigen::VectorXd> z(n);
  std::vector<Eigen::MatrixXd> S(n);
  for (std::size_t i = 0; i < n; ++i) {
    z[i] = H * estimates_[i].mean;
    S[i] = H * estimates_[i].cov * H.transpose();
  }
  std::vector<char> keep(n, 0);
  std::vector<std::size_t> kept;
  for (std::size_t i : order) {
    bool duplicate = false;
    for (std::size_t j : kept) {
      const Eigen::VectorXd dz = z[i] - z[j];
      const Eigen::LDLT<Eigen::MatrixXd> sum(S[i] + S[j]);
      // A singular sum (two point masses) is a duplicate only where the means coincide.
      const double d2 = sum.info() == Eigen::Success && sum.isPositive() && sum.rcond() > 1e-12
                            ? dz.dot(sum.solve(dz))
                            : (dz.isZero(0.0) ? 0.0 : detail::kInfinity);
      if (d2 <= params_.estimator.duplicate_gate) {
        duplicate = true;
        break;
      }
    }
    if (duplicate) continue;
    keep[i] = 1;
    kept.push_back(i);
  }
  std::size_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    if (out != i) {
      estimates_[out] = std::move(estimates_[i]);
      reported_[out] = reported_[i];
    }
    ++out;
  }
  estimates_.resize(out);
  reported_.resize(out);
}

template <class Tracks>
bool GlmbFilter<Tracks>::holds(const TrackLabel& label) const {
  return std::any_of(tracks_.begin(), tracks_.end(),
                     [&](const Track& t) { return t.label == label; });
}

}  // namespace vtrack::filters
