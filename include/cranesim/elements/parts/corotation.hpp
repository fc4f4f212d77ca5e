#pragma once
// The co-rotated frame R_B of a beam between two end frames and its local deformations
// d = [u¹, ψ¹, u², ψ²] (thesis 3.2.2, (3-29), (3-34)), with their tangent J_d = ∂d/∂(twist) in
// closed form (the Timoshenko beam, timoshenko_beam.hpp, and the condensed truss' frame; their
// elastic coordinate tangent, corotated_elastic_tangent.hpp). Templated on the scalar.

#include <cmath>
#include <type_traits>

#include "cranesim/math/rotation.hpp"

namespace cranesim {

/// R_B and d.
template <class S> struct CoRotated {
  Mat3T<S> R;               // R_B, body → inertial; x axis along the chord
  Eigen::Matrix<S, 12, 1> d;  // [u¹, ψ¹, u², ψ²] in R_B axes
};
/// The same with J_d = ∂d/∂(twist), d's derivatives along r + δr, R (I + δθ̃) of both ends, in
/// its factors (coRotation): the rows of ψᵉ are T(ψᵉ)⁻¹ (E_θᵉ − Qᵉᵀ W), Qᵉ = R_BᵀRᵉ and W the
/// 3 × 12 map to δω_B, the row of u²_x is b·(δr² − δr¹), the others are zero. The forces apply
/// J_d and J_dᵀ through them (a few 3 × 3 products) instead of forming the 12 × 12 matrix.
template <class S> struct CoRotatedTangent : CoRotated<S> {
  using V12 = Eigen::Matrix<S, 12, 1>;
  Eigen::Matrix<S, 3, 12> W;
  Mat3T<S> Tinv[2], Q[2];
  Vec3T<S> b;

  /// J_d x.
  V12 apply(const V12& x) const {
    const Vec3T<S> w = W * x;
    V12 out = V12::Zero();
    for (int e = 0; e < 2; ++e)
      out.template segment<3>(3 + 6 * e) = Tinv[e] * Vec3T<S>(x.template segment<3>(3 + 6 * e) - Q[e].transpose() * w);
    out(6) = b.dot(Vec3T<S>(x.template segment<3>(6) - x.template segment<3>(0)));
    return out;
  }
  /// J_dᵀ y.
  V12 applyTransposed(const V12& y) const {
    V12 out = V12::Zero();
    Vec3T<S> turned = Vec3T<S>::Zero();
    for (int e = 0; e < 2; ++e) {
      const Vec3T<S> z = Tinv[e].transpose() * y.template segment<3>(3 + 6 * e);
      out.template segment<3>(3 + 6 * e) = z;
      turned.noalias() += Q[e] * z;
    }
    out.noalias() -= W.transpose() * turned;
    out.template segment<3>(0) -= y(6) * b;
    out.template segment<3>(6) += y(6) * b;
    return out;
  }
  /// J_d as a matrix.
  Eigen::Matrix<S, 12, 12> matrix() const {
    Eigen::Matrix<S, 12, 12> Jd = Eigen::Matrix<S, 12, 12>::Zero();
    for (int e = 0; e < 2; ++e) {
      Eigen::Matrix<S, 3, 12> dtheta = -(Q[e].transpose() * W);
      dtheta.template block<3, 3>(0, 3 + 6 * e) += Mat3T<S>::Identity();
      Jd.template middleRows<3>(3 + 6 * e) = Tinv[e] * dtheta;
    }
    Jd.template block<1, 3>(6, 0) = -b.transpose();
    Jd.template block<1, 3>(6, 6) = b.transpose();
    return Jd;
  }
};

/// What the co-rotated frame is built from (coRotation): R_rel = R¹ᵀR², φ = log(R_rel),
/// E = exp(φ̃/2), the mean frame R_m = R¹E, the chord c = r² − r¹ with ℓ = ‖c‖ and b = c/ℓ,
/// a = R_m e_x, k = a × b and 1 + a·b.
template <class S> struct MeanFrame {
  Mat3T<S> Rrel, E, Rm;
  Vec3T<S> phi, chord, b, a, k;
  S ell, one_plus_ab;
};
template <class S>
MeanFrame<S> meanFrame(const Vec3T<S>& r1, const Mat3T<S>& R1, const Vec3T<S>& r2, const Mat3T<S>& R2) {
  using std::sqrt;
  MeanFrame<S> m;
  m.Rrel = R1.transpose() * R2;
  m.phi = rotationLog<S>(m.Rrel);
  m.E = rotationMatrix<S>(Vec3T<S>(S(0.5) * m.phi));
  m.Rm = R1 * m.E;
  m.chord = r2 - r1;
  m.ell = sqrt(m.chord.squaredNorm());
  m.b = m.chord / m.ell;
  m.a = m.Rm.col(0);
  m.k = m.a.cross(m.b);
  m.one_plus_ab = S(1.0) + m.a.dot(m.b);
  return m;
}

/// Row x of W, δω_B,x = W_x [δr¹, δθ¹, δr², δθ²]: the twist of the co-rotated frame about the
/// chord (coRotation), with the δθ² block (a + b)ᵀR_m G / (1 + a·b) as row-vector products.
template <class S> Eigen::Matrix<S, 1, 12> chordTwistRow(const MeanFrame<S>& m) {
  const Eigen::Matrix<S, 1, 3> twist_of_mid = ((m.a + m.b).transpose() * m.Rm) / m.one_plus_ab;
  const Eigen::Matrix<S, 1, 3> twist_of_mid_G =
      (S(0.5) * (twist_of_mid * angularVelocityMap<S>(Vec3T<S>(S(0.5) * m.phi)))) * angularVelocityMapInverse<S>(m.phi);
  const Eigen::Matrix<S, 1, 3> twist_of_chord = m.k.transpose() / (m.ell * m.one_plus_ab);
  Eigen::Matrix<S, 1, 12> row;
  row << twist_of_chord, twist_of_mid * m.E.transpose() - twist_of_mid_G * m.Rrel.transpose(), -twist_of_chord, twist_of_mid_G;
  return row;
}

/// R_B and d (3-34) of a beam of length L from its mean frame, and with kTangent J_d in closed
/// form. With δω_B the variation of R_B in its own axes (δR_B = R_B δω̃_B), c = r² − r¹, ℓ = ‖c‖,
/// b = c/ℓ, a = R_m e_x, k = a × b:
/// - the chord direction turns the x axis: δω_B,y = −(R_B e_z)·δc/ℓ, δω_B,z = (R_B e_y)·δc/ℓ;
/// - the twist about it, from R_B = A(a, b) R_m with A the smallest rotation taking a onto b,
///   whose spatial variation δα satisfies b·δα = −k·(δa + δb)/(1 + a·b):
///     δω_B,x = ((a + b)·R_m δω_m − k·δc/ℓ) / (1 + a·b),
///   δω_m = (Eᵀ − G R_relᵀ) δθ¹ + G δθ², G = ½ T(φ/2) T(φ)⁻¹, E = exp(φ̃/2), R_rel = R¹ᵀR² (B-8);
/// - ψᵉ = log(R_Bᵀ Rᵉ): δψᵉ = T(ψᵉ)⁻¹ (δθᵉ − (R_BᵀRᵉ)ᵀ δω_B);
/// - u² = R_Bᵀ c − L e_x: δu² = (b·δc, 0, 0), since R_B e_x = b exactly.
template <class S, bool kTangent>
[[gnu::flatten]] std::conditional_t<kTangent, CoRotatedTangent<S>, CoRotated<S>> coRotation(const MeanFrame<S>& m, const Mat3T<S>& R1,
                                                                          const Mat3T<S>& R2, double length) {
  const Mat3T<S> K = skew<S>(m.k);
  // Smallest rotation taking a onto b: I + k̃ + k̃²/(1 + a·b).
  const Mat3T<S> align = Mat3T<S>::Identity() + K + (K * K) / m.one_plus_ab;
  std::conditional_t<kTangent, CoRotatedTangent<S>, CoRotated<S>> c;
  c.R = align * m.Rm;
  const Mat3T<S> Q1 = c.R.transpose() * R1, Q2 = c.R.transpose() * R2;
  c.d.setZero();
  c.d.template segment<3>(3) = rotationLog<S>(Q1);
  c.d.template segment<3>(6) = c.R.transpose() * m.chord;
  c.d(6) -= length;
  c.d.template segment<3>(9) = rotationLog<S>(Q2);
  if constexpr (kTangent) {
    auto& W = c.W;  // δω_B = W [δr¹, δθ¹, δr², δθ²]
    W.row(0) = chordTwistRow<S>(m);
    const Eigen::Matrix<S, 1, 3> ey = c.R.col(1).transpose() / m.ell, ez = c.R.col(2).transpose() / m.ell;
    W.template block<1, 3>(1, 3).setZero(), W.template block<1, 3>(1, 9).setZero();
    W.template block<1, 3>(2, 3).setZero(), W.template block<1, 3>(2, 9).setZero();
    W.template block<1, 3>(1, 0) = ez, W.template block<1, 3>(1, 6) = -ez;
    W.template block<1, 3>(2, 0) = -ey, W.template block<1, 3>(2, 6) = ey;
    c.Q[0] = Q1, c.Q[1] = Q2;
    for (int e = 0; e < 2; ++e) c.Tinv[e] = angularVelocityMapInverse<S>(Vec3T<S>(c.d.template segment<3>(3 + 6 * e)));
    c.b = m.b;
  }
  return c;
}

}  // namespace cranesim
