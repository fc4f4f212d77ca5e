// The section inertia's coordinate tangent (section_inertia_coordinate_tangent.hpp), compiled
// here once.
#include "cranesim/elements/parts/section_inertia_coordinate_tangent.hpp"

namespace cranesim {

SectionInertiaCoordinateTangent::SectionInertiaCoordinateTangent(const Mat3T<D>& R1, const Mat3T<D>& R2, const V12& v,
                                                                 const V12* a, const Vec3& gravity, double length)
    : Base(R1, R2, v, a, gravity, length) {
  split(phi_, phi_plain_, Phi_);
  split(phi_dot_, phi_dot_plain_, Phi_dot_);
  split(phi_ddot_, phi_ddot_plain_, Phi_ddot_);
  split(k2_, k2_plain_, K2_);
  Mat3 unused;
  split(omega1_, omega1_plain_, unused);
  split(domega1_, domega1_plain_, unused);
  split(acc1_, acc1_plain_, unused);
  split(acc2_, acc2_plain_, unused);
  split(k1_, k1_plain_, unused);
  split(g1_, g1_plain_, unused);
  for (int n = 0; n < 4; ++n) f_[n].setZero(), F_[n].setZero();
  turned_plain_.setZero(), twisted_plain_.setZero(), Turned_.setZero(), Twisted_.setZero();
}

void SectionInertiaCoordinateTangent::add(double xi, double mass, const Vec3& s, const Mat3& J) {
  const HermiteBasis h = hermiteBasis(xi, length_);
  const Vec3 psi = xi * phi_plain_, psi_dot = xi * phi_dot_plain_, psi_ddot = xi * phi_ddot_plain_;
  const Mat3 P1 = xi * Phi_, P2 = xi * Phi_dot_, P3 = xi * Phi_ddot_;  // ψ′, ψ̇′, ψ̈′
  const double t2 = psi.squaredNorm();
  const ExpCoefficients<double> k = expCoefficients<double>(t2);
  const Mat3 Ps = skew<double>(psi), Ps2 = skewTimesSkew(psi, psi);
  const Mat3 R = Mat3::Identity() + k.a * Ps + k.b * Ps2, T = Mat3::Identity() - k.b * Ps + k.c * Ps2;
  const Mat3 TP = T * P1;  // E_T ψ′
  const auto rateMapDerivative = [&](const Vec3& x, double sign) {  // D_T(x) (sign −1), D_Tᵀ(x) (+1)
    const Vec3 px = psi.cross(x), ppx = psi.cross(px);
    return Mat3(2.0 * (k.dc * ppx + sign * k.db * px) * psi.transpose() - sign * k.b * skew<double>(x) -
                k.c * (skew<double>(px) + skewTimesSkew(psi, x)));
  };
  // Ω and its derivative.
  const Vec3 omega_E = T * psi_dot;
  const Mat3 Omega_E = T * P2 + rateMapDerivative(psi_dot, -1.0) * P1;
  const Vec3 turned = R.transpose() * omega1_plain_;
  const Mat3 Turned = crossColumns(turned, TP);
  const Vec3 omega = turned + omega_E;
  const Mat3 Omega = Turned + Omega_E;
  // Ω̇ and its derivative, Z = Ė_T ψ̇ in the file comment.
  const Vec3 p = psi.cross(psi_dot), pp = psi.cross(p), zc = k.dc * pp - k.db * p;
  const double sigma = psi.dot(psi_dot);
  const ExpCoefficientCurvatures kk = expCoefficientCurvatures(t2, k);
  const Mat3 Sd = skew<double>(psi_dot), Sp = skew<double>(p);
  const Mat3 Z_psi = 2.0 * zc * psi_dot.transpose() +
                     2.0 * sigma * (2.0 * (kk.ddc * pp - kk.ddb * p) * psi.transpose() - k.dc * (Sp + skewTimesSkew(psi, psi_dot)) + k.db * Sd) +
                     2.0 * k.dc * psi_dot.cross(p) * psi.transpose() - k.c * skewTimesSkew(psi_dot, psi_dot);
  const Mat3 Z_psi_dot = 2.0 * zc * psi.transpose() + 2.0 * sigma * (k.dc * Ps2 - k.db * Ps) + k.c * (skewTimesSkew(psi_dot, psi) - Sp);
  const Vec3 turned_rate = R.transpose() * domega1_plain_;
  const Vec3 domega = turned.cross(omega_E) + turned_rate + 2.0 * sigma * zc + k.c * psi_dot.cross(p) + T * psi_ddot;
  const Mat3 dOmega = crossColumns(turned, Omega_E) - crossColumns(omega_E, Turned) + crossColumns(turned_rate, TP) +
                      (Z_psi + rateMapDerivative(psi_ddot, -1.0)) * P1 + Z_psi_dot * P2 + T * P3;
  // f and τ (section_inertia_forces.hpp) and their derivatives.
  const Vec3 x = h.N[0] * acc1_plain_ + h.N[2] * acc2_plain_ - h.N[1] * k1_plain_ - h.N[3] * k2_plain_ - g1_plain_;
  const Mat3 X = -h.N[3] * K2_;
  const Vec3 omega_s = omega.cross(s);
  const Vec3 y = domega.cross(s) + omega.cross(omega_s);
  const Mat3 Y = -crossColumns(s, dOmega) - crossColumns(omega_s, Omega) - crossColumns(omega, crossColumns(s, Omega));
  const Vec3 f = mass * x + R * y;
  const Mat3 F = mass * X + R * (Y - crossColumns(y, TP));
  const Vec3 u = R.transpose() * x;
  const Mat3 U = R.transpose() * X + crossColumns(u, TP);
  const Vec3 J_omega = J * omega;
  const Vec3 tau = s.cross(u) + J * domega + omega.cross(J_omega);
  const Mat3 Tau = crossColumns(s, U) + J * dOmega + crossColumns(omega, Mat3(J * Omega)) - crossColumns(J_omega, Omega);
  for (int n = 0; n < 4; ++n) f_[n] += h.N[n] * f, F_[n] += h.N[n] * F;
  turned_plain_ += R * tau;
  Turned_ += R * (Tau - crossColumns(tau, TP));
  twisted_plain_ += xi * (T.transpose() * tau);
  Twisted_ += xi * (T.transpose() * Tau + rateMapDerivative(tau, 1.0) * P1);
}

auto SectionInertiaCoordinateTangent::forces() -> V12 {
  Vec3T<D>* sums[4] = {&f0_, &f1_, &f2_, &f3_};
  for (int n = 0; n < 4; ++n) *sums[n] = dual(f_[n], F_[n]);
  turned_ = dual(turned_plain_, Turned_);
  twisted_ = dual(twisted_plain_, Twisted_);
  return Base::forces();
}

}  // namespace cranesim
