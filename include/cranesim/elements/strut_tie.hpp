#pragma once
// Two-node strut tie (thesis 3.2, C.3): axial stress only, linear interpolation between the
// end points (3-17, 3-18). q = [r¹, r²], dq = q̇ (3-7).
//
// - Mass: ρA L/6 [[2I, I], [I, 2I]] plus the rotary inertia of the section about the two
//   axes across the rod (3-21): T_rot = ½ ρ L I_y |ω⊥|², ω⊥ = d × ḋ / |d|², d = r² − r¹, i.e.
//   T_rot = ½ ḋᵀ A(d) ḋ with A = (c/n) P, c = ρ L I_y, n = |d|², P = I − d dᵀ/n. Its
//   quadratic-velocity force by Lagrange, F_d = Ȧ ḋ − ∂T_rot/∂d, with s = d·ḋ:
//     Ȧ ḋ = −3cs ḋ/n² + 4cs² d/n³ − c|ḋ|² d/n²,   ∂T_rot/∂d = −cs ḋ/n² + 2cs² d/n³ − c|ḋ|² d/n²,
//     F_d = −(2cs/n²) P ḋ   (node 1 takes −F_d, node 2 F_d; its power is ½ ḋᵀ Ȧ ḋ),
//   and its velocity tangent ∂F_d/∂ḋ = −(2c/n²)(P ḋ dᵀ + s P).
// - Axial force N = E A(ℓ) ε with ε = ℓ/L − 1. With `constant_volume` the section shrinks as
//   the rod stretches so that ρ and the mass stay constant (3-27): A(ℓ) = A L/ℓ; the strain
//   energy is then E A (ℓ − L − L ln(ℓ/L)), otherwise ½ E A L ε².
// - Smoothing factor h (3-16): σ̄ = E (ε + h/2 ε̇ + h²/6 ε̈), i.e. a viscous term and an axial
//   mass E A L h²/6 T_ε T_εᵀ (3-24); h = 0 by default.
// - Optional Kelvin–Voigt material damping with retardation time η: N += E A η ε̇, off by default.

#include <cmath>

#include "cranesim/elements/section.hpp"
#include "cranesim/math/types.hpp"

namespace cranesim {

struct StrutTieKernel {
  static constexpr int kNq = 6;
  static constexpr int kNv = 6;
  template <class S> using Q = Eigen::Matrix<S, 6, 1>;

  double length = 1.0;  // unstretched length L
  Section section;
  Material material;
  bool constant_volume = true;
  double smoothing = 0.0;  // h, s
  double damping = 0.0;    // Kelvin–Voigt retardation time η, s

  /// The smoothing's viscous term h/2 ε̇ dissipates as the damping does.
  bool damped() const { return smoothing > 0.0 || damping > 0.0; }

  template <class S> Eigen::Matrix<S, 6, 6> massMatrix(const Q<S>& q, double = 0.0) const {
    Eigen::Matrix<S, 6, 6> M = translationalMass<S>() + rotaryMass<S>(q);
    if (smoothing > 0.0) {
      const Q<S> Te = strainGradient<S>(q);
      M += (material.youngs_modulus * section.area * length * smoothing * smoothing / 6.0) * (Te * Te.transpose());
    }
    return M;
  }

  template <class S> Q<S> force(const Q<S>& q, const Q<S>& v, double, const Vec3& gravity) const {
    using std::sqrt;
    const Vec3T<S> d = q.template tail<3>() - q.template head<3>();
    const S l = sqrt(d.squaredNorm());
    const Vec3T<S> e = d / l;
    S N = axialForce<S>(l);
    if (smoothing > 0.0 || damping > 0.0) {
      const Vec3T<S> dd = v.template tail<3>() - v.template head<3>();
      const S ldot = e.dot(dd);
      const S ldd_quadratic = (dd.squaredNorm() - ldot * ldot) / l;  // ℓ̈ without the d̈ term
      const double EA = material.youngs_modulus * section.area;
      N += EA * ((0.5 * smoothing + damping) * ldot + smoothing * smoothing / 6.0 * ldd_quadratic) / length;
    }
    const Vec3T<S> rotary = rotaryForce<S>(d, Vec3T<S>(v.template tail<3>() - v.template head<3>()));
    Q<S> F;
    F.template head<3>() = -rotary - N * e;
    F.template tail<3>() = rotary + N * e;
    const double half_weight = 0.5 * material.density * section.area * length;
    F.template head<3>() -= (half_weight * gravity).cast<S>();
    F.template tail<3>() -= (half_weight * gravity).cast<S>();
    return F;
  }

  /// ∂(M a + F)/∂dq in closed form (file comment; the damping's and smoothing's axial force
  /// through ε̇ and ε̈'s quadratic part) and M beside it (element.hpp).
  Eigen::Matrix<double, 6, 6> velocityTangent(const Q<double>& q, const Q<double>& v, double, Eigen::Matrix<double, 6, 6>& M) const {
    M = massMatrix<double>(q);
    const Vec3 d = q.tail<3>() - q.head<3>(), dd = v.tail<3>() - v.head<3>();
    const double n = d.squaredNorm(), s = d.dot(dd);
    const Mat3 P = Mat3::Identity() - d * d.transpose() / n;
    Mat3 B = (-2.0 * rotaryCoefficient() / (n * n)) * (P * dd * d.transpose() + s * P);  // ∂F_d/∂ḋ
    if (smoothing > 0.0 || damping > 0.0) {
      const double l = std::sqrt(n);
      const Vec3 e = d / l;
      const double ldot = e.dot(dd);
      const double EA = material.youngs_modulus * section.area;
      const Vec3 dN = (EA / length) * ((0.5 * smoothing + damping) * e + (smoothing * smoothing / 3.0) * (dd - ldot * e) / l);
      B.noalias() += e * dN.transpose();
    }
    Eigen::Matrix<double, 6, 6> C;
    C << B, -B, -B, B;
    return C;
  }

  double kineticEnergy(const Q<double>& q, const Q<double>& v, double = 0.0) const {
    return 0.5 * v.dot(massMatrix<double>(q) * v);
  }

  double potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const {
    const double l = (q.tail<3>() - q.head<3>()).norm();
    const double EA = material.youngs_modulus * section.area;
    const double strain = constant_volume ? EA * (l - length - length * std::log(l / length))
                                          : 0.5 * EA * length * std::pow(l / length - 1.0, 2);
    const Vec3 centre = 0.5 * (q.head<3>() + q.tail<3>());
    return strain - material.density * section.area * length * gravity.dot(centre);
  }

  /// Axial force at current length ℓ (positive in tension).
  template <class S> S axialForce(const S& l) const {
    const double EA = material.youngs_modulus * section.area;
    const S strain = l / length - 1.0;
    return constant_volume ? S(EA * strain * length / l) : S(EA * strain);
  }

 private:
  template <class S> Eigen::Matrix<S, 6, 6> translationalMass() const {
    const double m = material.density * section.area * length;
    Eigen::Matrix<S, 6, 6> M = Eigen::Matrix<S, 6, 6>::Zero();
    for (int k = 0; k < 3; ++k) {
      M(k, k) = M(3 + k, 3 + k) = S(m / 3.0);
      M(k, 3 + k) = M(3 + k, k) = S(m / 6.0);
    }
    return M;
  }

  /// c = ρ L I_y (section symmetric, I_y = I_z: their mean).
  double rotaryCoefficient() const { return material.density * length * 0.5 * (section.Iy + section.Iz); }

  /// A = (c/n) P on the relative velocity ḋ (file comment).
  template <class S> Eigen::Matrix<S, 6, 6> rotaryMass(const Q<S>& q) const {
    const Vec3T<S> d = q.template tail<3>() - q.template head<3>();
    const S n = d.squaredNorm();
    const Mat3T<S> A = (rotaryCoefficient() / n) * (Mat3T<S>::Identity() - d * d.transpose() / n);
    Eigen::Matrix<S, 6, 6> M;
    M << A, -A, -A, A;
    return M;
  }

  /// F_d = −(2cs/n²) P ḋ: the rotary inertia's quadratic-velocity force on d (file comment).
  template <class S> Vec3T<S> rotaryForce(const Vec3T<S>& d, const Vec3T<S>& dd) const {
    const S n = d.squaredNorm(), s = d.dot(dd);
    return (-2.0 * rotaryCoefficient() * s / (n * n)) * Vec3T<S>(dd - (s / n) * d);
  }

  /// T_ε = ∂ε/∂q (3-15).
  template <class S> Q<S> strainGradient(const Q<S>& q) const {
    using std::sqrt;
    const Vec3T<S> d = q.template tail<3>() - q.template head<3>();
    const Vec3T<S> e = d / sqrt(d.squaredNorm());
    Q<S> T;
    T << -e / length, e / length;
    return T;
  }
};

}  // namespace cranesim
