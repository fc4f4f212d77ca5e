// The section inertia's velocity tangent (section_inertia_tangent.hpp), compiled here once.
#include "cranesim/elements/parts/section_inertia_tangent.hpp"

namespace cranesim {

void subtractTwistBracket(const Eigen::Matrix<double, 12, 12>& M, const Eigen::Matrix<double, 12, 1>& v,
                          Eigen::Matrix<double, 12, 12>& G) {
  for (int n = 0; n < 2; ++n)
    G.middleCols<3>(6 * n + 3).noalias() -= M.middleCols<3>(6 * n + 3) * skew<double>(Vec3(v.segment<3>(6 * n + 3)));
}

void SectionInertiaTangent::add(double xi, double mass, const Vec3& first_moment, const Mat3& inertia) {
  const HermiteBasis h = hermiteBasis(xi, length_);
  const Vec3 psi_dot = xi * phi_dot_;
  const RotationAndRateMapRates<double> E = rotationAndRateMapRates<double>(Vec3(xi * phi_), psi_dot);
  addStation(h, xi, E.R, E.T, mass, first_moment, inertia);
  const Mat3& J = inertia;
  const Vec3 omega_E = E.T * psi_dot;
  const Vec3 omega = E.R.transpose() * omega1_ + omega_E;
  const Mat3 We = skew<double>(omega_E), W = skew<double>(omega);
  const Mat3 g_tau = J * W + W * J - skew<double>(Vec3(J * omega));
  const Mat3 Y = (g_tau - 2.0 * (J * We)) * E.R.transpose();
  const Mat3 Z = 2.0 * (J * E.T_dot) + g_tau * E.T;
  A_11_.noalias() += E.R * Y;
  A_phi1_.noalias() += xi * (E.T.transpose() * Y);
  A_1phi_.noalias() += xi * (E.R * Z);
  A_phiphi_.noalias() += (xi * xi) * (E.T.transpose() * Z);
  if (first_moment == Vec3::Zero()) return;
  first_moments_ = true;
  const Mat3 Ss = skew<double>(first_moment);
  const Mat3 K = skew<double>(Vec3(omega.cross(first_moment))) + W * Ss + Ss * W;
  const Mat3 Q1 = E.R * (2.0 * (Ss * We) - K) * E.R.transpose();
  const Mat3 Q2 = -xi * (E.R * (2.0 * (Ss * E.T_dot) + K * E.T));
  for (int j = 0; j < 4; ++j) {
    F_[j] += h.N[j] * Q1;
    Phi_[j] += h.N[j] * Q2;
  }
}

auto SectionInertiaTangent::velocityTangent() const -> Mat12 {
  const Mat3 ex = skew<double>(Vec3(Vec3::UnitX()));
  const Mat3 Y1 = -(skew<double>(omega1_) * ex), Y3 = -(Rrel_ * (skew<double>(omega2_) * ex));
  // The two column blocks (rotations of ends 1, 2) of a row block; add() adds A P₁ + B P_φ + C Ṗ_φ.
  struct Columns {
    Mat3 c[2];
  };
  const auto add = [&](Columns& x, const Mat3& A, const Mat3& B, const Mat3& C) {
    x.c[0] += A - B * TinvRrelT_ - C * TinvRrelT_dot_;
    x.c[1] += B * Tinv_ + C * Tinv_dot_;
  };
  Columns row[4];
  for (int j = 0; j < 4; ++j) {
    row[j].c[0] = (2.0 * mu(j, 1)) * Y1, row[j].c[1] = (2.0 * mu(j, 3)) * Y3;
    if (first_moments_) add(row[j], F_[j], Phi_[j], Mat3(-2.0 * S_[j]));
  }
  Columns turn{{Mat3::Zero(), Mat3::Zero()}}, twist{{Mat3::Zero(), Mat3::Zero()}};
  add(turn, A_11_, A_1phi_, Mat3(2.0 * A01_));
  add(twist, A_phi1_, A_phiphi_, Mat3(2.0 * A11_));
  if (first_moments_) {
    turn.c[0].noalias() += 2.0 * (skew<double>(U_[1]) * Y1), turn.c[1].noalias() += 2.0 * (skew<double>(U_[3]) * Y3);
    twist.c[0].noalias() -= 2.0 * (S_[1].transpose() * Y1), twist.c[1].noalias() -= 2.0 * (S_[3].transpose() * Y3);
  }
  const Mat3 L3 = ex * Rrel_.transpose();
  Mat12 G = Mat12::Zero();
  for (int n = 0; n < 2; ++n) {
    G.block<3, 3>(0, 6 * n + 3).noalias() = R1_ * row[0].c[n];
    G.block<3, 3>(3, 6 * n + 3).noalias() = ex * row[1].c[n] + turn.c[n] - TinvRrelT_.transpose() * twist.c[n];
    G.block<3, 3>(6, 6 * n + 3).noalias() = R1_ * row[2].c[n];
    G.block<3, 3>(9, 6 * n + 3).noalias() = L3 * row[3].c[n] + Tinv_.transpose() * twist.c[n];
  }
  return G;
}

}  // namespace cranesim
