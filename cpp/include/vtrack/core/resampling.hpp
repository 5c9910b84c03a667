#pragma once
// Resampling schemes, each O(N + M) for N weights and M draws, returning ancestor indices in
// non-decreasing order. All four are unbiased: E[number of copies of particle i] = M * w_i.
// See Douc, Cappe & Moulines (2005), "Comparison of resampling schemes for particle filtering".
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/random.hpp"

namespace vtrack::core {

enum class ResamplingScheme { Multinomial, Stratified, Systematic, Residual };

// Parses "multinomial", "stratified", "systematic" or "residual"; InvalidArgument otherwise.
ResamplingScheme parse_resampling_scheme(const std::string& name);
const char* to_string(ResamplingScheme scheme);
// Every scheme with its name, for parameter tables.
const std::vector<std::pair<std::string, ResamplingScheme>>& resampling_scheme_names();

// Draws `count` ancestor indices from `weights` (finite, non-negative, not all zero; they need not
// sum to one). A particle of weight exactly zero is never chosen.
void resample(ResamplingScheme scheme, const Eigen::Ref<const Eigen::VectorXd>& weights,
              std::size_t count, Rng& rng, std::int64_t* ancestors);
std::vector<std::int64_t> resample(ResamplingScheme scheme,
                                   const Eigen::Ref<const Eigen::VectorXd>& weights,
                                   std::size_t count, Rng& rng);

}  // namespace vtrack::core
