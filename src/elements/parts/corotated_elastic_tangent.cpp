// The co-rotated elastic tangent (corotated_elastic_tangent.hpp), compiled here once.
#include "cranesim/elements/parts/corotated_elastic_tangent.hpp"

namespace cranesim {

namespace {
using D6 = Dual<double, 6>;

/// What chordTwistRow reads of the mean frame, with its derivatives in end 2's directions
/// [δr², δθ²] (file comment; the chord itself is not needed).
MeanFrame<D6> seededMeanFrame(const MeanFrame<double>& m, const Mat3& R1) {
  MeanFrame<D6> s;
  const Mat3 Tinv = angularVelocityMapInverse<double>(m.phi);
  const Mat3 G = 0.5 * angularVelocityMap<double>(Vec3(0.5 * m.phi)) * Tinv;
  const Mat3 Pb = (Mat3::Identity() - m.b * m.b.transpose()) / m.ell;
  for (int i = 0; i < 3; ++i) {
    s.phi(i) = D6(m.phi(i));
    s.b(i) = D6(m.b(i));
    for (int j = 0; j < 3; ++j) {
      s.phi(i).derivatives()(3 + j) = Tinv(i, j);
      s.b(i).derivatives()(j) = Pb(i, j);
    }
  }
  s.ell = D6(m.ell);
  for (int j = 0; j < 3; ++j) s.ell.derivatives()(j) = m.b(j);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) s.E(i, k) = D6(m.E(i, k)), s.Rrel(i, k) = D6(m.Rrel(i, k));
  for (int j = 0; j < 3; ++j) {
    const Mat3 dE = m.E * skew<double>(Vec3(G.col(j)));
    const Mat3 dRrel = m.Rrel * skew<double>(Vec3(Vec3::Unit(j)));
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) s.E(i, k).derivatives()(3 + j) = dE(i, k), s.Rrel(i, k).derivatives()(3 + j) = dRrel(i, k);
  }
  s.Rm = R1.cast<D6>() * s.E;
  s.a = s.Rm.col(0);
  s.k = s.a.cross(s.b);
  s.one_plus_ab = D6(1.0) + s.a.dot(s.b);
  return s;
}
}  // namespace

CoRotatedElasticTangent coRotatedElasticTangent(double length, double eta, const Vec3& r1, const Mat3& R1,
                                                const Vec3& r2, const Mat3& R2, const Eigen::Matrix<double, 12, 1>& v,
                                                const Eigen::Matrix<double, 12, 12>& K) {
  using Mat3x6 = Eigen::Matrix<double, 3, 6>;
  using Mat12x6 = Eigen::Matrix<double, 12, 6>;
  using V12 = Eigen::Matrix<double, 12, 1>;
  const MeanFrame<double> m = meanFrame<double>(r1, R1, r2, R2);
  const CoRotatedTangent<double> c = coRotation<double, true>(m, R1, R2, length);
  const Eigen::Matrix<double, 12, 12> J = c.matrix();
  const Mat3x6 W2 = c.W.rightCols<6>();  // end 2's columns of W
  const bool damped = eta > 0.0;
  V12 strain = c.d;
  if (damped) strain.noalias() += eta * c.apply(v);
  const V12 s = K * strain;
  CoRotatedElasticTangent out;
  out.force = c.applyTransposed(s);

  // Row x of W in forward AD from the seeded mean frame.
  const Eigen::Matrix<D6, 1, 12> Wx = chordTwistRow<D6>(seededMeanFrame(m, R1));
  // Rows y, z of W: ∓(R_B e_z)/ℓ, ±(R_B e_y)/ℓ on δc, and their derivatives.
  const Mat3& RB = c.R;
  const Vec3 ey = RB.col(1), ez = RB.col(2);
  const Mat3 RB_ey = RB * skew<double>(Vec3(Vec3::UnitY())), RB_ez = RB * skew<double>(Vec3(Vec3::UnitZ()));
  Eigen::Matrix<double, 1, 6> chord_row = Eigen::Matrix<double, 1, 6>::Zero();  // δℓ = b·δr²
  chord_row.head<3>() = m.b.transpose();
  const Mat3 Pb = Mat3::Identity() - m.b * m.b.transpose();

  // H, and with damping Ĵ = ∂(J_d dq)/∂[δr², δθ²] (its Ω = ∂(W dq)/∂[δr², δθ²]).
  Mat12x6 Jhat = Mat12x6::Zero(), H = Mat12x6::Zero();
  Vec3 omega = Vec3::Zero();
  Mat3x6 Omega = Mat3x6::Zero();
  if (damped) {
    omega = c.W * v;
    const Vec3 v_delta = v.segment<3>(6) - v.segment<3>(0);
    for (int j = 0; j < 12; ++j) Omega.row(0) += v(j) * Wx(j).derivatives().transpose();
    Omega.row(1) = (v_delta.transpose() * RB_ez * W2 + (ez.dot(v_delta) / m.ell) * chord_row) / m.ell;
    Omega.row(2) = -(v_delta.transpose() * RB_ey * W2 + (ey.dot(v_delta) / m.ell) * chord_row) / m.ell;
    Jhat.block<1, 3>(6, 0) = (Pb * v_delta).transpose() / m.ell;
  }
  Vec3 y = Vec3::Zero();
  Vec3 z[2];
  Mat3x6 dz[2];
  for (int e = 0; e < 2; ++e) {
    const Vec3 psi = c.d.segment<3>(3 + 6 * e);
    const Mat3x6 J_psi = J.block<3, 6>(3 + 6 * e, 6);
    const Mat3& Q = c.Q[e];
    if (damped) {
      const Vec3 turned_omega = Q.transpose() * omega;
      const Vec3 h = v.segment<3>(3 + 6 * e) - turned_omega;
      Mat3x6 dturned = -Q.transpose() * skew<double>(omega) * W2 + Q.transpose() * Omega;  // δ(Qᵉᵀ ω)
      if (e == 1) dturned.rightCols<3>() += skew<double>(turned_omega);
      Jhat.middleRows<3>(3 + 6 * e) = rateMapInverseDerivative(psi, h) * J_psi - c.Tinv[e] * dturned;
    }
    z[e] = c.Tinv[e].transpose() * s.segment<3>(3 + 6 * e);
    dz[e] = rateMapInverseTransposedDerivative(psi, Vec3(s.segment<3>(3 + 6 * e))) * J_psi;
    H.middleRows<3>(3 + 6 * e) += dz[e];
    y += Q * z[e];
  }

  Mat3x6 dy = Mat3x6::Zero();  // ∂y/∂[δr², δθ²]
  for (int e = 0; e < 2; ++e) {
    const Vec3 Qz = c.Q[e] * z[e];
    dy += skew<double>(Qz) * W2 + c.Q[e] * dz[e];
    if (e == 1) dy.rightCols<3>() -= c.Q[e] * skew<double>(z[e]);
  }
  H -= c.W.transpose() * dy;
  // ∂(Wᵀ y)/∂x at y held: row x from its AD, rows y, z as n = (y_y e_z − y_z e_y)/ℓ on [δr¹; δr²] = [n; −n].
  for (int j = 0; j < 12; ++j) H.row(j) -= y(0) * Wx(j).derivatives().transpose();
  const Vec3 n = (y(1) * ez - y(2) * ey) / m.ell;
  const Mat3x6 dn = (y(2) * RB_ey - y(1) * RB_ez) * W2 / m.ell - n * chord_row / m.ell;
  H.middleRows<3>(0) -= dn;
  H.middleRows<3>(6) += dn;
  // s_u [−b; 0; b; 0]
  H.block<3, 3>(0, 0) -= (s(6) / m.ell) * Pb;
  H.block<3, 3>(6, 0) += (s(6) / m.ell) * Pb;

  // J_dᵀ K (J_d + η Ĵ) through J_d's seven non-zero rows (ψ¹, u_x, ψ²) and K between them.
  constexpr std::array<int, 7> rows{3, 4, 5, 6, 9, 10, 11};
  Eigen::Matrix<double, 7, 12> J7;
  Eigen::Matrix<double, 7, 7> K7;
  Eigen::Matrix<double, 7, 6> X7;
  for (int i = 0; i < 7; ++i) {
    J7.row(i) = J.row(rows[i]);
    X7.row(i) = J.block<1, 6>(rows[i], 6);
    if (damped) X7.row(i) += eta * Jhat.row(rows[i]);
    for (int j = 0; j < 7; ++j) K7(i, j) = K(rows[i], rows[j]);
  }
  const Eigen::Matrix<double, 7, 6> KX = K7.lazyProduct(X7);
  out.second_end = H;
  out.second_end.noalias() += J7.transpose().lazyProduct(KX);
  return out;
}

}  // namespace cranesim
