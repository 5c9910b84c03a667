#pragma once
// Importance weights in the log domain.
//
// Convention for vanishing weights: when every log weight is -inf (no particle explains the data),
// the total log_sum_exp is -inf, normalize_log_weights() returns -inf and sets the weights to the
// uniform 1/N (the filter has learnt nothing, so it keeps its prior), and the effective sample
// size is 0. None of these ever produce NaN; a NaN in the input is an InvalidArgument.
#include <limits>

#include <Eigen/Core>

namespace vtrack::core {

// The log weight of a particle that explains nothing is -kInf.
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// log(sum_i exp(x_i)), computed stably. Empty input or all -inf gives -inf; any +inf gives +inf.
double log_sum_exp(const Eigen::Ref<const Eigen::VectorXd>& log_weights);

// Writes the normalised linear weights exp(x_i - log_sum_exp(x)) to `weights` (resized to match)
// and returns log_sum_exp(x) (the log of the normalising constant, e.g. the log evidence).
double normalize_log_weights(const Eigen::Ref<const Eigen::VectorXd>& log_weights,
                             Eigen::VectorXd& weights);

// Effective sample size N_eff = 1 / sum_i w_i^2 of normalised weights
// (part-based-graphical-model-pf.txt eq. 7). Computed as (sum w)^2 / sum w^2, which equals eq. 7
// for normalised weights and is scale-invariant for unnormalised ones. All-zero weights give 0.
// Weights must be finite and non-negative.
double effective_sample_size(const Eigen::Ref<const Eigen::VectorXd>& weights);

// N_eff of unnormalised log weights; all -inf gives 0.
double effective_sample_size_log(const Eigen::Ref<const Eigen::VectorXd>& log_weights);

}  // namespace vtrack::core
