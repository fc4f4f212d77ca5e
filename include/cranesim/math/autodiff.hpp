#pragma once
// Forward-mode automatic differentiation with Eigen's AutoDiffScalar and fixed-size
// derivative vectors (no heap allocation). Nesting Dual<Dual<double,N>,M> gives second
// derivatives, which the constraint kernels use for exact Jacobians of B(q)ᵀλ and for Γ.

#include <cmath>

#include "cranesim/math/types.hpp"  // Eigen/Dense must precede the AutoDiff module

#include <unsupported/Eigen/AutoDiff>

namespace cranesim {

template <class T, int N> using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<T, N, 1>>;

/// The plain value of a (possibly nested) dual number.
inline double valueOf(double x) { return x; }
template <class D> double valueOf(const Eigen::AutoDiffScalar<D>& x) { return valueOf(x.value()); }

/// A dual number equal to `value` whose derivative is 1 in direction `k` and 0 elsewhere.
template <class T, int N> Dual<T, N> seeded(const T& value, int k) {
  Dual<T, N> x(value, Eigen::Matrix<T, N, 1>::Zero());
  x.derivatives()(k) = T(1.0);
  return x;
}

/// A dual number equal to `value` with all derivatives zero.
template <class T, int N> Dual<T, N> constant(const T& value) {
  return Dual<T, N>(value, Eigen::Matrix<T, N, 1>::Zero());
}

}  // namespace cranesim
