// The objective tangent's functions that are not templates (objective_tangent.hpp), compiled
// here once.
#include "cranesim/elements/parts/objective_tangent.hpp"

namespace cranesim {

Eigen::Matrix<double, 12, 12> objective_detail::fromSecondEnd(const ObjectiveTangentInput& in, const Eigen::Matrix<double, 12, 1>& residual,
                                                              const Eigen::Matrix<double, 12, 6>& second_end) {
  using Mat12x3 = Eigen::Matrix<double, 12, 3>;
  const Vec3 phi1 = in.q.segment<3>(3), phi2 = in.q.segment<3>(9);
  const Mat3 R1 = rotationMatrix<double>(phi1), R2 = rotationMatrix<double>(phi2);
  const auto A = second_end.leftCols<3>();
  const Mat12x3 B = second_end.rightCols<3>() * angularVelocityMapInverse<double>(phi2);
  Mat12x3 X = Mat12x3::Zero();
  for (int n = 0; n < 2; ++n) X.middleRows<3>(6 * n) = -skew<double>(Vec3(residual.segment<3>(6 * n)));
  for (int n = 0; n < 2; ++n) {
    X.noalias() += in.velocity_tangent.middleCols<3>(6 * n) * skew<double>(Vec3(in.v.segment<3>(6 * n)));
    X.noalias() += in.mass.middleCols<3>(6 * n) * skew<double>(Vec3(in.a.segment<3>(6 * n) - in.gravity));
  }
  X.noalias() += A * skew<double>(Vec3(in.q.segment<3>(6) - in.q.segment<3>(0)));
  X.noalias() -= B * R2.transpose();
  Eigen::Matrix<double, 12, 12> J;
  J.middleCols<3>(0) = -A;
  J.middleCols<3>(3).noalias() = X * (R1 * angularVelocityMap<double>(phi1));
  J.middleCols<3>(6) = A;
  J.middleCols<3>(9) = second_end.rightCols<3>();
  return J;
}

Vec3T<Dual<double, 3>> seededSecondRotation(const Eigen::Matrix<double, 12, 1>& q) {
  Vec3T<Dual<double, 3>> phi2;
  for (int k = 0; k < 3; ++k) phi2(k) = seeded<double, 3>(q(9 + k), k);
  return phi2;
}

Eigen::Matrix<double, 12, 12> objectiveCoordinateTangent(const ObjectiveTangentInput& in, Eigen::Matrix<double, 12, 1> r_elastic,
                                                         Eigen::Matrix<double, 12, 6> second_end,
                                                         const Eigen::Matrix<Dual<double, 3>, 12, 1>& inertial) {
  for (int i = 0; i < 12; ++i) {
    r_elastic(i) += inertial(i).value();
    second_end.block<1, 3>(i, 3) += inertial(i).derivatives().transpose();
  }
  return objective_detail::fromSecondEnd(in, r_elastic, second_end);
}

}  // namespace cranesim
