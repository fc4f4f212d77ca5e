#pragma once
// The velocity tangent ∂(M a + F)/∂dq of material riding on an interpolated section
// (timoshenko_beam.hpp: section map H(q, ξ), its rate Ḣ along the motion), in closed form: the
// Jacobian's velocity columns at the cost of about one residual, instead of 24 residuals by
// polarization (element.hpp). The velocities are twists, so ∂(Ḣ dq)/∂dq is not 2Ḣ: the bracket
// C(dq) of the twists enters, and its terms add up to −M C over the stations, which the kernel
// subtracts once (subtractTwistBracket). The station sums (Q₁, Q₂, Y, Z, F_j, Φ_j, A_..) are
// named as in the derivation: docs/elements.md#material-on-an-interpolated-section.

#include <Eigen/Dense>

#include "cranesim/elements/parts/section_mass_matrix.hpp"
#include "cranesim/math/hermite.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {

/// M and G = ∂r/∂dq + M C(dq) of mass stations riding on the section interpolation (file
/// comment), from the end frames and their rates along the motion.
class SectionInertiaTangent : public SectionMassMatrix<double> {
 public:
  using Mat12 = Eigen::Matrix<double, 12, 12>;

  /// End rotation R¹, R_rel = R¹ᵀR², φ = log(R_rel), its rate φ̇, T(φ)⁻¹ and T(φ)⁻¹R_relᵀ with
  /// their rates, the end velocities dq and the length that scales the Hermite slopes.
  SectionInertiaTangent(const Mat3& R1, const Mat3& Rrel, const Vec3& phi, const Vec3& phi_dot, const Mat3& Tinv,
                        const Mat3& TinvRrelT, const Mat3& Tinv_dot, const Mat3& TinvRrelT_dot,
                        const Eigen::Matrix<double, 12, 1>& v, double length)
      : SectionMassMatrix<double>(R1, Rrel, phi, Tinv, length),
        phi_dot_(phi_dot),
        omega1_(v.segment<3>(3)),
        omega2_(v.segment<3>(9)),
        TinvRrelT_(TinvRrelT),
        Tinv_dot_(Tinv_dot),
        TinvRrelT_dot_(TinvRrelT_dot) {
    for (int j = 0; j < 4; ++j) F_[j].setZero(), Phi_[j].setZero();
    A_11_.setZero(), A_phi1_.setZero(), A_1phi_.setZero(), A_phiphi_.setZero();
  }

  /// Adds a mass station: mass m, first moment s and inertia J about the axis point (section
  /// axes) on the section at ξ.
  [[gnu::flatten]] void add(double xi, double mass, const Vec3& first_moment, const Mat3& inertia);

  /// G = ∂r/∂dq + M C of the stations added (file comment); its translation columns are zero.
  /// Without first moments (a beam's Gauss points) F_j, Φ_j, S_j and U_k vanish.
  Mat12 velocityTangent() const;

 private:
  Vec3 phi_dot_, omega1_, omega2_;
  Mat3 TinvRrelT_, Tinv_dot_, TinvRrelT_dot_;
  Mat3 F_[4], Phi_[4];  // Σ N_j Q₁, Σ N_j Q₂
  Mat3 A_11_, A_phi1_, A_1phi_, A_phiphi_;
  bool first_moments_ = false;  // a station with s ≠ 0 was added
};

/// G − M C(dq) in place: C has the blocks ω̃ⁿ (ωⁿ = dq's rotational velocity of node n) on the
/// diagonal of each node's rotation.
void subtractTwistBracket(const Eigen::Matrix<double, 12, 12>& M, const Eigen::Matrix<double, 12, 1>& v,
                          Eigen::Matrix<double, 12, 12>& G);

}  // namespace cranesim
