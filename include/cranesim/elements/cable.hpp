#pragma once
// Two-node cable (docs/scene-format.md): a straight, tension-only rope element of variable
// unstretched length between two point nodes, q = [r¹, r²], dq = q̇ — what real-time crane
// simulators use for hoist lines, for ropes whose sag and sideways (string) vibration do not
// matter. It has no transverse degrees of freedom of its own, so a taut rope's string modes
// (14–27 Hz on the thesis crane's luffing rope) do not exist in the model.
//
// - Strain ε = ℓ/L − 1 of the chord ℓ = ‖r² − r¹‖ against the unstretched length L(t) =
//   length(t)/segments; tension N = EA max(ε + η ε̇, 0) with ε̇ the total rate
//   ℓ̇/L − ℓ L̇/L², the material's: a rope reeled at constant stretch has ε̇ = 0 (no lag η L̇).
//   Continuous where it snaps taut (tension starts at ε = −η ε̇), as the spline rope's law.
// - Forces: ∓N u on the two nodes, u = (r² − r¹)/ℓ; gravity ρA L g/2 on each.
// - Mass: the linear interpolation's consistent matrix ρA L/6 [[2I, I], [I, 2I]] (the rope's
//   mass, first and second moments about its centre exact for a straight rope), with L = L(t):
//   the equations use M(t) d(dq)/dt, the material entering and leaving with the element.
// - Energy books (element.hpp): with e = ½ vᵀ M v / L + ½ EA max(ε, 0)² L / L − ρA g·(r¹ + r²)/2
//   per unit length, the winch's power is L̇ ∂(T + V)/∂L at fixed (q, dq) plus the damping
//   stress' power on the stretch rate that L̇ causes, L (σ − σ₀) L̇ ∂ε/∂L; the damper
//   dissipates L (σ − σ₀) ε̇ ≥ 0.

#include <algorithm>
#include <cmath>

#include "cranesim/elements/parts/reeled_length.hpp"
#include "cranesim/elements/section.hpp"

namespace cranesim {

struct CableKernel : ReeledLength {
  static constexpr int kNq = 6;
  static constexpr int kNv = 6;
  template <class S> using Q = Eigen::Matrix<S, 6, 1>;

  Section section;
  Material material;
  double damping = 0.0;  // Kelvin–Voigt retardation time η, s

  template <class S> Eigen::Matrix<S, 6, 6> massMatrix(const Q<S>&, double t) const {
    const double m = material.density * section.area * segmentLength(t);
    Eigen::Matrix<double, 6, 6> M;
    M << (m / 3.0) * Mat3::Identity(), (m / 6.0) * Mat3::Identity(), (m / 6.0) * Mat3::Identity(), (m / 3.0) * Mat3::Identity();
    return M.cast<S>();
  }

  /// `rates`: which L̇ the damping takes (element.hpp, ElementInput::rates).
  template <class S>
  Q<S> force(const Q<S>& q, const Q<S>& v, double t, const Vec3& gravity, ParameterRates rates = ParameterRates::Left) const {
    using std::sqrt;
    const double L = segmentLength(t), EA = material.youngs_modulus * section.area;
    const Vec3T<S> d = q.template segment<3>(3) - q.template segment<3>(0);
    const S chord = sqrt(d.squaredNorm());
    const Vec3T<S> u = d / chord;
    S stress = chord / L - 1.0;  // σ/E
    if (damping > 0.0) {
      const S chord_rate = u.dot(Vec3T<S>(v.template segment<3>(3) - v.template segment<3>(0)));
      stress += damping * (chord_rate / L - chord * segmentRate(t, rates) / (L * L));
    }
    Q<S> F;
    const Vec3T<S> weight = (-0.5 * material.density * section.area * L * gravity).template cast<S>();
    const Vec3T<S> pull = stress > 0.0 ? Vec3T<S>(S(EA) * stress * u) : Vec3T<S>(Vec3T<S>::Zero());
    F << weight - pull, weight + pull;
    return F;
  }

  double kineticEnergy(const Q<double>& q, const Q<double>& v, double t) const {
    return 0.5 * v.dot(massMatrix<double>(q, t) * v);
  }

  /// ½ EA L max(ε, 0)² − ρA L g·(r¹ + r²)/2.
  double potentialEnergy(const Q<double>& q, double t, const Vec3& gravity) const {
    const double L = segmentLength(t), strain = std::max(chord(q) / L - 1.0, 0.0);
    return 0.5 * material.youngs_modulus * section.area * L * strain * strain -
           0.5 * material.density * section.area * L * gravity.dot(q.segment<3>(0) + q.segment<3>(3));
  }

  /// The winch's power: L̇ ∂(T + V)/∂L at fixed (q, dq), with ∂ε/∂L = −ℓ/L², plus the damping
  /// stress' power on the stretch rate that L̇ causes (file comment).
  double explicitTimePower(const Q<double>& q, const Q<double>& v, double t, const Vec3& gravity) const {
    const double rate = segmentRate(t);
    if (rate == 0.0) return 0.0;
    const double L = segmentLength(t), EA = material.youngs_modulus * section.area, ell = chord(q);
    const double strain = std::max(ell / L - 1.0, 0.0), strain_L = -ell / (L * L);
    double power = rate * (kineticEnergy(q, v, t) / L +
                           0.5 * EA * strain * strain + EA * L * strain * strain_L -
                           0.5 * material.density * section.area * gravity.dot(q.segment<3>(0) + q.segment<3>(3)));
    if (damping > 0.0) power += L * EA * dampingStress(q, v, t) * rate * strain_L;
    return power;
  }

  /// Kelvin–Voigt power L EA (max(ε + η ε̇, 0) − max(ε, 0)) ε̇ ≥ 0 (max is monotone).
  double dissipatedPower(const Q<double>& q, const Q<double>& v, double t, const Vec3&) const {
    if (damping == 0.0) return 0.0;
    const double L = segmentLength(t);
    return L * material.youngs_modulus * section.area * dampingStress(q, v, t) * strainRate(q, v, t);
  }

  /// Axial force (the elastic one, as the spline rope's), the same at every ξ.
  double tension(const Q<double>& q, double t, double = 0.0) const {
    return material.youngs_modulus * section.area * std::max(chord(q) / segmentLength(t) - 1.0, 0.0);
  }

 private:
  static double chord(const Q<double>& q) { return (q.segment<3>(3) - q.segment<3>(0)).norm(); }

  /// ε̇ = ℓ̇/L − ℓ L̇/L², the material's stretch rate.
  double strainRate(const Q<double>& q, const Q<double>& v, double t) const {
    const Vec3 d = q.segment<3>(3) - q.segment<3>(0);
    const double L = segmentLength(t), ell = d.norm();
    return (d / ell).dot(v.segment<3>(3) - v.segment<3>(0)) / L - ell * segmentRate(t) / (L * L);
  }

  /// (σ − σ₀)/E: the damped law's stress less the elastic one.
  double dampingStress(const Q<double>& q, const Q<double>& v, double t) const {
    const double strain = chord(q) / segmentLength(t) - 1.0;
    return std::max(strain + damping * strainRate(q, v, t), 0.0) - std::max(strain, 0.0);
  }
};

}  // namespace cranesim
