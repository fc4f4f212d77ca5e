#pragma once
// Two-node strut tie (thesis 3.2, C.3): axial stress only, linear interpolation between the
// end points (3-17, 3-18). q = [r¹, r²], dq = q̇ (3-7).
//
// - Mass: ρA L/6 [[2I, I], [I, 2I]] plus the rotary inertia of the section about the two
//   axes across the rod (3-21): T_rot = ½ ρ L I_y |ω⊥|², ω⊥ = d × ḋ / |d|², d = r² − r¹.
//   The quadratic-velocity terms follow from M by Lagrange (quadratic_velocity.hpp).
// - Axial force N = E A(ℓ) ε with ε = ℓ/L − 1. With `constant_volume` the section shrinks as
//   the rod stretches so that ρ and the mass stay constant (3-27): A(ℓ) = A L/ℓ; the strain
//   energy is then E A (ℓ − L − L ln(ℓ/L)), otherwise ½ E A L ε².
// - Smoothing factor h (3-16): σ̄ = E (ε + h/2 ε̇ + h²/6 ε̈), i.e. a viscous term and an axial
//   mass E A L h²/6 T_ε T_εᵀ (3-24); h = 0 by default.
// - Optional Kelvin–Voigt material damping with retardation time η: N += E A η ε̇, off by default.

#include <cmath>

#include "cranesim/elements/quadratic_velocity.hpp"
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
    Q<S> F = quadraticVelocityForces<6, S>([this](const auto& x) { return rotaryMass(x); }, q, v);
    F.template head<3>() -= N * e;
    F.template tail<3>() += N * e;
    const double half_weight = 0.5 * material.density * section.area * length;
    F.template head<3>() -= (half_weight * gravity).cast<S>();
    F.template tail<3>() -= (half_weight * gravity).cast<S>();
    return F;
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

  /// ρ L I_y P/|d|² on the relative velocity ḋ, with P = I − d̂ d̂ᵀ (section symmetric, I_y = I_z).
  template <class S> Eigen::Matrix<S, 6, 6> rotaryMass(const Q<S>& q) const {
    const Vec3T<S> d = q.template tail<3>() - q.template head<3>();
    const S n = d.squaredNorm();
    const double c = material.density * length * 0.5 * (section.Iy + section.Iz);
    const Mat3T<S> A = (c / n) * (Mat3T<S>::Identity() - d * d.transpose() / n);
    Eigen::Matrix<S, 6, 6> M;
    M << A, -A, -A, A;
    return M;
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
