#pragma once
// Cubic spline beam kernel (thesis 3.4, C.4): a geometrically exact Euler–Bernoulli beam
// segment between two FrameStretch nodes, q = [r¹, φ¹, s¹, r², φ², s²] (3-54), s = ‖r'‖ the
// stretch at an end, so r' = s R e_x (3-61). Cubic Hermite centre line (3-60); section frame
// R¹ C(α) with Cardan angles of the tangent (3-64) and torsion linear along the segment (3-66);
// strain energy (3-77) from ε = ‖r'‖ − 1 and κ = T_C α' (3-71, 3-72), optional Kelvin–Voigt
// damping; inertia by d'Alembert with the exact section velocities (3-73..3-76).
// The bending angles use atan2 where the thesis' (3-65) uses asin: equal where those are defined,
// smooth through 0 and accurate near ±90°.
// Derivation, forces along body twists and cost: docs/elements.md#cubic-spline-beam.
// All functions are templated on the scalar and use fixed-size types only (no allocation).

#include <cmath>

#include "cranesim/elements/section.hpp"
#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/gauss_legendre.hpp"
#include "cranesim/math/hermite.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {

namespace spline_beam_detail {

/// Second-order Taylor jet f(τ) ≈ v + d τ + ½ dd τ² (value, first and second derivative at
/// τ = 0) over any scalar S, for second derivatives along a path without nesting a third level
/// of dual numbers (three numbers per jet instead of four, on top of S). Scalar operations only.
template <class S> struct Jet2 {
  S v, d, dd;
};
template <class S> Jet2<S> operator+(const Jet2<S>& a, const Jet2<S>& b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
template <class S> Jet2<S> operator-(const Jet2<S>& a, const Jet2<S>& b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
template <class S> Jet2<S> operator-(const Jet2<S>& a) { return {-a.v, -a.d, -a.dd}; }
template <class S> Jet2<S> operator*(const Jet2<S>& a, const Jet2<S>& b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2.0 * (a.d * b.d) + a.v * b.dd};
}
template <class S> Jet2<S> operator*(const Jet2<S>& a, double c) { return {a.v * c, a.d * c, a.dd * c}; }
template <class S> Jet2<S> operator*(double c, const Jet2<S>& a) { return a * c; }
template <class S> Jet2<S> operator+(const Jet2<S>& a, double c) { return {a.v + c, a.d, a.dd}; }
template <class S> Jet2<S> operator-(const Jet2<S>& a, double c) { return {a.v - c, a.d, a.dd}; }
template <class S> Jet2<S> operator/(const Jet2<S>& a, double c) { return a * (1.0 / c); }
template <class S> Jet2<S> operator/(const Jet2<S>& a, const Jet2<S>& b) {
  const S q = a.v / b.v;
  const S dq = (a.d - q * b.d) / b.v;
  return {q, dq, (a.dd - 2.0 * (dq * b.d) - q * b.dd) / b.v};
}
template <class S> Jet2<S> sqrt(const Jet2<S>& a) {
  using std::sqrt;
  const S r = sqrt(a.v);
  const S dr = a.d / (2.0 * r);
  return {r, dr, (a.dd - 2.0 * (dr * dr)) / (2.0 * r)};  // from r² = a
}
/// sin and cos of a jet from one sine and cosine of its value.
template <class S> struct JetSinCos {
  Jet2<S> sin, cos;
};
template <class S> JetSinCos<S> sinCos(const Jet2<S>& a) {
  using std::cos, std::sin;
  const S s = sin(a.v), c = cos(a.v);
  return {{s, c * a.d, c * a.dd - s * (a.d * a.d)}, {c, -(s * a.d), -(s * a.dd) - c * (a.d * a.d)}};
}
template <class S> Jet2<S> atan2(const Jet2<S>& y, const Jet2<S>& x) {
  using std::atan2;
  const S m = x.v * x.v + y.v * y.v, n = x.v * y.d - y.v * x.d;  // θ' = n/m
  const S dn = x.v * y.dd - y.v * x.dd, dm = 2.0 * (x.v * x.d + y.v * y.d);
  return {atan2(y.v, x.v), n / m, (dn * m - n * dm) / (m * m)};
}

/// Accumulates M = Σ Gᵀ diag(w) G over 3 × n blocks G. Generic scalars use plain products; for
/// first-order duals (the scalar of KernelElement's Jacobian) the value and the n derivative
/// directions are split into double GEMMs, dM_k = Σ (Y_k + Y_kᵀ) with Y_k = (diag(w)G₀)ᵀ ∂_kG,
/// about ten times faster than the products of dual-number matrices were (measured with Eigen's
/// AutoDiffScalar, which autodiff.hpp's Dual replaced).
template <class S, int n> struct GramAccumulator {
  Eigen::Matrix<S, n, n> M = Eigen::Matrix<S, n, n>::Zero();
  void add(const Eigen::Matrix<S, 3, n>& G, const Eigen::Vector3d& w) {
    Eigen::Matrix<S, 3, n> WG;
    for (int i = 0; i < 3; ++i) WG.row(i) = w(i) * G.row(i);
    M.noalias() += G.transpose() * WG;
  }
  Eigen::Matrix<S, n, n> result() const { return M; }
};

template <int N, int n> struct GramAccumulator<Dual<double, N>, n> {
  using D = Dual<double, N>;
  Eigen::Matrix<double, n, n> M0 = Eigen::Matrix<double, n, n>::Zero();
  Eigen::Matrix<double, n, n * N> Y = Eigen::Matrix<double, n, n * N>::Zero();  // [Y_0 … Y_N−1]
  void add(const Eigen::Matrix<D, 3, n>& G, const Eigen::Vector3d& w) {
    Eigen::Matrix<double, 3, n> G0, WG0;
    Eigen::Matrix<double, 3, n * N> dG;  // [∂_0G … ∂_N−1G]
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < 3; ++i) {
        G0(i, j) = G(i, j).value();
        WG0(i, j) = w(i) * G0(i, j);
        for (int k = 0; k < N; ++k) dG(i, k * n + j) = G(i, j).derivatives()(k);
      }
    M0.noalias() += G0.transpose() * WG0;
    Y.noalias() += WG0.transpose().lazyProduct(dG);
  }
  Eigen::Matrix<D, n, n> result() const {
    Eigen::Matrix<D, n, n> M;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        M(i, j).value() = M0(i, j);
        for (int k = 0; k < N; ++k) M(i, j).derivatives()(k) = Y(i, k * n + j) + Y(j, k * n + i);
      }
    return M;
  }
};

}  // namespace spline_beam_detail

struct SplineBeamKernel {
  static constexpr int kNodes = 2;
  static constexpr int kNq = 14;
  static constexpr int kNv = 14;
  static constexpr int kNodeSize = 7;
  static constexpr int kLocal = 8;  // [d, χ, s¹, s²]
  template <class S> using Q = Eigen::Matrix<S, kNq, 1>;
  template <class S> using V = Eigen::Matrix<S, kNv, 1>;
  template <class S> using Strain = Eigen::Matrix<S, 4, 1>;  // [ε, κ_x, κ_y, κ_z]

  double length = 1.0;  // reference (unstretched) length L of the segment, m
  Section section;
  Material material;
  GaussRule rule = gaussLegendre(5);  // 4 points integrate the straight-beam mass exactly; 5 for curved states
  double damping = 0.0;               // Kelvin–Voigt retardation time η, s (0: undamped)

  bool damped() const { return damping > 0.0; }

  // ---------------------------------------------------------------------------------------
  // Kinematic building blocks (public: used by tests, output and joint frames).

  /// The two end sections: positions, rotation matrices, stretches.
  template <class T> struct Ends {
    Vec3T<T> r1, r2;
    Mat3T<T> R1, R2;
    T s1, s2;
  };
  /// The deformation seen from end section 1: d = R¹ᵀ(r² − r¹), R₁₂ = R¹ᵀR², s¹, s².
  template <class T> struct Relative {
    Vec3T<T> d;
    Mat3T<T> R12;
    T s1, s2;
  };
  /// Cardan angles α = [φ, ψ, θ] of the section at ξ relative to section 1, α' = dα/ds, and
  /// the stretch ‖r'‖.
  template <class T> struct SectionState {
    Vec3T<T> angles, dangles;
    T stretch;
  };

  template <class S> static Ends<S> ends(const Q<S>& q) {
    return {q.template segment<3>(0), q.template segment<3>(7),
            rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3))),
            rotationMatrix<S>(Vec3T<S>(q.template segment<3>(10))), q(6), q(13)};
  }

  template <class T> static Relative<T> relative(const Ends<T>& e) {
    const Mat3T<T> R1t = e.R1.transpose();
    return {R1t * (e.r2 - e.r1), R1t * e.R2, e.s1, e.s2};
  }

  /// C(α) = R_z(θ) R_y(ψ) R_x(φ) (B-16).
  template <class T> static Mat3T<T> cardanMatrix(const Vec3T<T>& a) {
    using std::cos, std::sin;
    return cardanMatrix<T>(sin(a(0)), cos(a(0)), sin(a(1)), cos(a(1)), sin(a(2)), cos(a(2)));
  }
  /// The same from the angles' sines and cosines.
  template <class T>
  static Mat3T<T> cardanMatrix(const T& sf, const T& cf, const T& sp, const T& cp, const T& st, const T& ct) {
    Mat3T<T> C;
    C << cp * ct, sf * sp * ct - cf * st, cf * sp * ct + sf * st,  //
        cp * st, sf * sp * st + cf * ct, cf * sp * st - sf * ct,   //
        -sp, sf * cp, cf * cp;
    return C;
  }

  /// T_C(α) of B-17: body-frame angular velocity (curvature) ω = T_C α̇ (κ = T_C α').
  template <class T> static Mat3T<T> cardanRateMap(const Vec3T<T>& a) {
    using std::cos, std::sin;
    const T cf = cos(a(0)), sf = sin(a(0)), cp = cos(a(1)), sp = sin(a(1));
    Mat3T<T> M;
    M << T(1.0), T(0.0), -sp,  //
        T(0.0), cf, sf * cp,   //
        T(0.0), -sf, cf * cp;
    return M;
  }

  /// Section angles (3-64..3-67) from the tangent a = R¹ᵀ r' and its derivative c = R¹ᵀ r''
  /// at ξ and the end torsion φ₁₂; scalar operations only, so any scalar type works.
  template <class T> struct Angles {
    T phi, psi, theta, dphi, dpsi, dtheta, stretch;
  };
  template <class T>
  Angles<T> sectionAngles(const T (&a)[3], const T (&c)[3], const T& phi12, double xi) const {
    using std::atan2, std::sqrt;
    const T rho2 = a[0] * a[0] + a[1] * a[1];
    const T rho = sqrt(rho2);
    const T a2 = rho2 + a[2] * a[2];
    const T drho = (a[0] * c[0] + a[1] * c[1]) / rho;
    return {phi12 * xi,
            atan2(T(-a[2]), rho),                    // ψ (3-65)
            atan2(a[1], a[0]),                       // θ (3-65)
            phi12 / length,                           // φ' (3-66, C-114)
            (a[2] * drho - rho * c[2]) / a2,          // ψ'
            (a[0] * c[1] - a[1] * c[0]) / rho2,       // θ'
            sqrt(a2)};
  }

  /// Section angles and stretch at ξ from the relative deformation.
  template <class T> SectionState<T> sectionState(const Relative<T>& rel, double xi) const {
    using std::atan2;
    const HermiteBasis b = hermiteBasis(xi, length);
    T a[3], c[3];  // a = R¹ᵀ r', c = R¹ᵀ r'' (the local position of node 1 is 0, N₀¹' = −N₀²')
    for (int i = 0; i < 3; ++i) {
      a[i] = rel.d(i) * b.dN[2] + rel.s2 * rel.R12(i, 0) * b.dN[3];
      c[i] = rel.d(i) * b.ddN[2] + rel.s2 * rel.R12(i, 0) * b.ddN[3];
    }
    a[0] = a[0] + rel.s1 * b.dN[1];
    c[0] = c[0] + rel.s1 * b.ddN[1];
    const Angles<T> g = sectionAngles<T>(a, c, atan2(rel.R12(2, 1), rel.R12(2, 2)), xi);  // φ₁₂ (3-57)
    SectionState<T> st;
    st.angles << g.phi, g.psi, g.theta;
    st.dangles << g.dphi, g.dpsi, g.dtheta;
    st.stretch = g.stretch;
    return st;
  }

  /// Section angles, strains and their derivatives along the 8 local perturbations at ξ, in
  /// closed form (checked against finite differences of U in the tests). With a = R¹ᵀ r',
  /// c = R¹ᵀ r'', ρ² = a_x² + a_y², A = ‖a‖²:
  ///   ∂θ/∂a = g_θ = [−a_y, a_x, 0]/ρ²,  ∂ψ/∂a = g_ψ = [a_z a_x/ρ, a_z a_y/ρ, −ρ]/A,
  ///   θ' = g_θ·c,  ψ' = g_ψ·c  (so ∂θ'/∂c = g_θ, ∂ψ'/∂c = g_ψ),
  ///   ∂θ'/∂a = [c_y − 2a_xθ', −c_x − 2a_yθ', 0]/ρ²,
  ///   ∂ψ'/∂a_i = (∂N/∂a_i − 2a_iψ')/A,  N = a_z P/ρ − ρ c_z,  P = a_x c_x + a_y c_y,
  ///     ∂N/∂a_{x,y} = a_z c_{x,y}/ρ − a_z P a_{x,y}/ρ³ − c_z a_{x,y}/ρ,  ∂N/∂a_z = P/ρ,
  ///   ∂a/∂δd = N₀²' I,  ∂a/∂δχ = N₁²' s² R₁₂ (−ẽ_x),  ∂a/∂δs¹ = N₁¹' e_x,  ∂a/∂δs² = N₁²' R₁₂ e_x
  ///   (the same for c with N''),
  ///   ∂φ₁₂/∂δχ = [1, −R₂₁R₂₀/m, −R₂₂R₂₀/m],  m = R₂₁² + R₂₂²  (R₁₂ → R₁₂(I + δχ̃) in atan2(R₂₁, R₂₂)),
  ///   κ = T_C(φ, ψ) α':  ∂κ = T_C ∂α' + [0, κ_z, −κ_y]ᵀ ∂φ + [−cψ θ', −sφ sψ θ', −cφ sψ θ']ᵀ ∂ψ.
  template <class S> struct SectionDerivatives {
    Vec3T<S> alpha;                       // [φ, ψ, θ]
    Eigen::Matrix<S, 3, kLocal> dalpha;   // ∂α/∂δ_local
    Strain<S> strain;                     // [ε, κ]
    Eigen::Matrix<S, 4, kLocal> dstrain;  // ∂[ε, κ]/∂δ_local
  };
  template <class S>
  [[gnu::flatten]] SectionDerivatives<S> sectionDerivatives(const Relative<S>& rel, double xi, bool strains = true) const {
    using std::atan2, std::cos, std::sin, std::sqrt;
    const HermiteBasis b = hermiteBasis(xi, length);
    Vec3T<S> a, c;
    Eigen::Matrix<S, 3, kLocal> da = Eigen::Matrix<S, 3, kLocal>::Zero(), dc = Eigen::Matrix<S, 3, kLocal>::Zero();
    for (int i = 0; i < 3; ++i) {
      const S t = rel.s2 * rel.R12(i, 0);
      a(i) = rel.d(i) * b.dN[2] + t * b.dN[3];
      c(i) = rel.d(i) * b.ddN[2] + t * b.ddN[3];
      da(i, i) = S(b.dN[2]);
      dc(i, i) = S(b.ddN[2]);
      const S t4 = -(rel.s2 * rel.R12(i, 2)), t5 = rel.s2 * rel.R12(i, 1);
      da(i, 4) = t4 * b.dN[3], dc(i, 4) = t4 * b.ddN[3];
      da(i, 5) = t5 * b.dN[3], dc(i, 5) = t5 * b.ddN[3];
      da(i, 7) = rel.R12(i, 0) * b.dN[3], dc(i, 7) = rel.R12(i, 0) * b.ddN[3];
    }
    a(0) += rel.s1 * b.dN[1];
    c(0) += rel.s1 * b.ddN[1];
    da(0, 6) = S(b.dN[1]);
    dc(0, 6) = S(b.ddN[1]);

    const S rho2 = a(0) * a(0) + a(1) * a(1), rho = sqrt(rho2), A = rho2 + a(2) * a(2), norm = sqrt(A);
    const Vec3T<S> gpsi(a(2) * a(0) / (rho * A), a(2) * a(1) / (rho * A), -rho / A);
    const Vec3T<S> gtheta(-a(1) / rho2, a(0) / rho2, S(0.0));
    const S dpsi = gpsi.dot(c), dtheta = gtheta.dot(c);
    const S P = a(0) * c(0) + a(1) * c(1);
    const Vec3T<S> hpsi((a(2) * c(0) / rho - a(2) * P * a(0) / (rho2 * rho) - c(2) * a(0) / rho - 2.0 * a(0) * dpsi) / A,
                        (a(2) * c(1) / rho - a(2) * P * a(1) / (rho2 * rho) - c(2) * a(1) / rho - 2.0 * a(1) * dpsi) / A,
                        (P / rho - 2.0 * a(2) * dpsi) / A);
    const Vec3T<S> htheta((c(1) - 2.0 * a(0) * dtheta) / rho2, (-c(0) - 2.0 * a(1) * dtheta) / rho2, S(0.0));

    const S R20 = rel.R12(2, 0), R21 = rel.R12(2, 1), R22 = rel.R12(2, 2), m = R21 * R21 + R22 * R22;
    const S phi12 = atan2(R21, R22);
    Eigen::Matrix<S, 1, kLocal> dphi12 = Eigen::Matrix<S, 1, kLocal>::Zero();
    dphi12(3) = S(1.0);
    dphi12(4) = -(R21 * R20) / m;
    dphi12(5) = -(R22 * R20) / m;

    SectionDerivatives<S> out;
    out.alpha << phi12 * xi, atan2(S(-a(2)), rho), atan2(a(1), a(0));
    out.dalpha.row(0) = dphi12 * S(xi);
    out.dalpha.row(1) = gpsi.transpose().lazyProduct(da);
    out.dalpha.row(2) = gtheta.transpose().lazyProduct(da);

    if (!strains) return out;
    const S sf = sin(out.alpha(0)), cf = cos(out.alpha(0)), sp = sin(out.alpha(1)), cp = cos(out.alpha(1));
    const S dphi = phi12 / length;
    const S kx = dphi - sp * dtheta, ky = cf * dpsi + sf * cp * dtheta, kz = -(sf * dpsi) + cf * cp * dtheta;
    out.strain << norm - 1.0, kx, ky, kz;
    const Eigen::Matrix<S, 1, kLocal> ddphi = dphi12 / S(length);
    const Eigen::Matrix<S, 1, kLocal> ddpsi = hpsi.transpose().lazyProduct(da) + gpsi.transpose().lazyProduct(dc);
    const Eigen::Matrix<S, 1, kLocal> ddtheta = htheta.transpose().lazyProduct(da) + gtheta.transpose().lazyProduct(dc);
    out.dstrain.row(0) = (a / norm).transpose().lazyProduct(da);
    out.dstrain.row(1) = ddphi - sp * ddtheta - (cp * dtheta) * out.dalpha.row(1);
    out.dstrain.row(2) = cf * ddpsi + (sf * cp) * ddtheta + kz * out.dalpha.row(0) - (sf * sp * dtheta) * out.dalpha.row(1);
    out.dstrain.row(3) = -(sf * ddpsi) + (cf * cp) * ddtheta - ky * out.dalpha.row(0) - (cf * sp * dtheta) * out.dalpha.row(1);
    return out;
  }

  /// Strain vector [ε, κ] (3-71, 3-72) from a section state.
  template <class T> static Strain<T> strainOf(const SectionState<T>& st) {
    const Vec3T<T> kappa = cardanRateMap<T>(st.angles) * st.dangles;
    Strain<T> e;
    e << st.stretch - 1.0, kappa(0), kappa(1), kappa(2);
    return e;
  }

  /// Strains [ε, κ_x, κ_y, κ_z] at ξ ∈ [0, 1].
  Strain<double> strains(const Q<double>& q, double xi) const {
    return strainOf<double>(sectionState<double>(relative<double>(ends<double>(q)), xi));
  }

  /// Centre-line position and section frame at ξ ∈ [0, 1].
  Frame sectionFrame(const Q<double>& q, double xi) const {
    const Ends<double> e = ends<double>(q);
    const HermiteBasis b = hermiteBasis(xi, length);
    return {centreLine<double>(e, b), e.R1 * cardanMatrix<double>(sectionState<double>(relative<double>(e), xi).angles)};
  }

  /// Λ dq: rates of [d, χ, s¹, s²] from the end velocities (Λ: see top),
  ///   ḋ = R¹ᵀ(ṙ² − ṙ¹) + d × ω¹,  χ̇ = ω² − R₁₂ᵀ ω¹.
  template <class S> static Eigen::Matrix<S, kLocal, 1> localRates(const Ends<S>& e, const Relative<S>& rel, const V<S>& v) {
    const Vec3T<S> w1 = v.template segment<3>(3);
    Eigen::Matrix<S, kLocal, 1> l;
    l.template head<3>() = e.R1.transpose() * (v.template segment<3>(7) - v.template head<3>()) + rel.d.cross(w1);
    l.template segment<3>(3) = v.template segment<3>(10) - rel.R12.transpose() * w1;
    l(6) = v(6);
    l(7) = v(13);
    return l;
  }

  /// Λᵀ g: generalized forces from forces g conjugate to the local perturbations,
  ///   F_r¹ = −R¹g_d, F_r² = R¹g_d, F_θ¹ = g_d × d − R₁₂ g_χ, F_θ² = g_χ, F_s = g_s.
  template <class S> static V<S> localForce(const Ends<S>& e, const Relative<S>& rel, const Eigen::Matrix<S, kLocal, 1>& g) {
    const Vec3T<S> gd = g.template head<3>(), gchi = g.template segment<3>(3);
    const Vec3T<S> f = e.R1 * gd;
    V<S> F;
    F.template segment<3>(0) = -f;
    F.template segment<3>(3) = gd.cross(rel.d) - rel.R12 * gchi;
    F(6) = g(6);
    F.template segment<3>(7) = f;
    F.template segment<3>(10) = gchi;
    F(13) = g(7);
    return F;
  }

  // ---------------------------------------------------------------------------------------
  // Kernel contract (element.hpp).

  /// M(q) = Σ w L (ρA G_rᵀ G_r + ρ G_ωᵀ J_c G_ω) (3-74, 3-76).
  template <class S> Eigen::Matrix<S, kNv, kNv> massMatrix(const Q<S>& q, double = 0.0) const {
    const Ends<S> e = ends(q);
    const Relative<S> rel = relative(e);
    const SectionProperties p = section.properties(material);
    const double rhoA = p.rhoA;
    spline_beam_detail::GramAccumulator<S, kNv> M;
    for (int g = 0; g < rule.points; ++g) {
      const double wL = rule.weight[g] * length;
      const HermiteBasis b = hermiteBasis(rule.xi[g], length);
      const SectionDerivatives<S> sd = sectionDerivatives(rel, rule.xi[g], false);
      M.add(translationJacobian(e, b), Eigen::Vector3d::Constant(wL * rhoA));
      M.add(rotationJacobian<S>(sd.alpha, sd.dalpha, e, rel), wL * Eigen::Vector3d(p.rhoIp, p.rhoIy, p.rhoIz));
    }
    return M.result();
  }

  /// F = F_ine (quadratic velocity) + F_int (elastic, damping) + F_g (gravity), left-hand side.
  template <class S> V<S> force(const Q<S>& q, const V<S>& v, double, const Vec3& gravity) const {
    return forces(q, v, gravity, Terms::All);
  }

  /// M a + F in one pass over the Gauss points (element.hpp: fused residual): G_r a and G_ω a
  /// join the section's accelerations, so M is never formed.
  template <class S> V<S> residual(const Q<S>& q, const V<S>& v, const V<S>& a, double, const Vec3& gravity) const {
    return forces(q, v, gravity, Terms::All, &a);
  }

  /// Elastic and damping forces alone (zero for rigid placements and rigid velocities).
  template <class S> V<S> internalForce(const Q<S>& q, const V<S>& v) const {
    return forces(q, v, Vec3::Zero(), Terms::Internal);
  }

  /// Quadratic-velocity inertial forces alone.
  template <class S> V<S> inertialForce(const Q<S>& q, const V<S>& v) const {
    return forces(q, v, Vec3::Zero(), Terms::Inertial);
  }

  double kineticEnergy(const Q<double>& q, const V<double>& v, double = 0.0) const {
    return 0.5 * v.dot(massMatrix<double>(q) * v);
  }

  /// U = ½ ∫ eᵀ K e ds (3-77).
  double strainEnergy(const Q<double>& q) const {
    const Relative<double> rel = relative<double>(ends<double>(q));
    const Eigen::Vector4d K = stiffness();
    double U = 0.0;
    for (int g = 0; g < rule.points; ++g) {
      const Strain<double> e = strainOf<double>(sectionState<double>(rel, rule.xi[g]));
      U += 0.5 * rule.weight[g] * length * e.dot(K.cwiseProduct(e));
    }
    return U;
  }

  /// Strain energy − ρA g·∫ r ds.
  double potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const {
    const Ends<double> e = ends<double>(q);
    Vec3 first = Vec3::Zero();
    for (int g = 0; g < rule.points; ++g)
      first += rule.weight[g] * length * centreLine<double>(e, hermiteBasis(rule.xi[g], length));
    return strainEnergy(q) - section.properties(material).rhoA * gravity.dot(first);
  }

  /// Diagonal of K_ε (3-77): [EA, GJ, EI_y, EI_z].
  Eigen::Vector4d stiffness() const {
    const SectionProperties p = section.properties(material);
    return {p.EA, p.GJ, p.EIy, p.EIz};
  }

 private:
  template <class T> static Vec3T<T> centreLine(const Ends<T>& e, const HermiteBasis& b) {
    Vec3T<T> r;
    for (int i = 0; i < 3; ++i)
      r(i) = e.r1(i) * b.N[0] + e.s1 * e.R1(i, 0) * b.N[1] + e.r2(i) * b.N[2] + e.s2 * e.R2(i, 0) * b.N[3];
    return r;
  }

  /// G_r = ∂ṙ(ξ)/∂dq (3-63, C-95).
  template <class S> static Eigen::Matrix<S, 3, kNv> translationJacobian(const Ends<S>& e, const HermiteBasis& b) {
    Eigen::Matrix<S, 3, kNv> G = Eigen::Matrix<S, 3, kNv>::Zero();
    const Mat3T<S>* R[2] = {&e.R1, &e.R2};
    const S* s[2] = {&e.s1, &e.s2};
    for (int n = 0; n < 2; ++n) {
      const int o = kNodeSize * n;
      const double N0 = b.N[2 * n], N1 = b.N[2 * n + 1];
      for (int i = 0; i < 3; ++i) {
        G(i, o + i) = S(N0);
        // d/dδθ of s R (I + δθ̃) e_x = s R (δθ × e_x) = s [0, −R e_z, R e_y] δθ
        G(i, o + 4) = -(*s[n]) * (*R[n])(i, 2) * N1;
        G(i, o + 5) = (*s[n]) * (*R[n])(i, 1) * N1;
        G(i, o + 6) = (*R[n])(i, 0) * N1;
      }
    }
    return G;
  }

  /// G_r a, column by column as translationJacobian (forming that 3 × 14 matrix and multiplying
  /// made the 8-segment cantilever's step 4 % slower, 21.5 → 22.4 µs).
  template <class S> static Vec3T<S> centreLineAcceleration(const Ends<S>& e, const HermiteBasis& b, const V<S>& a) {
    const Mat3T<S>* R[2] = {&e.R1, &e.R2};
    const S* s[2] = {&e.s1, &e.s2};
    Vec3T<S> out = Vec3T<S>::Zero();
    for (int n = 0; n < 2; ++n) {
      const int o = kNodeSize * n;
      const double N0 = b.N[2 * n], N1 = b.N[2 * n + 1];
      out += S(N0) * a.template segment<3>(o);
      out += S(N1) * Vec3T<S>(*s[n] * Vec3T<S>(R[n]->col(1) * a(o + 5) - R[n]->col(2) * a(o + 4)) + R[n]->col(0) * a(o + 6));
    }
    return out;
  }

  /// G_ω = Cᵀ [ω¹ selector] + T_C(α) (∂α/∂δ_local) Λ (3-69, C-119), with Λ's blocks written out.
  template <class S>
  static Eigen::Matrix<S, 3, kNv> rotationJacobian(const Vec3T<S>& alpha, const Eigen::Matrix<S, 3, kLocal>& dalpha,
                                                   const Ends<S>& e, const Relative<S>& rel) {
    const Eigen::Matrix<S, 3, kLocal> TD = cardanRateMap<S>(alpha).lazyProduct(dalpha);
    const Mat3T<S> Td = TD.template leftCols<3>(), Tchi = TD.template middleCols<3>(3);
    const Mat3T<S> B = Td.lazyProduct(e.R1.transpose());
    Eigen::Matrix<S, 3, kNv> G;
    G.template middleCols<3>(0) = -B;
    G.template middleCols<3>(3) = Td.lazyProduct(skew<S>(rel.d)) - Tchi.lazyProduct(rel.R12.transpose()) +
                                  cardanMatrix<S>(alpha).transpose();
    G.col(6) = TD.col(6);
    G.template middleCols<3>(7) = B;
    G.template middleCols<3>(10) = Tchi;
    G.col(13) = TD.col(7);
    return G;
  }

  /// ρJ_c x with ρJ_c = diag(ρI_p, ρI_y, ρI_z) = diag(rhoJ), column-wise.
  template <class S, int C>
  static Eigen::Matrix<S, 3, C> sectionInertia(const Vec3& rhoJ, const Eigen::Matrix<S, 3, C>& x) {
    Eigen::Matrix<S, 3, C> y;
    for (int k = 0; k < 3; ++k) y.row(k) = rhoJ(k) * x.row(k);
    return y;
  }

  /// Which forces `forces` sums: all of them; the elastic and damping forces alone; the
  /// quadratic-velocity inertial forces alone.
  enum class Terms { All, Internal, Inertial };

  /// With accelerations `acc` (and inertial terms), M a is added: the centre line's G_r a (translationJacobian)
  /// to ρA r̈, the section's G_ω a = Cᵀ a_ω¹ + T_C(α) (∂α/∂δ_local) Λ a (rotationJacobian) to ω̇.
  template <class S>
  [[gnu::flatten]] V<S> forces(const Q<S>& q, const V<S>& v, const Vec3& gravity, Terms terms, const V<S>* acc = nullptr) const {
    const bool inertia = terms != Terms::Internal, internal = terms != Terms::Inertial, weight = terms == Terms::All;
    using Jet = spline_beam_detail::Jet2<S>;
    const Ends<S> e = ends(q);
    const Relative<S> rel = relative(e);
    const Eigen::Matrix<S, kLocal, 1> vl = localRates(e, rel, v);  // Λ dq
    const Eigen::Matrix<S, kLocal, 1> al = acc ? localRates(e, rel, *acc) : Eigen::Matrix<S, kLocal, 1>::Zero();  // Λ a
    const Eigen::Vector4d K = stiffness();
    const SectionProperties p = section.properties(material);
    const double rhoA = p.rhoA;
    const Vec3 rhoJ(p.rhoIp, p.rhoIy, p.rhoIz);

    // The relative deformation along the path q(τ) = (r + τṙ, R exp(τω̃), s + τṡ) to second
    // order: with W = ω̃, R¹ᵀ(τ) = exp(−τW¹)R¹ᵀ, d(τ) = exp(−τW¹)(d + τu), u = R¹ᵀ(ṙ² − ṙ¹),
    // R₁₂(τ) = exp(−τW¹) R₁₂ exp(τW²):
    //   d' = u − W¹d,  d'' = W¹²d − 2W¹u,  R₁₂' = R₁₂W² − W¹R₁₂,  R₁₂'' = W¹²R₁₂ − 2W¹R₁₂W² + R₁₂W²².
    const Vec3T<S> w1 = v.template segment<3>(3), w2 = v.template segment<3>(10);
    const Jet zero{S(0.0), S(0.0), S(0.0)};
    Jet pd[3], pt[3], pphi12 = zero, ps1 = zero, ps2 = zero;  // d(τ), R₁₂(τ) e_x, φ₁₂(τ), s(τ)
    if (inertia) {
      const Mat3T<S> W1 = skew<S>(w1), W2 = skew<S>(w2);
      const Vec3T<S> u = e.R1.transpose() * (v.template segment<3>(7) - v.template head<3>());
      const Vec3T<S> d1 = vl.template head<3>(), d2 = W1 * (W1 * rel.d) - 2.0 * (W1 * u);  // d1 = u − W¹d
      const Mat3T<S> R1d = rel.R12 * W2 - W1 * rel.R12;
      const Mat3T<S> R2d = W1 * (W1 * rel.R12) - 2.0 * (W1 * rel.R12 * W2) + rel.R12 * (W2 * W2);
      for (int i = 0; i < 3; ++i) {
        pd[i] = {rel.d(i), d1(i), d2(i)};
        pt[i] = {rel.R12(i, 0), R1d(i, 0), R2d(i, 0)};
      }
      pphi12 = spline_beam_detail::atan2(Jet{rel.R12(2, 1), R1d(2, 1), R2d(2, 1)}, Jet{rel.R12(2, 2), R1d(2, 2), R2d(2, 2)});
      ps1 = {rel.s1, v(6), S(0.0)};
      ps2 = {rel.s2, v(13), S(0.0)};
    }

    // Forces are gathered per Gauss point in the cheapest coordinates and mapped once at the end:
    // gl along the local perturbations (elastic, damping, and the relative-rotation part of
    // G_ωᵀ), fN[k] = Σ w L N_k f_r for G_rᵀ, m1 = Σ w L ρ C h for the Cᵀ-part of G_ωᵀ (on ω¹).
    Eigen::Matrix<S, kLocal, 1> gl = Eigen::Matrix<S, kLocal, 1>::Zero();
    Vec3T<S> fN[4] = {Vec3T<S>::Zero(), Vec3T<S>::Zero(), Vec3T<S>::Zero(), Vec3T<S>::Zero()};
    Vec3T<S> m1 = Vec3T<S>::Zero();
    for (int g = 0; g < rule.points; ++g) {
      const double xi = rule.xi[g], wL = rule.weight[g] * length;
      const SectionDerivatives<S> sd = sectionDerivatives(rel, xi, internal);
      if (internal) {
        for (int i = 0; i < 4; ++i) {
          S sigma = sd.strain(i);
          if (damping > 0.0) sigma += damping * sd.dstrain.row(i).dot(vl.transpose());
          gl += ((wL * K(i)) * sigma) * sd.dstrain.row(i).transpose();
        }
      }
      if (!inertia && !weight) continue;
      const HermiteBasis b = hermiteBasis(xi, length);
      Vec3T<S> fr = Vec3T<S>::Zero();
      if (weight) fr -= (rhoA * gravity).template cast<S>();
      if (inertia) {
        // r̈ at d(dq)/dt = 0: Σ N₁ d²/dτ²(s R exp(τω̃) e_x) = N₁ (2ṡ R(ω × e_x) + s R(ω × (ω × e_x)))
        const Vec3T<S> ex = Vec3T<S>::UnitX();
        const Vec3T<S> a1 = e.R1 * ((2.0 * v(6)) * w1.cross(ex) + e.s1 * w1.cross(w1.cross(ex)));
        const Vec3T<S> a2 = e.R2 * ((2.0 * v(13)) * w2.cross(ex) + e.s2 * w2.cross(w2.cross(ex)));
        fr += rhoA * (b.N[1] * a1 + b.N[3] * a2);
        if (acc) fr += rhoA * centreLineAcceleration(e, b, *acc);
        // ω = Cᵀω¹ + ω_rel, ω̇ at d(dq)/dt = 0: −ω_rel × Cᵀω¹ + d/dt(T_C(α) α̇)
        Jet a[3], c[3];  // R¹ᵀ r', R¹ᵀ r'' along the path (as in sectionState)
        for (int i = 0; i < 3; ++i) {
          a[i] = pd[i] * b.dN[2] + ps2 * pt[i] * b.dN[3];
          c[i] = pd[i] * b.ddN[2] + ps2 * pt[i] * b.ddN[3];
        }
        a[0] = a[0] + ps1 * b.dN[1];
        c[0] = c[0] + ps1 * b.ddN[1];
        const Angles<Jet> ang = sectionAngles<Jet>(a, c, pphi12, xi);  // α, α̇, α̈
        // ω_rel = T_C(α) α̇ (B-17), ω̇_rel = Ṫ_C α̇ + T_C α̈ (B-19)
        const spline_beam_detail::JetSinCos<S> of_phi = spline_beam_detail::sinCos(ang.phi);
        const spline_beam_detail::JetSinCos<S> of_psi = spline_beam_detail::sinCos(ang.psi);
        const Jet &sf = of_phi.sin, &cf = of_phi.cos, &sp = of_psi.sin, &cp = of_psi.cos;
        const Jet t02 = -sp, t12 = sf * cp, t21 = -sf, t22 = cf * cp;  // t00 = 1, t11 = cφ
        const S r0 = ang.phi.d, r1 = ang.psi.d, r2 = ang.theta.d;
        const S a0 = ang.phi.dd, a1r = ang.psi.dd, a2r = ang.theta.dd;
        Vec3T<S> wr, wrDot;
        wr << r0 + t02.v * r2, cf.v * r1 + t12.v * r2, t21.v * r1 + t22.v * r2;
        wrDot << a0 + t02.v * a2r + t02.d * r2,                              //
            cf.v * a1r + cf.d * r1 + t12.v * a2r + t12.d * r2,               //
            t21.v * a1r + t21.d * r1 + t22.v * a2r + t22.d * r2;
        using std::cos, std::sin;
        const Mat3T<S> C = cardanMatrix<S>(sf.v, cf.v, sp.v, cp.v, sin(ang.theta.v), cos(ang.theta.v));
        const Vec3T<S> w1c = C.transpose() * w1;
        const Vec3T<S> w = w1c + wr;
        Vec3T<S> wDot = wrDot - wr.cross(w1c);
        if (acc) {  // G_ω a
          const Vec3T<S> x = sd.dalpha * al;
          wDot += C.transpose() * acc->template segment<3>(3);
          wDot += Vec3T<S>(x(0) + t02.v * x(2), cf.v * x(1) + t12.v * x(2), t21.v * x(1) + t22.v * x(2));
        }
        // G_ωᵀ h = [C h on ω¹] + Λᵀ (∂α/∂δ_local)ᵀ T_Cᵀ h,  h = J_c ω̇ + ω × J_c ω
        const Vec3T<S> h = wL * (sectionInertia<S, 1>(rhoJ, wDot) + w.cross(sectionInertia<S, 1>(rhoJ, w)));
        const Vec3T<S> y(h(0), cf.v * h(1) + t21.v * h(2), t02.v * h(0) + t12.v * h(1) + t22.v * h(2));  // T_Cᵀ h
        m1 += C * h;
        gl.noalias() += sd.dalpha.transpose() * y;
      }
      for (int k = 0; k < 4; ++k) fN[k] += (wL * b.N[k]) * fr;
    }
    V<S> F = (internal || inertia) ? localForce(e, rel, gl) : V<S>::Zero();
    if (!inertia && !weight) return F;
    // G_rᵀ: per end, [N₀ f, s(0, −R e_z·N₁f, R e_y·N₁f), R e_x·N₁f] (see translationJacobian)
    const Mat3T<S>* R[2] = {&e.R1, &e.R2};
    const S* st[2] = {&e.s1, &e.s2};
    for (int n = 0; n < 2; ++n) {
      const int o = kNodeSize * n;
      const Vec3T<S>& f0 = fN[2 * n];
      const Vec3T<S>& f1 = fN[2 * n + 1];
      F.template segment<3>(o) += f0;
      F(o + 4) -= (*st[n]) * R[n]->col(2).dot(f1);
      F(o + 5) += (*st[n]) * R[n]->col(1).dot(f1);
      F(o + 6) += R[n]->col(0).dot(f1);
    }
    F.template segment<3>(3) += m1;
    return F;
  }
};

}  // namespace cranesim
