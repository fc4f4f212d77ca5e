#pragma once
// Spatial co-rotational Timoshenko beam (thesis 3.3, C.2): one segment between two frame nodes,
// q_e = [r¹, φ¹, r², φ²] (3-28), forces along the body twists. Co-rotated mid-frame, local
// deformations (3-34), exact Timoshenko stiffness from the consistent shape functions of C.2.6
// (two Gauss points, no shear locking), optional Kelvin–Voigt damping; inertia and gravity of
// material riding on a cubic Hermite centre line with geodesic section rotation, exact kinetic
// energy (the inertial forces do no work).
// Thesis errata kept here: its shear stiffness GA/4 (3-43, C-20) is a factor 4 too soft and
// lacks κ (σ_xy = G ε_xy in (3-41) should be 2G ε_xy, counted once in C-28), so Φ = 12 EI/(κGA L²)
// replaces its α = 48EI/(AGL²); its torsion stiffness G(I_y + I_z)/4 is GJ here; it names I_y
// and I_z the other way round (C-56): here I_y = ∫z² dA pairs with ψ_y.
// Derivation: docs/elements.md#co-rotational-timoshenko-beam.

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <type_traits>

#include "cranesim/elements/parts/corotated_elastic_tangent.hpp"
#include "cranesim/elements/parts/corotation.hpp"
#include "cranesim/elements/parts/objective_tangent.hpp"
#include "cranesim/elements/section.hpp"
#include "cranesim/elements/parts/section_inertia_coordinate_tangent.hpp"
#include "cranesim/elements/parts/section_inertia_forces.hpp"
#include "cranesim/elements/parts/section_inertia_tangent.hpp"
#include "cranesim/elements/parts/section_mass_matrix.hpp"
#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/gauss_legendre.hpp"
#include "cranesim/math/hermite.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {

struct TimoshenkoBeamKernel {
  static constexpr int kNodes = 2;
  static constexpr int kNq = 12;
  static constexpr int kNv = 12;
  template <class S> using Q = Eigen::Matrix<S, kNq, 1>;
  template <class S> using V = Eigen::Matrix<S, kNv, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;
  using Mat6x12 = Eigen::Matrix<double, 6, 12>;

  double length = 1.0;  // L, unstretched length of the segment, m
  Section section;
  Material material;
  int mass_points = 4;       // Gauss points for mass, inertial forces, gravity (4: exact for the cubic centre line)
  int stiffness_points = 2;  // Gauss points for K (2: exact with the consistent shape functions)
  double damping = 0.0;      // Kelvin–Voigt retardation time η, s (σ = E(ε + η ε̇)); 0: off

  bool damped() const { return damping > 0.0; }

  // ---------------------------------------------------------------------------------------------
  // Consistent Timoshenko shape functions (C.2.6)

  /// Φ = 12 EI/(κ G A L²) of the bending plane with second moment I; 0 (Euler–Bernoulli) when
  /// the section has no shear factor.
  static double shearParameter(double EI, double kGA, double length) {
    return kGA > 0.0 ? 12.0 * EI / (kGA * length * length) : 0.0;
  }

  /// Interpolation of the local deformation q_d,c = [u, v, w, ψ_x, ψ_y, ψ_z] at ξ = s/L from the
  /// end deformations d = [u¹, ψ¹, u², ψ²] (3-48): q_d,c = N d, q_d,c' = dN d (d/ds).
  struct ShapeFunctions {
    Mat6x12 N = Mat6x12::Zero(), dN = Mat6x12::Zero();
  };

  ShapeFunctions shapeFunctions(double xi) const;

  /// Section strains [ε, κ_x, κ_y, κ_z, γ_y, γ_z] = B(ξ) d (C-16).
  Mat6x12 strainMatrix(double xi) const;

  /// Local stiffness K = ∫ Bᵀ D B ds of the end deformations d (the thesis' K_d,end, C-33).
  Mat12 localStiffness() const;

  /// K kept once the kernel's section and material are final (makeElement does it), so that
  /// the forces need not integrate it again at every call.
  void keepStiffness() { kept_stiffness_ = localStiffness(); }
  /// K: the kept one, or integrated now.
  Mat12 stiffness() const { return kept_stiffness_ ? *kept_stiffness_ : localStiffness(); }

  // ---------------------------------------------------------------------------------------------
  // Co-rotated frame and local deformations (3-29, 3-34)

  template <class S> using CoRotated = cranesim::CoRotated<S>;
  template <class S> using CoRotatedTangent = cranesim::CoRotatedTangent<S>;

  template <class S>
  CoRotated<S> coRotate(const Vec3T<S>& r1, const Mat3T<S>& R1, const Vec3T<S>& r2, const Mat3T<S>& R2) const {
    return cranesim::coRotation<S, false>(meanFrame<S>(r1, R1, r2, R2), R1, R2, length);
  }

  template <class S>
  CoRotatedTangent<S> coRotateWithTangent(const Vec3T<S>& r1, const Mat3T<S>& R1, const Vec3T<S>& r2,
                                          const Mat3T<S>& R2) const {
    return cranesim::coRotation<S, true>(meanFrame<S>(r1, R1, r2, R2), R1, R2, length);
  }

  /// Local deformations d(q).
  template <class S> Eigen::Matrix<S, 12, 1> localDeformation(const Q<S>& q) const {
    return coRotate<S>(q.template segment<3>(0), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3))),
                       q.template segment<3>(6), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9))))
        .d;
  }

  double strainEnergy(const Q<double>& q) const;

  /// Elastic and damping forces along dq: J_dᵀ K (d + η J_d dq).
  template <class S> V<S> elasticForce(const Q<S>& q, const V<S>& v) const {
    return elasticForce<S>(q.template segment<3>(0), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3))),
                           q.template segment<3>(6), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9))), v,
                           stiffness());
  }

  /// The same from the end frames and a precomputed K = localStiffness() (for callers that
  /// know the frames as matrices, e.g. the super truss element).
  template <class S>
  V<S> elasticForce(const Vec3T<S>& r1, const Mat3T<S>& R1, const Vec3T<S>& r2, const Mat3T<S>& R2, const V<S>& v,
                    const Mat12& K) const {
    return elasticForce<S>(coRotateWithTangent<S>(r1, R1, r2, R2), v, K);
  }

  /// The same from a co-rotation already made.
  template <class S> V<S> elasticForce(const CoRotatedTangent<S>& c, const V<S>& v, const Mat12& K) const {
    Eigen::Matrix<S, 12, 1> strain = c.d;
    if (damping > 0.0) strain.noalias() += S(damping) * c.apply(v);
    return c.applyTransposed(stiffnessTimes<S>(K, strain));
  }

  /// Section forces at the two ends, [N, V_y, V_z, T, M_y, M_z] at end 1 and then at end 2, in
  /// the co-rotated frame R_B (x along the chord; N > 0 in tension): the forces the nodes exert
  /// on the beam, its residual M a + F (elastic, damping, inertia and gravity), turned into R_B
  /// (the rotational parts act about the section frames' axes) — at end 2 the section's
  /// resultant, at end 1 with the opposite sign (its face points the other way).
  Eigen::Matrix<double, 12, 1> sectionForces(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2, const V<double>& v,
                                             const V<double>& a, const Vec3& gravity, const Mat12& K) const;
  Eigen::Matrix<double, 12, 1> sectionForces(const Q<double>& q, const V<double>& v, const V<double>& a, const Vec3& gravity) const;

  /// The damping forces alone, η J_dᵀ K J_d dq (their power is the Kelvin–Voigt dissipation).
  template <class S> V<S> dampingForce(const Q<S>& q, const V<S>& v) const {
    return dampingForce<S>(q.template segment<3>(0), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3))),
                           q.template segment<3>(6), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9))), v,
                           stiffness());
  }
  template <class S>
  V<S> dampingForce(const Vec3T<S>& r1, const Mat3T<S>& R1, const Vec3T<S>& r2, const Mat3T<S>& R2, const V<S>& v,
                    const Mat12& K) const {
    const CoRotatedTangent<S> c = coRotateWithTangent<S>(r1, R1, r2, R2);
    return S(damping) * c.applyTransposed(stiffnessTimes<S>(K, c.apply(v)));
  }

 private:
  std::optional<Mat12> kept_stiffness_;

  /// K x: for dual numbers coefficient by coefficient with K's entries as plain factors, as
  /// K.cast<S>() * x computes it but without multiplying K's zero derivatives (same values).
  template <class S> static Eigen::Matrix<S, 12, 1> stiffnessTimes(const Mat12& K, const Eigen::Matrix<S, 12, 1>& x) {
    if constexpr (std::is_same_v<S, double>)
      return K * x;
    else
      return K.lazyProduct(x);
  }

 public:
  // ---------------------------------------------------------------------------------------------
  // Interpolated section motion (inertia, gravity, output)

  /// The end frames and their relative rotation φ = log(R¹ᵀR²), computed once per call.
  template <class T> struct EndFrames {
    Vec3T<T> r1, r2;
    Mat3T<T> R1, R2, Rrel, TinvRrelT, Tinv;  // Rrel = R¹ᵀR², Tinv = T(φ)⁻¹, TinvRrelT = T(φ)⁻¹ Rrelᵀ
    Vec3T<T> phi;
  };

  template <class T>
  EndFrames<T> endFrames(const Vec3T<T>& r1, const Mat3T<T>& R1, const Vec3T<T>& r2, const Mat3T<T>& R2) const {
    EndFrames<T> f{r1, r2, R1, R2, R1.transpose() * R2, Mat3T<T>(), Mat3T<T>(), Vec3T<T>()};
    f.phi = rotationLog<T>(f.Rrel);
    f.Tinv = angularVelocityMapInverse<T>(f.phi);
    f.TinvRrelT = f.Tinv * f.Rrel.transpose();
    return f;
  }

  template <class S> EndFrames<S> endFrames(const Q<S>& q) const {
    return endFrames<S>(q.template segment<3>(0), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3))),
                        q.template segment<3>(6), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9))));
  }

  /// Position and rotation of the section at ξ ∈ [0, 1] (the interpolation used for inertia):
  /// x = N0¹ r¹ + N1¹ R¹e_x + N0² r² + N1² R²e_x (A-9 with unit end slopes), R_c = R¹ exp(ξφ̃).
  template <class S> FrameT<S> sectionFrame(const Q<S>& q, double xi) const {
    const EndFrames<S> e = endFrames<S>(q);
    const HermiteBasis h = hermiteBasis(xi, length);
    return FrameT<S>{Vec3T<S>(S(h.N[0]) * e.r1 + S(h.N[1]) * e.R1.col(0) + S(h.N[2]) * e.r2 + S(h.N[3]) * e.R2.col(0)),
                     Mat3T<S>(e.R1 * rotationMatrix<S>(Vec3T<S>(S(xi) * e.phi)))};
  }

  /// M = ∫ (ρA H_xᵀH_x + H_Ωᵀ ρJ H_Ω) ds: the Gauss points as mass stations with mass w ρA, no
  /// first moment and inertia w ρJ (section_mass_matrix.hpp).
  template <class S> Eigen::Matrix<S, 12, 12> massMatrix(const Q<S>& q, double = 0.0) const {
    return massMatrix<S>(endFrames<S>(q));
  }

  template <class S> Eigen::Matrix<S, 12, 12> massMatrix(const EndFrames<S>& e) const {
    const SectionProperties p = section.properties(material);
    const Vec3 J(p.rhoIp, p.rhoIy, p.rhoIz);
    const GaussRule& rule = gaussLegendre(mass_points);
    SectionMassMatrix<S> M(e.R1, e.Rrel, e.phi, e.Tinv, length);
    for (int g = 0; g < rule.points; ++g) {
      const double w = rule.weight[g] * length;
      M.add(rule.xi[g], w * p.rhoA, Vec3::Zero(), Mat3((w * J).asDiagonal()));
    }
    return M.matrix();
  }

  /// Quadratic-velocity inertial forces and gravity: ∫ H_xᵀ ρA (Ḣ_x dq − g)
  /// + H_Ωᵀ (ρJ Ḣ_Ω dq + Ω × ρJ Ω) ds, Gauss point by Gauss point (section_inertia_forces.hpp).
  /// With accelerations `a`, M a is added in the same pass (H a joins Ḣ dq), which is cheaper
  /// than building M.
  template <class S>
  V<S> inertialAndGravityForce(const Vec3T<S>&, const Mat3T<S>& R1, const Vec3T<S>&, const Mat3T<S>& R2, const V<S>& v,
                               const Vec3& gravity, const V<S>* a = nullptr) const {
    SectionInertiaForces<S> inertia(R1, R2, v, a, gravity, length);
    addMassPoints(inertia);
    return inertia.forces();
  }

  /// Calls sum.add(ξ, w ρA, w ρJ) for the Gauss points of the mass rule (weights w in length).
  template <class Sum> void addMassPoints(Sum& sum) const {
    const SectionProperties p = section.properties(material);
    const Vec3 J(p.rhoIp, p.rhoIy, p.rhoIz);
    const GaussRule& rule = gaussLegendre(mass_points);
    for (int gp = 0; gp < rule.points; ++gp) {
      const double wl = rule.weight[gp] * length;
      sum.add(rule.xi[gp], wl * p.rhoA, Vec3(wl * J));
    }
  }

  /// ∂(M a + F)/∂q (element.hpp) from M and the velocity tangent C (objective_tangent.hpp): the
  /// elastic and damping forces' columns of end 2 in closed form (corotated_elastic_tangent.hpp),
  /// the inertial and gravity forces' in its three rotation directions
  /// (section_inertia_coordinate_tangent.hpp), the other columns by frame indifference.
  Mat12 coordinateTangent(const Q<double>& q, const V<double>& v, const V<double>& a, double, const Vec3& gravity,
                          const Mat12& M, const Mat12& C) const;

  /// ∂(M a + F)/∂dq in closed form (section_inertia_tangent.hpp: the Gauss points as stations
  /// with mass w ρA, no first moment, inertia w ρJ) and M beside it (element.hpp).
  Mat12 velocityTangent(const Q<double>& q, const V<double>& v, double, Mat12& M) const;

  /// The same from the end frames and a precomputed K = localStiffness().
  Mat12 velocityTangent(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2, const V<double>& v, const Mat12& K,
                        Mat12& M) const;

  /// ∂(M a + F)/∂dq in closed form and M beside it for mass stations riding on this interpolation
  /// (section_inertia_tangent.hpp), with the damping η J_dᵀ K J_d of the co-rotated stiffness K.
  /// `stations(add)` calls add(ξ, m, s, J) for every station.
  template <class Stations>
  Mat12 stationVelocityTangent(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2, const V<double>& v,
                               const Mat12& K, const Stations& stations, Mat12& M) const {
    const EndFrameRates e = endFrameRates(r1, R1, r2, R2, v);
    const EndFrames<double>& f = e.frames;
    SectionInertiaTangent inertia(f.R1, f.Rrel, f.phi, e.phi_dot, f.Tinv, f.TinvRrelT, e.Tinv_dot, e.TinvRrelT_dot, v, length);
    stations([&](double xi, double mass, const Vec3& first_moment, const Mat3& J) { inertia.add(xi, mass, first_moment, J); });
    M = inertia.matrix();
    Mat12 G = inertia.velocityTangent();
    subtractTwistBracket(M, v, G);
    if (damped()) {
      // η J_dᵀ K J_d through J_d's seven nonzero rows (ψ¹, u²_x, ψ²) and K between them.
      constexpr std::array<int, 7> rows{3, 4, 5, 6, 9, 10, 11};
      const Mat12 Jd = coRotateWithTangent<double>(r1, R1, r2, R2).matrix();
      Eigen::Matrix<double, 7, 12> J7;
      Eigen::Matrix<double, 7, 7> K7;
      for (int i = 0; i < 7; ++i) {
        J7.row(i) = Jd.row(rows[i]);
        for (int j = 0; j < 7; ++j) K7(i, j) = K(rows[i], rows[j]);
      }
      const Eigen::Matrix<double, 7, 12> KJ = K7.lazyProduct(J7);
      G.noalias() += damping * J7.transpose().lazyProduct(KJ);
    }
    return G;
  }

  /// The end frames and the rates along the motion (dq held constant) of what the section maps
  /// take from them: φ̇ and the rates of T(φ)⁻¹ and T(φ)⁻¹ R_relᵀ (one forward-AD direction
  /// through the end frames, Ṙⁿ = Rⁿ ω̃ⁿ, once per call).
  struct EndFrameRates {
    EndFrames<double> frames;
    Mat3 Tinv_dot, TinvRrelT_dot;
    Vec3 phi_dot;
  };
  EndFrameRates endFrameRates(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2, const V<double>& v) const;

  template <class S> V<S> force(const Q<S>& q, const V<S>& v, double, const Vec3& gravity) const {
    return forcesAndInertia<S>(q, v, nullptr, gravity);
  }

  /// M a + F in one pass over the Gauss points (element.hpp: fused residual).
  template <class S> V<S> residual(const Q<S>& q, const V<S>& v, const V<S>& a, double, const Vec3& gravity) const {
    return forcesAndInertia<S>(q, v, &a, gravity);
  }

  /// F, and with accelerations `a` M a + F: the end rotations formed once for the inertial,
  /// gravity and elastic forces.
  template <class S> V<S> forcesAndInertia(const Q<S>& q, const V<S>& v, const V<S>* a, const Vec3& gravity) const {
    const Vec3T<S> r1 = q.template segment<3>(0), r2 = q.template segment<3>(6);
    const Mat3T<S> R1 = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3)));
    const Mat3T<S> R2 = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9)));
    return inertialAndGravityForce<S>(r1, R1, r2, R2, v, gravity, a) + elasticForce<S>(r1, R1, r2, R2, v, stiffness());
  }

  /// −∫ H_xᵀ ρA g ds: inertialAndGravityForce at rest (dq = 0, d(dq)/dt = 0). Gravity acts on
  /// the centre line alone, x = N₀ r¹ + N₁ R¹e_x + N₂ r² + N₃ R²e_x (sectionMap), whose blocks
  /// give H_xᵀ g = [N₀ g, N₁ e_x × R¹ᵀ g, N₂ g, N₃ e_x × R²ᵀ g]: the weights ∫ Nᵢ ds times four
  /// vectors, without the section rotations.
  template <class S> V<S> gravityForce(const EndFrames<S>& e, const Vec3& gravity) const {
    const std::array<double, 4> n = centreLineWeights();
    const double rhoA = section.properties(material).rhoA;
    const Vec3T<S> g = gravity.cast<S>(), ex = Vec3::UnitX().cast<S>();
    V<S> F;
    F.template segment<3>(0) = S(-rhoA * n[0]) * g;
    F.template segment<3>(3) = S(-rhoA * n[1]) * ex.cross(Vec3T<S>(e.R1.transpose() * g));
    F.template segment<3>(6) = S(-rhoA * n[2]) * g;
    F.template segment<3>(9) = S(-rhoA * n[3]) * ex.cross(Vec3T<S>(e.R2.transpose() * g));
    return F;
  }

  /// ∫ Nᵢ ds of the centre line's Hermite functions, by the mass quadrature.
  std::array<double, 4> centreLineWeights() const;

  double kineticEnergy(const Q<double>& q, const V<double>& v, double = 0.0) const;

  /// −∫ ρA g·x ds (same quadrature as the gravity forces) + strain energy.
  double gravityPotential(const Q<double>& q, const Vec3& gravity) const;

  /// −∫ ρA g·x ds over the centre line (gravityForce's potential).
  double gravityPotential(const EndFrames<double>& e, const Vec3& gravity) const;

  double potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const;
};

}  // namespace cranesim
