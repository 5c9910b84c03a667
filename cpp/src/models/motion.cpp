#include "vtrack/models/motion.hpp"

#include <cmath>

#include "vtrack/core/errors.hpp"

namespace vtrack::models {
namespace {

// Per-component standard deviations: sigma broadcast to `dims` (0 = sigma.size()), each > 0.
void validate_sigma(const std::vector<double>& sigma, int dims) {
  require(!sigma.empty(), "sigma", 0.0, "non-empty");
  require(dims >= 0, "dims", dims, ">= 0");
  require(dims == 0 || sigma.size() == 1 || static_cast<int>(sigma.size()) == dims, "dims", dims,
          "sigma's length (or sigma a single value)");
  for (double s : sigma) require(s > 0.0 && std::isfinite(s), "sigma", s, "positive and finite");
}

Eigen::VectorXd broadcast_sigma(const std::vector<double>& sigma, int dims) {
  const int d = dims > 0 ? dims : static_cast<int>(sigma.size());
  Eigen::VectorXd out(d);
  for (int i = 0; i < d; ++i) out[i] = sigma[sigma.size() == 1 ? 0 : static_cast<std::size_t>(i)];
  return out;
}

LinearTransition random_walk(const RandomWalkParams& p) {
  validate(p);
  const Eigen::VectorXd s = broadcast_sigma(p.sigma, p.dims);
  const auto d = s.size();
  return LinearTransition(Eigen::MatrixXd::Identity(d, d), s.asDiagonal());
}

LinearTransition constant_velocity(const ConstantVelocityParams& p) {
  validate(p);
  const int n = 2 * p.axes;
  const double T = p.period;
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(n, n);
  const bool continuous = p.noise == AccelerationNoise::Continuous;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, continuous ? n : p.axes);
  // Continuous: the Cholesky factor of q [[T^3/3, T^2/2], [T^2/2, T]] in closed form,
  // [[sqrt(T^3/3), 0], [sqrt(3 T)/2, sqrt(T)/2]] sqrt(q). Discrete: sqrt(q) g.
  const double sq = std::sqrt(p.q);
  for (int a = 0; a < p.axes; ++a) {
    F(2 * a, 2 * a + 1) = T;
    if (continuous) {
      S(2 * a, 2 * a) = sq * std::sqrt(T * T * T / 3.0);
      S(2 * a + 1, 2 * a) = sq * std::sqrt(3.0 * T) / 2.0;
      S(2 * a + 1, 2 * a + 1) = sq * std::sqrt(T) / 2.0;
    } else {
      S(2 * a, a) = sq * T * T / 2.0;
      S(2 * a + 1, a) = sq * T;
    }
  }
  return LinearTransition(std::move(F), std::move(S));
}

LinearTransition second_order_ar(const SecondOrderAutoRegressiveParams& p) {
  validate(p);
  const Eigen::VectorXd s = broadcast_sigma(p.sigma, p.dims);
  const auto m = s.size();
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  F.topLeftCorner(m, m).diagonal().setConstant(2.0);
  F.topRightCorner(m, m).diagonal().setConstant(-1.0);
  F.bottomLeftCorner(m, m).setIdentity();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * m, m);
  S.topRows(m) = s.asDiagonal();
  return LinearTransition(std::move(F), std::move(S));
}

}  // namespace

void validate(const RandomWalkParams& p) { validate_sigma(p.sigma, p.dims); }

void validate(const SecondOrderAutoRegressiveParams& p) { validate_sigma(p.sigma, p.dims); }

void validate(const ConstantVelocityParams& p) {
  require(p.axes >= 1, "axes", p.axes, ">= 1");
  require(p.period > 0.0 && std::isfinite(p.period), "period", p.period, "positive and finite");
  require(p.q > 0.0 && std::isfinite(p.q), "q", p.q, "positive and finite");
}

AccelerationNoise parse_acceleration_noise(const std::string& name) {
  if (name == "continuous") return AccelerationNoise::Continuous;
  if (name == "discrete") return AccelerationNoise::Discrete;
  throw InvalidArgument("noise must be 'continuous' or 'discrete', got '" + name + "'");
}

const char* to_string(AccelerationNoise noise) {
  return noise == AccelerationNoise::Continuous ? "continuous" : "discrete";
}

RandomWalk::RandomWalk(const RandomWalkParams& params)
    : LinearTransition(random_walk(params)), params_(params) {}

ConstantVelocity::ConstantVelocity(const ConstantVelocityParams& params)
    : LinearTransition(constant_velocity(params)), params_(params) {}

SecondOrderAutoRegressive::SecondOrderAutoRegressive(const SecondOrderAutoRegressiveParams& params)
    : LinearTransition(second_order_ar(params)), params_(params) {}

}  // namespace vtrack::models
