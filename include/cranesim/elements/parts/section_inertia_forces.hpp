#pragma once
// Inertial and gravity forces of material riding on the beam interpolation (timoshenko_beam.hpp:
// cubic Hermite centre line with unit end slopes Rⁱ e_x, geodesic section rotation
// R_c(ξ) = R¹ exp(ξ φ̃), φ = log(R¹ᵀR²)), M a + F_ine + F_g = Σ H_xᵀ f + H_Ωᵀ τ over mass
// stations (ξ, m, s, J):
//   f = m (ẍ − g) + R_c (Ω̇ × s + Ω × (Ω × s)),   τ = s × R_cᵀ (ẍ − g) + J Ω̇ + Ω × J Ω.
// The sum Σ H_xᵀ f + H_Ωᵀ τ of section_inertia_tangent.hpp's maps, arranged so that a station
// costs a few vector operations and one small map: no 3 × 12 blocks of H, no forward-AD
// direction along the motion through the whole section map.
// - Centre line: ẍ = N₀ r̈¹ + N₂ r̈² − N₁ R¹ k¹ − N₃ R² k² with kⁿ = e_x × ω̇ⁿ + ωⁿ × (e_x × ωⁿ)
//   (H_x's blocks −N R ẽ_x and their rates −N R ω̃ ẽ_x), evaluated in the axes of end 1, where
//   R² = R¹ R_rel: every station's ẍ is a combination of four vectors fixed per call.
// - Section rotation: with ψ = ξφ, E_R = exp(ψ̃), E_T = T(ψ) (B-8), ω_E = E_T ψ̇ (the body rate of
//   E_R(ψ(t))), φ̇ = T(φ)⁻¹ (ω² − R_relᵀ ω¹) and
//   φ̈ = (T(φ)⁻¹)˙ (ω² − R_relᵀ ω¹) + T(φ)⁻¹ (ω̇² − R_relᵀ ω̇¹ + ω² × R_relᵀ ω¹) per call, where
//   (T(φ)⁻¹)˙ (ω² − R_relᵀ ω¹) = −T(φ)⁻¹ Ṫ φ̇ with Ṫ φ̇ as Ė_T ψ̇ below (ψ = φ),
//     Ω = E_Rᵀ ω¹ + ω_E,   Ω̇ = (E_Rᵀ ω¹) × ω_E + E_Rᵀ ω̇¹ + Ė_T ψ̇ + E_T ψ̈,
//   since Ė_R = E_R ω̃_E, and with the coefficients a, b, c of expCoefficients (rotation.hpp)
//     Ė_T ψ̇ = 2(ψ·ψ̇)(c' ψ × (ψ × ψ̇) − b' ψ × ψ̇) + c ψ̇ × (ψ × ψ̇).
//   E_R, E_T never become matrices: each product with them is two cross products,
//   E_R x = x + a ψ × x + b ψ × (ψ × x), E_T x = x − b ψ × x + c ψ × (ψ × x).
// - Projection: H_xᵀ f has the rows N₀ f, N₁ e_x × R¹ᵀ f, N₂ f, N₃ e_x × R²ᵀ f and H_Ωᵀ τ the rows
//   E_R τ − ξ R_rel T(φ)⁻ᵀ E_Tᵀ τ and ξ T(φ)⁻ᵀ E_Tᵀ τ: sums over the stations of f (in the axes of
//   end 1) weighted by N₀…N₃, of E_R τ and of ξ E_Tᵀ τ, turned once per call.
// Scalars: templated on S (double for the residual; a dual number for the per-call part of the
// Jacobian's coordinate columns, section_inertia_coordinate_tangent.hpp, whose stations are
// differentiated in closed form, and for the tests' forward-AD reference of those).

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/hermite.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {

template <class S> class SectionInertiaForces {
 public:
  using V12 = Eigen::Matrix<S, 12, 1>;

  /// End rotations R¹, R² (the forces do not depend on the end positions), velocities
  /// dq = [ṙ¹, ω¹, ṙ², ω²], accelerations d(dq)/dt (or none: F without M a), gravity, and the
  /// length that scales the Hermite slopes.
  SectionInertiaForces(const Mat3T<S>& R1, const Mat3T<S>& R2, const V12& v, const V12* a, const Vec3& gravity,
                       double length)
      : length_(length), R1_(R1), Rrel_(R1.transpose() * R2) {
    const Vec3T<S> w1 = v.template segment<3>(3), w2 = v.template segment<3>(9);
    Vec3T<S> dw1 = Vec3T<S>::Zero(), dw2 = Vec3T<S>::Zero(), acc1 = Vec3T<S>::Zero(), acc2 = Vec3T<S>::Zero();
    if (a) {
      acc1 = a->template segment<3>(0), dw1 = a->template segment<3>(3);
      acc2 = a->template segment<3>(6), dw2 = a->template segment<3>(9);
    }
    omega1_ = w1;
    domega1_ = dw1;
    phi_ = rotationLog<S>(Rrel_);
    const Vec3T<S> relative = w2 - Rrel_.transpose() * w1;  // ω² − R_relᵀ ω¹
    const Mat3T<S> Tinv = angularVelocityMapInverse<S>(phi_);
    phi_dot_ = Tinv * relative;
    const Vec3T<S> pd = phi_.cross(phi_dot_);
    const Vec3T<S> T_dot_phi_dot = rateMapRate(phi_dot_, pd, Vec3T<S>(phi_.cross(pd)), S(phi_.dot(phi_dot_)),
                                               expCoefficients<S>(S(phi_.squaredNorm())));
    phi_ddot_ = Tinv * Vec3T<S>(dw2 - Rrel_.transpose() * dw1 + w2.cross(Vec3T<S>(Rrel_.transpose() * w1)) - T_dot_phi_dot);
    TinvT_ = Tinv.transpose();
    // ẍ in the axes of end 1: N₀ A¹ + N₂ A² − N₁ k¹ − N₃ R_rel k².
    const Vec3 ex = Vec3::UnitX();
    const auto k = [&](const Vec3T<S>& w, const Vec3T<S>& dw) {
      return Vec3T<S>(Vec3T<S>(ex.cast<S>().cross(dw)) + w.cross(Vec3T<S>(ex.cast<S>().cross(w))));
    };
    acc1_ = R1.transpose() * acc1;
    acc2_ = R1.transpose() * acc2;
    k1_ = k(w1, dw1);
    k2_ = Rrel_ * k(w2, dw2);
    g1_ = R1.transpose() * gravity.cast<S>();
    for (Vec3T<S>* sum : {&f0_, &f1_, &f2_, &f3_, &turned_, &twisted_}) sum->setZero();
  }

  /// Adds a mass station: mass m, first moment s and inertia J about the axis point (section
  /// axes) on the section at ξ.
  [[gnu::flatten]] void add(double xi, double mass, const Vec3& first_moment, const Mat3& inertia) {
    const HermiteBasis h = hermiteBasis(xi, length_);
    const Vec3T<S> s = first_moment.cast<S>();
    const Mat3T<S> J = inertia.cast<S>();
    const Section m = sectionRotation(xi);
    const Vec3T<S> xdd_g = relativeAcceleration(h);
    const Vec3T<S> y = m.domega.cross(s) + m.omega.cross(Vec3T<S>(m.omega.cross(s)));
    const Vec3T<S> f = S(mass) * xdd_g + m.rotate(y);  // R¹ᵀ f
    const Vec3T<S> tau = s.cross(m.rotateBack(xdd_g)) + J * m.domega + m.omega.cross(Vec3T<S>(J * m.omega));
    accumulate(xi, h, f, m, tau);
  }

  /// A station without first moment and with principal inertia J = diag(j) (a beam's section).
  [[gnu::flatten]] void add(double xi, double mass, const Vec3& j) {
    const HermiteBasis h = hermiteBasis(xi, length_);
    const Section m = sectionRotation(xi);
    const Vec3T<S> xdd_g = relativeAcceleration(h);
    const Vec3T<S> J = j.cast<S>();
    const Vec3T<S> Jw = J.cwiseProduct(m.omega);
    accumulate(xi, h, Vec3T<S>(S(mass) * xdd_g), m, Vec3T<S>(J.cwiseProduct(m.domega) + m.omega.cross(Jw)));
  }

  /// H_xᵀ f + H_Ωᵀ τ summed over the stations added.
  V12 forces() const {
    V12 out;
    const Vec3T<S> ex = Vec3::UnitX().cast<S>();
    const Vec3T<S> twist = TinvT_ * twisted_;  // T(φ)⁻ᵀ Σ ξ E_Tᵀ τ
    out.template segment<3>(0) = R1_ * f0_;
    out.template segment<3>(3) = ex.cross(f1_) + turned_ - Rrel_ * twist;
    out.template segment<3>(6) = R1_ * f2_;
    out.template segment<3>(9) = ex.cross(Vec3T<S>(Rrel_.transpose() * f3_)) + twist;
    return out;
  }

 protected:
  /// The section at ξ: E_R = exp(ψ̃) with ψ = ξφ, applied through its coefficients, and Ω, Ω̇.
  struct Section {
    Vec3T<S> psi;
    S a, b, c;
    Vec3T<S> omega, domega;  // Ω, Ω̇ (section axes)

    Vec3T<S> rotate(const Vec3T<S>& x) const {  // E_R x
      const Vec3T<S> px = psi.cross(x);
      return x + a * px + b * Vec3T<S>(psi.cross(px));
    }
    Vec3T<S> rotateBack(const Vec3T<S>& x) const {  // E_Rᵀ x
      const Vec3T<S> px = psi.cross(x);
      return x - a * px + b * Vec3T<S>(psi.cross(px));
    }
    Vec3T<S> rateMap(const Vec3T<S>& x) const {  // E_T x
      const Vec3T<S> px = psi.cross(x);
      return x - b * px + c * Vec3T<S>(psi.cross(px));
    }
    Vec3T<S> rateMapTransposed(const Vec3T<S>& x) const {  // E_Tᵀ x
      const Vec3T<S> px = psi.cross(x);
      return x + b * px + c * Vec3T<S>(psi.cross(px));
    }
  };

  /// R¹ᵀ (ẍ − g) of the centre line at the station with Hermite basis h.
  Vec3T<S> relativeAcceleration(const HermiteBasis& h) const {
    return S(h.N[0]) * acc1_ + S(h.N[2]) * acc2_ - S(h.N[1]) * k1_ - S(h.N[3]) * k2_ - g1_;
  }

  Section sectionRotation(double xi) const {
    const Vec3T<S> psi = S(xi) * phi_, psi_dot = S(xi) * phi_dot_;
    const ExpCoefficients<S> k = expCoefficients<S>(S(psi.squaredNorm()));
    Section out{psi, k.a, k.b, k.c, Vec3T<S>(), Vec3T<S>()};
    const Vec3T<S> pd = psi.cross(psi_dot), ppd = psi.cross(pd);
    const Vec3T<S> omega_E = psi_dot - k.b * pd + k.c * ppd;
    const Vec3T<S> Tdot_psi_dot = rateMapRate(psi_dot, pd, ppd, S(psi.dot(psi_dot)), k);
    const Vec3T<S> turned = out.rotateBack(omega1_);
    out.omega = turned + omega_E;
    out.domega = turned.cross(omega_E) + out.rotateBack(domega1_) + Tdot_psi_dot + out.rateMap(Vec3T<S>(S(xi) * phi_ddot_));
    return out;
  }

  /// Ė_T ψ̇, the rate of T(ψ) along ψ̇ applied to ψ̇ (file comment), from pd = ψ × ψ̇,
  /// ppd = ψ × pd, ψ·ψ̇ and the coefficients k at |ψ|².
  static Vec3T<S> rateMapRate(const Vec3T<S>& psi_dot, const Vec3T<S>& pd, const Vec3T<S>& ppd, const S& psi_dot_psi,
                              const ExpCoefficients<S>& k) {
    return S(2.0 * psi_dot_psi) * Vec3T<S>(k.dc * ppd - k.db * pd) + k.c * Vec3T<S>(psi_dot.cross(pd));
  }

  void accumulate(double xi, const HermiteBasis& h, const Vec3T<S>& f, const Section& m, const Vec3T<S>& tau) {
    f0_ += S(h.N[0]) * f;
    f1_ += S(h.N[1]) * f;
    f2_ += S(h.N[2]) * f;
    f3_ += S(h.N[3]) * f;
    turned_ += m.rotate(tau);
    twisted_ += S(xi) * m.rateMapTransposed(tau);
  }

  double length_;
  Mat3T<S> R1_, Rrel_, TinvT_;
  Vec3T<S> omega1_, domega1_, phi_, phi_dot_, phi_ddot_;
  Vec3T<S> acc1_, acc2_, k1_, k2_, g1_;
  Vec3T<S> f0_, f1_, f2_, f3_;  // Σ Nᵢ R¹ᵀ f
  Vec3T<S> turned_, twisted_;   // Σ E_R τ, Σ ξ E_Tᵀ τ
};

}  // namespace cranesim
