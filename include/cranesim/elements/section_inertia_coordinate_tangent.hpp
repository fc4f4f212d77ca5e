#pragma once
// The coordinate columns of the section inertia (section_inertia_forces.hpp) in end 2's three
// rotation directions, with the stations differentiated in closed form (objective_tangent.hpp
// builds the other nine columns from these). A station costs ~5 residual stations (≈ 4 200
// instructions, 16 % fewer than forward AD through it): the products below, with the skew
// products as cross products, are most of it.
//
// The per-call part (φ, φ̇, φ̈, R_rel k², R_rel, T(φ)⁻ᵀ as functions of end 2's rotation vector)
// stays in forward AD, once per call. A station then needs the derivatives of its f and τ with
// respect to ψ = ξφ, ψ̇ = ξφ̇, ψ̈ = ξφ̈ and k², carried as 3 × 3 matrices (one column per seeded
// direction; ′ marks them). With E_R = exp(ψ̃), E_T = T(ψ) and its coefficients a, b, c
// (rotation.hpp), and since δE_R = E_R (E_T δψ)~:
//   (E_R x)′ = E_R (x′ − x̃ E_T ψ′),   (E_Rᵀ x)′ = E_Rᵀ x′ + (E_Rᵀ x)~ E_T ψ′,
//   (E_T x)′ = E_T x′ + D_T(x) ψ′,    D_T(x) = 2(c′ ψ×(ψ×x) − b′ ψ×x) ψᵀ + b x̃ − c ((ψ×x)~ + ψ̃ x̃),
//   (E_Tᵀ x)′ = E_Tᵀ x′ + D_Tᵀ(x) ψ′, D_Tᵀ(x) = 2(c′ ψ×(ψ×x) + b′ ψ×x) ψᵀ − b x̃ − c ((ψ×x)~ + ψ̃ x̃),
// and for Z = Ė_T ψ̇ = 2σ (c′ pp − b′ p) + c ψ̇ × p (σ = ψ·ψ̇, p = ψ × ψ̇, pp = ψ × p):
//   ∂Z/∂ψ = 2(c′ pp − b′ p) ψ̇ᵀ + 2σ (2(c″ pp − b″ p) ψᵀ − c′ (p̃ + ψ̃ ψ̇̃) + b′ ψ̇̃) + 2c′ (ψ̇ × p) ψᵀ − c ψ̇̃ ψ̇̃,
//   ∂Z/∂ψ̇ = 2(c′ pp − b′ p) ψᵀ + 2σ (c′ ψ̃² − b′ ψ̃) + c (ψ̇̃ ψ̃ − p̃).
// The rest is products: Ω = E_Rᵀ ω¹ + E_T ψ̇, Ω̇ = (E_Rᵀ ω¹) × E_T ψ̇ + E_Rᵀ ω̇¹ + Z + E_T ψ̈, f and τ
// as in section_inertia_forces.hpp, and the sums Σ Nᵢ f, Σ E_R τ, Σ ξ E_Tᵀ τ with their
// derivatives, turned by the per-call maps in forward AD (SectionInertiaForces::forces).

#include "cranesim/elements/section_inertia_forces.hpp"

namespace cranesim {

class SectionInertiaCoordinateTangent : public SectionInertiaForces<Dual<double, 3>> {
 public:
  using D = Dual<double, 3>;
  using Base = SectionInertiaForces<D>;

  /// As SectionInertiaForces<D>: end rotations with the seeded directions in R², velocities,
  /// accelerations (or none), gravity and length.
  SectionInertiaCoordinateTangent(const Mat3T<D>& R1, const Mat3T<D>& R2, const V12& v, const V12* a, const Vec3& gravity,
                                  double length)
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

  /// Adds a mass station (SectionInertiaForces::add) with its derivatives. Products with skew
  /// matrices are taken as cross products (crossColumns, skewTimesSkew).
  [[gnu::flatten]] void add(double xi, double mass, const Vec3& s, const Mat3& J) {
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

  /// A station without first moment and with principal inertia J = diag(j) (a beam's section).
  void add(double xi, double mass, const Vec3& j) { add(xi, mass, Vec3::Zero(), Mat3(j.asDiagonal())); }

  /// H_xᵀ f + H_Ωᵀ τ summed over the stations added, with its derivatives in the seeded directions.
  V12 forces() {
    Vec3T<D>* sums[4] = {&f0_, &f1_, &f2_, &f3_};
    for (int n = 0; n < 4; ++n) *sums[n] = dual(f_[n], F_[n]);
    turned_ = dual(turned_plain_, Turned_);
    twisted_ = dual(twisted_plain_, Twisted_);
    return Base::forces();
  }

 private:
  /// ṽ M: v × each column of M.
  static Mat3 crossColumns(const Vec3& v, const Mat3& M) {
    Mat3 out;
    for (int j = 0; j < 3; ++j) out.col(j) = v.cross(Vec3(M.col(j)));
    return out;
  }
  /// ã b̃ = b aᵀ − (a·b) I.
  static Mat3 skewTimesSkew(const Vec3& a, const Vec3& b) {
    Mat3 out = b * a.transpose();
    out.diagonal().array() -= a.dot(b);
    return out;
  }
  static void split(const Vec3T<D>& x, Vec3& value, Mat3& derivatives) {
    for (int i = 0; i < 3; ++i) value(i) = x(i).value(), derivatives.row(i) = x(i).derivatives().transpose();
  }
  static Vec3T<D> dual(const Vec3& value, const Mat3& derivatives) {
    Vec3T<D> out;
    for (int i = 0; i < 3; ++i) out(i) = D(value(i), derivatives.row(i).transpose());
    return out;
  }

  Vec3 phi_plain_, phi_dot_plain_, phi_ddot_plain_, k2_plain_;
  Mat3 Phi_, Phi_dot_, Phi_ddot_, K2_;
  Vec3 omega1_plain_, domega1_plain_, acc1_plain_, acc2_plain_, k1_plain_, g1_plain_;
  Vec3 f_[4], turned_plain_, twisted_plain_;
  Mat3 F_[4], Turned_, Twisted_;
};

}  // namespace cranesim
