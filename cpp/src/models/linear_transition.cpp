#include "vtrack/models/linear_transition.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "vtrack/core/errors.hpp"

namespace vtrack::models {
namespace {

// dst[i] = sum_k coef[k] src[k][i] with K terms known at compile time, so the loop over particles
// vectorises with the terms unrolled inside.
template <int K, typename Scalar>
void sum_terms(const Scalar* const* src, const Scalar* coef, Scalar* dst, Eigen::Index n) {
  for (Eigen::Index i = 0; i < n; ++i) {
    Scalar acc = coef[0] * src[0][i];
    for (int k = 1; k < K; ++k) acc += coef[k] * src[k][i];
    dst[i] = acc;
  }
}

template <typename Scalar>
void sum_any(const Scalar* const* src, const Scalar* coef, int count, Scalar* dst, Eigen::Index n) {
  switch (count) {
    case 1: return sum_terms<1>(src, coef, dst, n);
    case 2: return sum_terms<2>(src, coef, dst, n);
    case 3: return sum_terms<3>(src, coef, dst, n);
    case 4: return sum_terms<4>(src, coef, dst, n);
    case 5: return sum_terms<5>(src, coef, dst, n);
    case 6: return sum_terms<6>(src, coef, dst, n);
    default: break;
  }
  // Dense rows: six terms at a time.
  sum_terms<6>(src, coef, dst, n);
  for (int k = 6; k < count; ++k) {
    const Scalar* s = src[k];
    const Scalar c = coef[k];
    for (Eigen::Index i = 0; i < n; ++i) dst[i] += c * s[i];
  }
}

void require_finite(const Eigen::MatrixXd& m, const char* name) {
  if (!m.allFinite()) throw InvalidArgument(std::string(name) + " contains NaN or inf");
}

}  // namespace

LinearTransition::LinearTransition(Eigen::MatrixXd F, Eigen::MatrixXd S)
    : F_(std::move(F)), S_(std::move(S)) {
  if (F_.rows() == 0 || F_.rows() != F_.cols()) {
    throw InvalidArgument("F must be square and non-empty, got " + std::to_string(F_.rows()) +
                          "x" + std::to_string(F_.cols()));
  }
  if (S_.rows() != F_.rows()) {
    throw InvalidArgument("the noise factor must have " + std::to_string(F_.rows()) +
                          " rows to match F, got " + std::to_string(S_.rows()));
  }
  require_finite(F_, "F");
  require_finite(S_, "the noise factor");
  terms_.resize(static_cast<std::size_t>(F_.rows()));
  for (Eigen::Index r = 0; r < F_.rows(); ++r) {
    auto& terms = terms_[static_cast<std::size_t>(r)];
    for (Eigen::Index c = 0; c < F_.cols(); ++c) {
      if (F_(r, c) != 0.0) terms.push_back({false, static_cast<int>(c), F_(r, c)});
    }
    for (Eigen::Index k = 0; k < S_.cols(); ++k) {
      if (S_(r, k) != 0.0) terms.push_back({true, static_cast<int>(k), S_(r, k)});
    }
  }
}

LinearTransition LinearTransition::from_covariance(Eigen::MatrixXd F, const Eigen::MatrixXd& Q,
                                                   const char* name) {
  const Eigen::Index d = F.rows();
  if (Q.rows() != d || Q.cols() != d) {
    throw InvalidArgument(std::string(name) + " must be " + std::to_string(d) + "x" +
                          std::to_string(d) + " to match F, got " + std::to_string(Q.rows()) +
                          "x" + std::to_string(Q.cols()));
  }
  require_finite(Q, name);
  const double scale = Q.cwiseAbs().maxCoeff();
  if ((Q - Q.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    throw InvalidArgument(std::string(name) + " is not symmetric");
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (Q + Q.transpose()));
  const Eigen::VectorXd lambda = eig.eigenvalues();  // ascending
  const double top = d > 0 ? std::max(lambda[d - 1], 0.0) : 0.0;
  if (lambda.size() > 0 && lambda[0] < -1e-9 * (1.0 + top)) {
    throw InvalidArgument(std::string(name) + " is not positive semi-definite (eigenvalue " +
                          value_text(lambda[0]) + ")");
  }
  const double tol = 1e-12 * top;
  Eigen::Index rank = 0;
  for (Eigen::Index i = 0; i < d; ++i) rank += lambda[i] > tol ? 1 : 0;
  if (rank == d) {
    // Positive definite: the lower Cholesky factor keeps Q's zeros (block-diagonal models stay
    // sparse), which an eigenvector factor would fill in.
    Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (Q + Q.transpose()));
    if (llt.info() == Eigen::Success) return LinearTransition(std::move(F), llt.matrixL());
  }
  Eigen::MatrixXd S(d, rank);
  for (Eigen::Index j = 0; j < rank; ++j) {
    const Eigen::Index i = d - rank + j;
    S.col(j) = eig.eigenvectors().col(i) * std::sqrt(lambda[i]);
  }
  return LinearTransition(std::move(F), std::move(S));
}

void LinearTransition::propagate(const StatesView<double>& prev, const StatesView<double>& eps,
                                 MutableStatesView<double> next) const {
  propagate_impl(prev, eps, next);
}

void LinearTransition::propagate(const StatesView<float>& prev, const StatesView<float>& eps,
                                 MutableStatesView<float> next) const {
  propagate_impl(prev, eps, next);
}

template <typename Scalar>
void LinearTransition::propagate_impl(const StatesView<Scalar>& prev, const StatesView<Scalar>& eps,
                                      MutableStatesView<Scalar>& next) const {
  const Eigen::Index n = prev.rows();
  if (n == 0) return;
  std::vector<const Scalar*> src;
  std::vector<Scalar> coef;
  for (std::size_t r = 0; r < terms_.size(); ++r) {
    src.clear();
    coef.clear();
    for (const Term& t : terms_[r]) {
      src.push_back(t.noise ? column(eps, t.column) : column(prev, t.column));
      coef.push_back(static_cast<Scalar>(t.coef));
    }
    Scalar* dst = column(next, static_cast<Eigen::Index>(r));
    if (src.empty()) {
      std::fill(dst, dst + n, Scalar(0));
    } else {
      sum_any(src.data(), coef.data(), static_cast<int>(src.size()), dst, n);
    }
  }
}

}  // namespace vtrack::models
