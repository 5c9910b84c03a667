#pragma once
// The state-space model concept of the SMC engine, resolved at compile time (no virtual call per
// particle; a model is a small struct passed by value as a template argument).
//
// Motion model M (x_k ~ p(x_k | x_{k-1})), driven by Gaussian noise:
//   int dim() const;                      state dimension d
//   int noise_dim() const;                r, standard normals per particle and step
//   template <typename S> void propagate(const models::StatesView<S>& prev,   // n x d
//                                        const models::StatesView<S>& eps,    // n x r, N(0, I)
//                                        models::MutableStatesView<S> next) const;  // n x d
// `propagate` is deterministic given eps: the engine draws eps from per-block streams (so any
// thread count gives the same particles), and the MCMC moves run their chains on eps (so a model
// whose noise is singular, e.g. the second-order auto-regressive one, can still be moved).
// Optional: `const Eigen::MatrixXd& noise_factor() const` (S, d x r) for a model
// x_k = propagate(x_{k-1}, 0) + S eps, which the MCMC filter's reference = "all" needs to evaluate
// the transition density p(x_k | x_{k-1}^i) (it requires S square and invertible).
//
// Observation model O (p(z_k | x_k)):
//   void check(const Eigen::VectorXd& z) const;          InvalidArgument for a bad measurement
//   template <typename S> void log_likelihood(const models::StatesView<S>& x,  // n x d
//                                             const Eigen::VectorXd& z, double* out) const;
//   int min_state_dim() const;                           the state dimension it needs at least
//
// Whole-array models (a model implemented in Python, called once per step on all particles):
// `static constexpr bool whole_array = true;` and instead of the above
//   motion:       void propagate_all(const Eigen::MatrixXd& prev, Eigen::MatrixXd& next) const;
//   observation:  void log_likelihood_all(const Eigen::MatrixXd& x, const Eigen::VectorXd& z,
//                                         Eigen::VectorXd& out) const;
// (N x d arrays, one particle per row). They are called from the thread that runs the step.
//
// Proposal P (particle-filters-human-vehicle §1.2, general importance weights), optional for SIR:
//   int noise_dim() const;
//   template <typename S> void propagate(const StatesView<S>& prev, const StatesView<S>& eps,
//                                        const Eigen::VectorXd& z, MutableStatesView<S> next) const;
//   template <typename S> void log_weight(const StatesView<S>& prev, const StatesView<S>& next,
//                                         const Eigen::VectorXd& z, double* out) const;
// where log_weight = log p(next | prev) - log q(next | prev, z), added to the log-likelihood
// (eq. 5). Without one the proposal is the motion model (bootstrap filter) and the weight is the
// likelihood alone.
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "vtrack/models/states.hpp"

namespace vtrack::smc {

namespace detail {
template <class M, class = void>
struct whole_array : std::false_type {};
template <class M>
struct whole_array<M, std::void_t<decltype(M::whole_array)>>
    : std::integral_constant<bool, M::whole_array> {};

template <class M, class = void>
struct has_noise_factor : std::false_type {};
template <class M>
struct has_noise_factor<M, std::void_t<decltype(std::declval<const M&>().noise_factor())>>
    : std::true_type {};
}  // namespace detail

// Whether a model is called once per step on whole arrays (not per block).
template <class M>
inline constexpr bool is_whole_array_v = detail::whole_array<M>::value;
// Whether a motion model exposes its noise factor S (x = propagate(x_prev, 0) + S eps).
template <class M>
inline constexpr bool has_noise_factor_v = detail::has_noise_factor<M>::value;

// The bootstrap proposal: the motion model itself, weight correction zero.
struct Bootstrap {};

}  // namespace vtrack::smc
