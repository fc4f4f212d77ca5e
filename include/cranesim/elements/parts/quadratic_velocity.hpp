#pragma once
// Quadratic-velocity (Coriolis and centrifugal) forces of an element whose velocities are the
// time derivatives of its coordinates (dq = q̇), from its mass matrix alone. Lagrange's
// equations with T = ½ q̇ᵀ M(q) q̇ give M q̈ + F with
//   F_i = Σ_jk (∂M_ij/∂q_k − ½ ∂M_jk/∂q_i) q̇_j q̇_k,
// so F is exactly consistent with M (energy conserving); ∂M/∂q by forward AD. The tests' reference
// for kernels whose quadratic-velocity forces are written in closed form (strut_tie.hpp).

#include "cranesim/math/autodiff.hpp"

namespace cranesim {

template <int N, class S, class MassFunction>
Eigen::Matrix<S, N, 1> quadraticVelocityForces(const MassFunction& mass, const Eigen::Matrix<S, N, 1>& q,
                                               const Eigen::Matrix<S, N, 1>& v) {
  using D = Dual<S, N>;
  Eigen::Matrix<D, N, 1> qd;
  for (int k = 0; k < N; ++k) qd(k) = seeded<S, N>(q(k), k);
  const Eigen::Matrix<D, N, N> M = mass(qd);
  Eigen::Matrix<S, N, 1> F = Eigen::Matrix<S, N, 1>::Zero();
  for (int j = 0; j < N; ++j)
    for (int k = 0; k < N; ++k) {
      const S vjvk = v(j) * v(k);
      for (int i = 0; i < N; ++i) F(i) += (M(i, j).derivatives()(k) - 0.5 * M(j, k).derivatives()(i)) * vjvk;
    }
  return F;
}

}  // namespace cranesim
