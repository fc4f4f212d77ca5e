#pragma once
// An element's DAE Jacobian by central differences of its residual, for kernels whose 12
// coordinates add (positions and slopes, no rotation vectors): the reference the closed-form and
// AD Jacobians are checked against; and the blockwise comparison of two Jacobians.

#include <algorithm>

#include <Eigen/Dense>

#include "cranesim/model/element.hpp"

namespace cranesim::test {

/// [∂r/∂q | ∂r/∂dq + cj M] at `in` (the residual's dq derivative lacks the mass matrix's cj M).
inline Eigen::Matrix<double, 12, 24> centralDifferenceJacobian(const Element& element, const ElementInput& in, double cj,
                                                              double h = 1e-7) {
  using Q = Eigen::Matrix<double, 12, 1>;
  const Q q = Eigen::Map<const Q>(in.q), v = Eigen::Map<const Q>(in.v);
  const auto residual = [&](const Q& qq, const Q& vv) {
    ElementInput at = in;
    at.q = qq.data(), at.v = vv.data();
    Q r;
    element.residual(at, r.data());
    return r;
  };
  Eigen::Matrix<double, 12, 24> fd;
  for (int c = 0; c < 24; ++c) {
    Q qp = q, qm = q, vp = v, vm = v;
    if (c < 12) qp(c) += h, qm(c) -= h;
    else vp(c - 12) += h, vm(c - 12) -= h;
    fd.col(c) = (residual(qp, vp) - residual(qm, vm)) / (2.0 * h);
  }
  Eigen::Matrix<double, 12, 12> M;
  element.mass(in, M.data());
  fd.rightCols<12>() += cj * M;
  return fd;
}

/// The largest relative difference between J and `reference` over their 3-column blocks, each
/// block against its own norm (so that a block of small terms is not measured against a large one).
template <class Computed, class Reference> double worstColumnBlockError(const Computed& J, const Reference& reference) {
  double worst = 0.0;
  for (int block = 0; block < J.cols() / 3; ++block)
    worst = std::max(worst, (J.middleCols(3 * block, 3) - reference.middleCols(3 * block, 3)).norm() /
                                reference.middleCols(3 * block, 3).norm());
  return worst;
}

}  // namespace cranesim::test
