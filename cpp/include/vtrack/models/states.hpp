#pragma once
// How models see particle states: a block of n particles as an n x d column-major view, one
// particle per row, each state component contiguous (the smc::ParticleSet layout). Column c of a
// block is the array &x(0, c) of n values, so model loops run over particles with unit stride and
// vectorise. Blocks of a larger set are views with an outer stride (Eigen::Ref below).
#include <Eigen/Core>

namespace vtrack::models {

template <typename Scalar>
using StatesView =
    Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>, 0, Eigen::OuterStride<>>;
template <typename Scalar>
using MutableStatesView =
    Eigen::Ref<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>, 0, Eigen::OuterStride<>>;

// Column c of a view: the n values of state component c, contiguous.
template <typename Scalar>
const Scalar* column(const StatesView<Scalar>& x, Eigen::Index c) {
  return x.data() + c * x.outerStride();
}
template <typename Scalar>
Scalar* column(MutableStatesView<Scalar>& x, Eigen::Index c) {
  return x.data() + c * x.outerStride();
}

}  // namespace vtrack::models
