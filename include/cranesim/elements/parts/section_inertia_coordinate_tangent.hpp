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

#include "cranesim/elements/parts/section_inertia_forces.hpp"

namespace cranesim {

class SectionInertiaCoordinateTangent : public SectionInertiaForces<Dual<double, 3>> {
 public:
  using D = Dual<double, 3>;
  using Base = SectionInertiaForces<D>;

  /// As SectionInertiaForces<D>: end rotations with the seeded directions in R², velocities,
  /// accelerations (or none), gravity and length.
  SectionInertiaCoordinateTangent(const Mat3T<D>& R1, const Mat3T<D>& R2, const V12& v, const V12* a, const Vec3& gravity,
                                  double length);

  /// Adds a mass station (SectionInertiaForces::add) with its derivatives. Products with skew
  /// matrices are taken as cross products (crossColumns, skewTimesSkew).
  [[gnu::flatten]] void add(double xi, double mass, const Vec3& s, const Mat3& J);

  /// A station without first moment and with principal inertia J = diag(j) (a beam's section).
  void add(double xi, double mass, const Vec3& j) { add(xi, mass, Vec3::Zero(), Mat3(j.asDiagonal())); }

  /// H_xᵀ f + H_Ωᵀ τ summed over the stations added, with its derivatives in the seeded directions.
  V12 forces();

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
