#pragma once
// The tangents of a contact's generalized force by forward AD (model/contact_elements.hpp).

#include <Eigen/Core>

#include "cranesim/math/autodiff.hpp"

namespace cranesim {

/// ∂Q/∂q and ∂Q/∂dq of the N generalized forces `force(q, dq)` of N coordinates, by forward AD
/// (column-major).
template <int N, class Force>
void forwardTangents(const Eigen::Matrix<double, N, 1>& q, const Eigen::Matrix<double, N, 1>& v, const Force& force, double* Qq,
                     double* Qv) {
  using D = Dual<double, N>;
  Eigen::Matrix<D, N, 1> qd, vd, q0, v0;
  for (int k = 0; k < N; ++k) {
    qd(k) = seeded<double, N>(q(k), k), vd(k) = seeded<double, N>(v(k), k);
    q0(k) = constant<double, N>(q(k)), v0(k) = constant<double, N>(v(k));
  }
  const Eigen::Matrix<D, N, 1> by_q = force(qd, v0), by_v = force(q0, vd);
  Eigen::Map<Eigen::Matrix<double, N, N>> dq(Qq), dv(Qv);
  for (int i = 0; i < N; ++i) dq.row(i) = by_q(i).derivatives().transpose(), dv.row(i) = by_v(i).derivatives().transpose();
}

}  // namespace cranesim
