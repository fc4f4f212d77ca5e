#pragma once
// Inertial and gravity forces of material riding on the beam interpolation (timoshenko_beam.hpp:
// cubic Hermite centre line with unit end slopes Rⁱ e_x, geodesic section rotation
// R_c(ξ) = R¹ exp(ξ φ̃), φ = log(R¹ᵀR²)), M a + F_ine + F_g = Σ H_xᵀ f + H_Ωᵀ τ over mass
// stations (ξ, m, s, J):
//   f = m (ẍ − g) + R_c (Ω̇ × s + Ω × (Ω × s)),   τ = s × R_cᵀ (ẍ − g) + J Ω̇ + Ω × J Ω.
// The same sum as timoshenko_beam.hpp's sectionMotion and project, arranged so that a station
// costs a few vector operations and one small map: no 3 × 12 blocks of H, no forward-AD
// direction along the motion through the whole section map.
// - Centre line: ẍ = N₀ r̈¹ + N₂ r̈² − N₁ R¹ k¹ − N₃ R² k² with kⁿ = e_x × ω̇ⁿ + ωⁿ × (e_x × ωⁿ)
//   (H_x's blocks −N R ẽ_x and their rates −N R ω̃ ẽ_x), evaluated in the axes of end 1, where
//   R² = R¹ R_rel: every station's ẍ is a combination of four vectors fixed per call.
// - Section rotation: Ω = E_Rᵀ ω¹ + ξ E_T φ̇ and Ω̇ = Ė_Rᵀ ω¹ + E_Rᵀ ω̇¹ + ξ (Ė_T φ̇ + E_T φ̈), with
//   E_R = exp(ξφ̃), E_T = T(ξφ) (B-8), φ̇ = T(φ)⁻¹ (ω² − R_relᵀ ω¹) and
//   φ̈ = (T(φ)⁻¹)˙ (ω² − R_relᵀ ω¹) + T(φ)⁻¹ (ω̇² − R_relᵀ ω̇¹ + ω² × R_relᵀ ω¹) per call. The rates
//   Ė_R, Ė_T along ξφ̇ in closed form (rotationAndRateMapRates), (T(φ)⁻¹)˙ by one forward-AD
//   direction through that 3 × 3 map, once per call.
// - Projection: H_xᵀ f has the rows N₀ f, N₁ e_x × R¹ᵀ f, N₂ f, N₃ e_x × R²ᵀ f and H_Ωᵀ τ the rows
//   E_R τ − ξ R_rel T(φ)⁻ᵀ E_Tᵀ τ and ξ T(φ)⁻ᵀ E_Tᵀ τ: sums over the stations of f (in the axes of
//   end 1) weighted by N₀…N₃, of E_R τ and of ξ E_Tᵀ τ, turned once per call.
// Scalars: templated on S (double for the residual, a dual number for the Jacobian's coordinate
// columns, section_inertia_tangent.hpp).

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
    using P = Dual<S, 1>;
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
    // T(φ)⁻¹ and its rate along φ̇ (one direction through the 3 × 3 map).
    Vec3T<P> phi_path;
    const Mat3T<S> Tinv = angularVelocityMapInverse<S>(phi_);
    phi_dot_ = Tinv * relative;
    for (int i = 0; i < 3; ++i) phi_path(i) = P(phi_(i), Eigen::Matrix<S, 1, 1>(phi_dot_(i)));
    const Vec3T<P> rate = angularVelocityMapInverse<P>(phi_path) * relative.template cast<P>();
    Vec3T<S> Tinv_dot_relative;
    for (int i = 0; i < 3; ++i) Tinv_dot_relative(i) = rate(i).derivatives()(0);
    phi_ddot_ = Tinv_dot_relative + Tinv * Vec3T<S>(dw2 - Rrel_.transpose() * dw1 + w2.cross(Vec3T<S>(Rrel_.transpose() * w1)));
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
  void add(double xi, double mass, const Vec3& first_moment, const Mat3& inertia) {
    const HermiteBasis h = hermiteBasis(xi, length_);
    const Vec3T<S> s = first_moment.cast<S>();
    const Mat3T<S> J = inertia.cast<S>();
    const Section m = sectionRotation(xi);
    const Vec3T<S> xdd_g = relativeAcceleration(h);
    const Vec3T<S> y = m.domega.cross(s) + m.omega.cross(Vec3T<S>(m.omega.cross(s)));
    const Vec3T<S> f = S(mass) * xdd_g + m.R * y;  // R¹ᵀ f
    const Vec3T<S> tau = s.cross(Vec3T<S>(m.R.transpose() * xdd_g)) + J * m.domega + m.omega.cross(Vec3T<S>(J * m.omega));
    accumulate(xi, h, f, m, tau);
  }

  /// A station without first moment and with principal inertia J = diag(j) (a beam's section).
  void add(double xi, double mass, const Vec3& j) {
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

 private:
  struct Section {
    Mat3T<S> R, T;           // E_R = exp(ξφ̃): the section's rotation in the axes of end 1; E_T = T(ξφ)
    Vec3T<S> omega, domega;  // Ω, Ω̇ (section axes)
  };

  /// R¹ᵀ (ẍ − g) of the centre line at the station with Hermite basis h.
  Vec3T<S> relativeAcceleration(const HermiteBasis& h) const {
    return S(h.N[0]) * acc1_ + S(h.N[2]) * acc2_ - S(h.N[1]) * k1_ - S(h.N[3]) * k2_ - g1_;
  }

  Section sectionRotation(double xi) const {
    const RotationAndRateMapRates<S> E = rotationAndRateMapRates<S>(Vec3T<S>(S(xi) * phi_), Vec3T<S>(S(xi) * phi_dot_));
    Section out{E.R, E.T, Vec3T<S>(), Vec3T<S>()};
    out.omega = E.R.transpose() * omega1_ + S(xi) * (E.T * phi_dot_);
    out.domega = E.R_dot.transpose() * omega1_ + E.R.transpose() * domega1_ + S(xi) * (E.T_dot * phi_dot_ + E.T * phi_ddot_);
    return out;
  }

  void accumulate(double xi, const HermiteBasis& h, const Vec3T<S>& f, const Section& m, const Vec3T<S>& tau) {
    f0_ += S(h.N[0]) * f;
    f1_ += S(h.N[1]) * f;
    f2_ += S(h.N[2]) * f;
    f3_ += S(h.N[3]) * f;
    turned_ += m.R * tau;
    twisted_ += S(xi) * (m.T.transpose() * tau);
  }

  double length_;
  Mat3T<S> R1_, Rrel_, TinvT_;
  Vec3T<S> omega1_, domega1_, phi_, phi_dot_, phi_ddot_;
  Vec3T<S> acc1_, acc2_, k1_, k2_, g1_;
  Vec3T<S> f0_, f1_, f2_, f3_;  // Σ Nᵢ R¹ᵀ f
  Vec3T<S> turned_, twisted_;   // Σ E_R τ, Σ ξ E_Tᵀ τ
};

}  // namespace cranesim
