#pragma once
// Cubic spline rope (thesis 7.2.1, C.5): a cable element in absolute nodal coordinates
// q = [r¹, r'¹, r², r'²] (C-141), r' = dr/ds, with the centre line interpolated by cubic Hermite
// functions (C-142). Tension only (7-1): N = EA max(ε, 0), ε = ‖r'‖ − 1 (C-150); no bending or
// torsion stiffness; translational inertia only (C-154).
// Optional Kelvin–Voigt damping with retardation time η: N = EA max(ε + η ε̇, 0), ε̇ the
// material's stretch rate: at fixed ξ the slope r' = dN(L(t)) q changes with q and with L,
// ε̇ = r'·(dN dq + L̇ ∂(dN)/∂L q)/‖r'‖, so a rope reeled at constant stretch is not damped (the
// rate at fixed L read reeling as a strain rate L̇/L, a lag η L̇ of the load). The law is
// continuous where a rope snaps taut: tension starts at ε = −η ε̇, not with a jump of EA η ε̇ at
// ε = 0, which no step size resolves (a crane released from its drawing, ropes at ε = 0, stalled
// IDAS at steps of 1e-12 s). It dissipates in every branch: N ε̇ ≥ d/dt ½ EA max(ε, 0)².
//
// Optional transverse damping c (N·s): a taut string's sideways vibration, which the axial law
// does not damp (the luffing rope's 14–27 Hz string modes on the crane). It acts on the turning
// of the centre line relative to the element's chord, the rate
//   w = ṫ − Ω × t,   t = r'/‖r'‖,  ṫ = P_t ṙ'/‖r'‖,   Ω = u × u̇,  u = d/‖d‖,  u̇ = P_u ḋ/‖d‖,
// d = r² − r¹ and P_a = I − a aᵀ, with the power c ∫ ‖w‖² ds and the force c ∫ (∂w/∂dq)ᵀ w ds,
// linear in dq. A rope turning as a whole about an axis across its chord (a pendulum's swing)
// has w = 0 also where it sags; only a sagging rope's spin about its own chord is damped. On a
// rope of one element (the scene reader allows no other) the chord is the rope's, and the first
// string mode's damping ratio is ζ₁ = c (π/ℓ) / (2 √(T ρA)), growing with the mode number.
//
// The unstretched length may follow a drive, L(t) = length(t)/segments per element; the mass
// ρA L(t) changes with it, as when a winch reels the rope in or out (6). The equations use
// M(t) d(dq)/dt: the rope material enters and leaves with the velocity of the element.

#include <algorithm>
#include <array>
#include <cmath>

#include "cranesim/elements/parts/reeled_length.hpp"
#include "cranesim/elements/section.hpp"
#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/gauss_legendre.hpp"
#include "cranesim/math/hermite.hpp"
#include "cranesim/math/profile.hpp"

namespace cranesim {

struct SplineRopeKernel : ReeledLength {
  static constexpr int kNq = 12;
  static constexpr int kNv = 12;
  template <class S> using Q = Eigen::Matrix<S, 12, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;

  Section section;
  Material material;
  GaussRule rule = gaussLegendre(4);
  double damping = 0.0;  // Kelvin–Voigt retardation time η, s
  double transverse_damping = 0.0;  // c, N·s (see the file comment)

  /// M = ∫ ρA Nᵀ N ds = m ⊗ I₃ with m_kl = ∫ ρA N_k N_l ds, the Hermite functions' 4 × 4 mass.
  template <class S> Eigen::Matrix<S, 12, 12> massMatrix(const Q<S>&, double t) const {
    const double L = segmentLength(t), rhoA = material.density * section.area;
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    for (int g = 0; g < rule.points; ++g) {
      const std::array<double, 4> N = hermiteBasis(rule.xi[g], L).N;
      const double w = rule.weight[g] * L * rhoA;
      for (int l = 0; l < 4; ++l)
        for (int k = 0; k < 4; ++k) m(k, l) += (w * N[k]) * N[l];
    }
    Eigen::Matrix<S, 12, 12> M = Eigen::Matrix<S, 12, 12>::Zero();
    for (int l = 0; l < 4; ++l)
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < 3; ++i) M(3 * k + i, 3 * l + i) = S(m(k, l));
    return M;
  }

  /// `rates`: which L̇ the damping takes (element.hpp, ElementInput::rates).
  template <class S>
  Q<S> force(const Q<S>& q, const Q<S>& v, double t, const Vec3& gravity, ParameterRates rates = ParameterRates::Left) const {
    using std::sqrt;
    const double L = segmentLength(t);
    const double rate = damping > 0.0 || transverse_damping > 0.0 ? segmentRate(t, rates) : 0.0;
    const double rhoA = material.density * section.area;
    const double EA = material.youngs_modulus * section.area;
    Q<S> F = Q<S>::Zero();
    for (int g = 0; g < rule.points; ++g) {
      const HermiteBasis b = hermiteBasis(rule.xi[g], L);
      const auto dN = shape(b.dN);
      const Vec3T<S> rs = dN.template cast<S>() * q;
      const S stretch = sqrt(rs.squaredNorm());
      S stress = stretch - 1.0;  // σ/E
      if (damping > 0.0) stress += damping * rs.dot(slopeRate<S>(q, v, rate, dN, rule.xi[g], L)) / stretch;
      if (stress > 0.0) F += (rule.weight[g] * L * EA) * (stress / stretch) * (dN.transpose().template cast<S>() * rs);
      F -= (rule.weight[g] * L * rhoA) * (shape(b.N).transpose() * gravity).template cast<S>();
    }
    if (transverse_damping > 0.0) F += transverseDampingForce<S>(q, v, rate, L);
    return F;
  }

  /// ∂(M a + F)/∂dq in closed form, and M beside it (element.hpp). Per Gauss point where the rope
  /// is taut, the damping stress' share: with r' = dN q, λ = ‖r'‖, u = r'/λ, the force
  /// k (σ/λ) dNᵀ r' (k = w L EA) and ∂σ/∂dq = η uᵀ dN give k η dNᵀ u uᵀ dN; the transverse
  /// damping's c Aᵀ A, A = ∂w/∂dq. M does not depend on q.
  Mat12 velocityTangent(const Q<double>& q, const Q<double>& v, double t, Mat12& M,
                        ParameterRates rates = ParameterRates::Left) const;

  /// ∂(M a + F)/∂q (element.hpp): M a and gravity do not depend on q; the axial force
  /// k (σ/λ) dNᵀ r' in closed form, k dNᵀ ((σ/λ)(I − u uᵀ) dN + u ∂σ/∂q) where taut, with
  /// ∂σ/∂q = uᵀ dN + η ∂ε̇/∂q, ε̇ = r'·ṡ/λ, ṡ = dN dq + L̇ dN_L q (slopeRate):
  /// ∂ε̇/∂q = (ṡᵀ dN + L̇ r'ᵀ dN_L)/λ − (ε̇/λ) uᵀ dN; the transverse damping's by forward AD of
  /// its force alone.
  Mat12 coordinateTangent(const Q<double>& q, const Q<double>& v, const Q<double>&, double t, const Vec3&,
                          ParameterRates rates = ParameterRates::Left) const;

  double kineticEnergy(const Q<double>& q, const Q<double>& v, double t) const;

  double potentialEnergy(const Q<double>& q, double t, const Vec3& gravity) const;

  /// The winch's power on the element: ∂(T + V)/∂t at fixed (q, dq) = L̇ ∂(T + V)/∂L, plus the
  /// damping stress' power on the stretch rate that L̇ causes. Adding unstretched length at
  /// fixed nodes brings in material with its kinetic, gravity and strain energy and lowers the
  /// strain of the material there, against the tension. Per unit of unstretched length the
  /// energy is e = ½ ρA |ṙ|² + ½ EA max(ε, 0)² − ρA g·r, and ∂/∂L ∫₀¹ e L dξ = ∫₀¹ (e + L ∂e/∂L) dξ
  /// with the shape functions' ∂/∂L at fixed ξ. With σ the tension of the damped law and σ₀ the
  /// elastic one, dqᵀF = ∂V/∂q·dq + ∫ (σ − σ₀)(ε̇ − ε̇_L) ds, ε̇_L = L̇ ∂ε/∂L: the part
  /// ∫ (σ − σ₀) ε̇ ds is the damper's (dissipatedPower), ∫ (σ − σ₀) ε̇_L ds the winch's.
  double explicitTimePower(const Q<double>& q, const Q<double>& v, double t, const Vec3& gravity) const;

  /// Kelvin–Voigt power ∫ EA (max(ε + η ε̇, 0) − max(ε, 0)) ε̇ ds ≥ 0 (max is monotone), ε̇ the
  /// material's stretch rate.
  double dissipatedPower(const Q<double>& q, const Q<double>& v, double t, const Vec3& gravity) const;

  /// c ∫ ‖w‖² ds of the transverse damping.
  double transverseDissipatedPower(const Q<double>& q, const Q<double>& v, double t, const Vec3&) const;

  double axialDissipatedPower(const Q<double>& q, const Q<double>& v, double t) const;

  /// Axial force at ξ ∈ [0, 1] of the element.
  double tension(const Q<double>& q, double t, double xi) const;

 private:
  /// The turning rate w of the centre line against the chord at one point (file comment), the
  /// part w_L that reeling alone causes, and what force() needs of ∂w/∂dq.
  template <class S> struct TransverseTurning {
    Vec3T<S> w, w_reeling;
    Eigen::Matrix<S, 3, 12> dw_dv;  // ∂w/∂dq
    Q<S> force() const { return dw_dv.transpose() * w; }
  };

  template <class S>
  TransverseTurning<S> transverseTurning(const Q<S>& q, const Q<S>& v, double rate, const Eigen::Matrix<double, 3, 12>& dN,
                                         double xi, double L) const {
    using std::sqrt;
    const Vec3T<S> rs = dN.template cast<S>() * q, d = q.template segment<3>(6) - q.template segment<3>(0);
    const S stretch = sqrt(rs.squaredNorm()), chord = sqrt(d.squaredNorm());
    const Vec3T<S> t = rs / stretch, u = d / chord;
    const Mat3T<S> Pt = Mat3T<S>::Identity() - t * t.transpose(), Pu = Mat3T<S>::Identity() - u * u.transpose();
    // Ω × t = u̇ (u·t) − u (u̇·t) = B u̇ with B = (u·t) I − u tᵀ.
    const Mat3T<S> B = u.dot(t) * Mat3T<S>::Identity() - u * t.transpose();
    Eigen::Matrix<S, 3, 12> relative = Eigen::Matrix<S, 3, 12>::Zero();  // ḋ = relative dq
    relative.template block<3, 3>(0, 6).setIdentity();
    relative.template block<3, 3>(0, 0) = -Mat3T<S>::Identity();
    TransverseTurning<S> out;
    out.dw_dv = (Pt / stretch) * dN.template cast<S>() - (B * Pu / chord) * relative;
    out.w_reeling = Vec3T<S>::Zero();
    if (rate != 0.0) out.w_reeling = (Pt / stretch) * (rate * shape(hermiteBasisLengthDerivative(xi, L).dN)).template cast<S>() * q;
    out.w = out.dw_dv * v + out.w_reeling;
    return out;
  }

  /// c ∫ (∂w/∂dq)ᵀ w ds: the transverse damping force (file comment).
  template <class S> Q<S> transverseDampingForce(const Q<S>& q, const Q<S>& v, double rate, double L) const {
    Q<S> F = Q<S>::Zero();
    for (int g = 0; g < rule.points; ++g)
      F += (rule.weight[g] * L * transverse_damping) *
           transverseTurning<S>(q, v, rate, shape(hermiteBasis(rule.xi[g], L).dN), rule.xi[g], L).force();
    return F;
  }

  /// The axial state at a point: slope r' = dN q, stretch λ = ‖r'‖, u = r'/λ, uᵀ dN = ∂λ/∂q, the
  /// slope's rate ṡ, ε̇ = r'·ṡ/λ and σ/E = λ − 1 + η ε̇ (force's law before the max).
  struct AxialStress {
    Vec3 slope, u, slope_rate;
    double stretch, strain_rate, stress;
    Eigen::Matrix<double, 1, 12> du;
  };
  AxialStress axialStress(const Q<double>& q, const Q<double>& v, double rate, const Eigen::Matrix<double, 3, 12>& dN,
                          double xi, double L) const;

  /// d/dt of the slope r' = dN(L(t)) q at fixed ξ: dN dq + L̇ ∂(dN)/∂L q.
  template <class S>
  Vec3T<S> slopeRate(const Q<S>& q, const Q<S>& v, double rate, const Eigen::Matrix<double, 3, 12>& dN, double xi,
                     double L) const {
    Vec3T<S> out = dN.template cast<S>() * v;
    if (rate != 0.0) out += (rate * shape(hermiteBasisLengthDerivative(xi, L).dN)).template cast<S>() * q;
    return out;
  }

  /// (σ − σ₀)/E at ξ: the damped law's stress less the elastic one, max(ε + η ε̇, 0) − max(ε, 0).
  double dampingStress(const Q<double>& q, const Q<double>& v, double rate, double xi, double L) const;

  /// The 3 × 12 interpolation matrix [N0¹ I, N1¹ I, N0² I, N1² I] (C-142).
  static Eigen::Matrix<double, 3, 12> shape(const std::array<double, 4>& n);
};

}  // namespace cranesim
