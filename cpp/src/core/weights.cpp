#include "vtrack/core/weights.hpp"

#include <cmath>
#include <string>

#include "vtrack/core/errors.hpp"

namespace vtrack::core {
namespace {

void require_no_nan(const Eigen::Ref<const Eigen::VectorXd>& x, const char* name) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (std::isnan(x[i])) {
      throw InvalidArgument(std::string(name) + " contains NaN at index " + std::to_string(i));
    }
  }
}

}  // namespace

double log_sum_exp(const Eigen::Ref<const Eigen::VectorXd>& log_weights) {
  require_no_nan(log_weights, "log_weights");
  if (log_weights.size() == 0) return -kInf;
  const double peak = log_weights.maxCoeff();
  if (!std::isfinite(peak)) return peak;  // all -inf -> -inf, any +inf -> +inf
  return peak + std::log((log_weights.array() - peak).exp().sum());
}

double normalize_log_weights(const Eigen::Ref<const Eigen::VectorXd>& log_weights,
                             Eigen::VectorXd& weights) {
  const double total = log_sum_exp(log_weights);
  const Eigen::Index n = log_weights.size();
  weights.resize(n);
  if (n == 0) return total;
  if (total == -kInf) {
    weights.setConstant(1.0 / static_cast<double>(n));
  } else if (total == kInf) {
    // Only the +inf entries carry weight; share it equally among them.
    const auto is_inf = (log_weights.array() == kInf).cast<double>();
    weights = is_inf / is_inf.sum();
  } else {
    weights = (log_weights.array() - total).exp().matrix();
  }
  return total;
}

double effective_sample_size(const Eigen::Ref<const Eigen::VectorXd>& weights) {
  for (Eigen::Index i = 0; i < weights.size(); ++i) {
    if (!(weights[i] >= 0.0) || !std::isfinite(weights[i])) {
      throw InvalidArgument("weights must be finite and non-negative; weights[" +
                            std::to_string(i) + "] = " + std::to_string(weights[i]));
    }
  }
  const double sum = weights.sum();
  if (sum == 0.0) return 0.0;
  // Scale by the largest weight first so the squares cannot overflow or underflow.
  const double peak = weights.maxCoeff();
  const Eigen::ArrayXd scaled = weights.array() / peak;
  const double s = scaled.sum();
  return s * s / scaled.square().sum();
}

double effective_sample_size_log(const Eigen::Ref<const Eigen::VectorXd>& log_weights) {
  Eigen::VectorXd weights;
  if (normalize_log_weights(log_weights, weights) == -kInf) return 0.0;
  return effective_sample_size(weights);
}

}  // namespace vtrack::core
