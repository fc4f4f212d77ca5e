#pragma once
// Condensed truss element: a whole lattice section on its two end sections (12 DOF, as
// super_truss.hpp) with the full-member model's linear stiffness condensed statically onto
// them, K_red = K_bb − K_bi K_ii⁻¹ K_ib, applied co-rotationally as the Timoshenko beam's
// (3-29..3-34); the tubes' mass rides on the Timoshenko interpolation in mass stations per bay.
// Derivation: docs/elements.md#condensed-truss.

#include <algorithm>
#include <cmath>
#include <vector>

#include "cranesim/elements/parts/objective_tangent.hpp"
#include "cranesim/elements/parts/section_inertia_coordinate_tangent.hpp"
#include "cranesim/elements/parts/section_inertia_forces.hpp"
#include "cranesim/elements/parts/section_mass_matrix.hpp"
#include "cranesim/elements/timoshenko_beam.hpp"
#include "cranesim/math/gauss_legendre.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/truss_geometry.hpp"

namespace cranesim {

struct CondensedTrussKernel {
  static constexpr int kNodes = 2;
  static constexpr int kNq = 12;
  static constexpr int kNv = 12;
  template <class S> using Q = Eigen::Matrix<S, kNq, 1>;
  template <class S> using V = Eigen::Matrix<S, kNv, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;

  /// Material on the section at ξ, about the axis point, in the section frame.
  struct MassStation {
    double xi = 0.0;
    double mass = 0.0;
    Vec3 first_moment = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
  };

  double length = 0.0;
  TimoshenkoBeamKernel frame;  // co-rotation, section interpolation, damping η (its own section unused)
  Mat12 stiffness = Mat12::Zero();  // K_red on [u¹, θ¹, u², θ²], truss axes
  std::vector<MassStation> stations;

  CondensedTrussKernel() = default;

  bool damped() const { return frame.damped(); }

  /// `points_per_bay`: Gauss points of the mass stations in each bay; `damping`: Kelvin–Voigt
  /// retardation time η of every tube, s.
  explicit CondensedTrussKernel(const TrussGeometry& g, int points_per_bay = 3, double damping = 0.0) : length(g.length) {
    frame.length = g.length;
    frame.damping = damping;
    stiffness = condensedStiffness(g);
    stations = massStations(g, points_per_bay);
  }

  // ---------------------------------------------------------------------------------------------
  // Kernel contract (element.hpp)

  /// M = Σ H_xᵀ (m H_x − R_c s̃ H_Ω) + H_Ωᵀ (s̃ R_cᵀ H_x + J H_Ω) over the mass stations
  /// (section_mass_matrix.hpp).
  template <class S> Eigen::Matrix<S, kNv, kNv> massMatrix(const Q<S>& q, double = 0.0) const {
    const auto e = frame.endFrames<S>(q);
    SectionMassMatrix<S> M(e.R1, e.Rrel, e.phi, e.Tinv, length);
    for (const MassStation& st : stations) M.add(st.xi, st.mass, st.first_moment, st.inertia);
    return M.matrix();
  }

  template <class S> V<S> force(const Q<S>& q, const V<S>& v, double, const Vec3& gravity) const {
    return forcesAndInertia<S>(q, v, nullptr, gravity);
  }

  /// M a + F in one pass over the stations (element.hpp: fused residual).
  template <class S> V<S> residual(const Q<S>& q, const V<S>& v, const V<S>& a, double, const Vec3& gravity) const {
    return forcesAndInertia<S>(q, v, &a, gravity);
  }

  /// ∂(M a + F)/∂q (element.hpp) from M and the velocity tangent C (objective_tangent.hpp): the
  /// elastic and damping forces' columns of end 2 in closed form (corotated_elastic_tangent.hpp),
  /// the inertial and gravity forces' in its three rotation directions
  /// (section_inertia_coordinate_tangent.hpp), the other columns by frame indifference.
  Mat12 coordinateTangent(const Q<double>& q, const V<double>& v, const V<double>& a, double, const Vec3& gravity,
                          const Mat12& M, const Mat12& C) const;

  /// ∂(M a + F)/∂dq in closed form (section_inertia_tangent.hpp) and M beside it (element.hpp).
  Mat12 velocityTangent(const Q<double>& q, const V<double>& v, double, Mat12& M) const;

  /// J_dᵀ K_red (d + η J_d dq): elastic and damping forces.
  template <class S> V<S> elasticForce(const Q<S>& q, const V<S>& v) const {
    return frame.elasticForce<S>(q.template segment<3>(0), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3))),
                                 q.template segment<3>(6), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9))), v,
                                 stiffness);
  }

  /// η J_dᵀ K_red J_d dq: the damping forces alone.
  template <class S> V<S> dampingForce(const Q<S>& q, const V<S>& v) const {
    return frame.dampingForce<S>(q.template segment<3>(0), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3))),
                                 q.template segment<3>(6), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9))), v,
                                 stiffness);
  }

  double strainEnergy(const Q<double>& q) const;

  double kineticEnergy(const Q<double>& q, const V<double>& v, double = 0.0) const;

  /// −Σ g·(m x + R_c s) + strain energy: with x = N₀ r¹ + N₁ R¹e_x + N₂ r² + N₃ R²e_x and
  /// R_c s = R¹ exp(ξφ̃) s, the sums Σ m Nᵢ and Σ exp(ξφ̃) s times per-call vectors.
  double potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const;

  double mass() const {
    double m = 0.0;
    for (const MassStation& st : stations) m += st.mass;
    return m;
  }

 private:
  /// F, and with accelerations `a` M a + F: the end rotations formed once for both parts.
  template <class S> V<S> forcesAndInertia(const Q<S>& q, const V<S>& v, const V<S>* a, const Vec3& gravity) const {
    const Mat3T<S> R1 = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3)));
    const Mat3T<S> R2 = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9)));
    return inertiaAndGravity<S>(R1, R2, v, a, gravity) +
           frame.elasticForce<S>(q.template segment<3>(0), R1, q.template segment<3>(6), R2, v, stiffness);
  }

  /// Inertial (and, with `a`, M a) and gravity forces of the mass stations from the end rotations
  /// (they do not depend on the end positions).
  template <class S>
  V<S> inertiaAndGravity(const Mat3T<S>& R1, const Mat3T<S>& R2, const V<S>& v, const V<S>* a, const Vec3& gravity) const {
    SectionInertiaForces<S> inertia(R1, R2, v, a, gravity, length);
    for (const MassStation& st : stations) inertia.add(st.xi, st.mass, st.first_moment, st.inertia);
    return inertia.forces();
  }

  /// K_red of the linear full-member model (see the file comment).
  static Mat12 condensedStiffness(const TrussGeometry& g);

  /// The tubes' material as mass stations (see the file comment).
  static std::vector<MassStation> massStations(const TrussGeometry& g, int points_per_bay);
};

}  // namespace cranesim
