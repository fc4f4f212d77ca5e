#pragma once
// Constraint equations Φ(J1, J2, t) = 0 between two joint frames (thesis 4.4), written once
// and templated on the scalar: B (4-11) and Γ (4-14, 4-19, 4-22) follow by automatic
// differentiation (see assembly/constraint_evaluation.hpp). e_i^k = R_Jk g_i are the joint axes.

#include "cranesim/math/profile.hpp"
#include "cranesim/math/types.hpp"
#include "cranesim/model/scene.hpp"

namespace cranesim {

/// Number of scalar equations of a constraint.
inline int constraintRows(ConstraintType type, bool driven) {
  switch (type) {
    case ConstraintType::Fixed: return 6;
    case ConstraintType::Revolute: return 5 + (driven ? 1 : 0);
    case ConstraintType::Prismatic: return 5 + (driven ? 1 : 0);
    case ConstraintType::Spherical: return 3;
    case ConstraintType::Distance: return 1;
  }
  return 0;
}

/// Parameters of one constraint that the equations need.
struct ConstraintLaw {
  ConstraintType type = ConstraintType::Fixed;
  int axis = 2;                  // i: revolute/prismatic axis; p, q are the two others
  const Profile* drive = nullptr;  // angle, displacement or length; may be null
  Limit limit = Limit::Left;       // side of a drive breakpoint
};

template <class S>
void constraintEquations(const ConstraintLaw& law, const FrameT<S>& j1, const FrameT<S>& j2,
                         const S& t, S* phi) {
  const int i = law.axis, p = (law.axis + 1) % 3, q = (law.axis + 2) % 3;
  const Vec3T<S> d = j1.r - j2.r;
  // Relative orientation locked: e_y¹·e_z², e_z¹·e_x², e_x¹·e_y² vanish for equal frames (4-13).
  const auto lockRotation = [&](S* out) {
    out[0] = j1.R.col(1).dot(j2.R.col(2));
    out[1] = j1.R.col(2).dot(j2.R.col(0));
    out[2] = j1.R.col(0).dot(j2.R.col(1));
  };
  switch (law.type) {
    case ConstraintType::Spherical:  // (4-24)
      for (int k = 0; k < 3; ++k) phi[k] = d(k);
      return;
    case ConstraintType::Fixed:  // (4-13)
      for (int k = 0; k < 3; ++k) phi[k] = d(k);
      lockRotation(phi + 3);
      return;
    case ConstraintType::Revolute: {  // (4-15): axes e_i¹ ∥ e_i²
      for (int k = 0; k < 3; ++k) phi[k] = d(k);
      phi[3] = j1.R.col(i).dot(j2.R.col(p));
      phi[4] = j1.R.col(i).dot(j2.R.col(q));
      if (law.drive) {
        // Angle ψ of J2 about e_i relative to J1: cos ψ = e_p¹·e_p², sin ψ = e_q¹·e_p². With the
        // angle error e = ψ − ψ_d(t) the equation is 2 tan(e/2) = 2 sin e / (1 + cos e) = 0: one
        // root per turn, slope 1 there, and Newton on it maps e to e − sin e, into the root from
        // anywhere within half a turn. (sin e = 0 alone has a false root at e = π and no slope
        // at e = ±π/2.)
        using std::cos, std::sin;
        const S angle = (*law.drive)(t, law.limit);
        const S cos_psi = j1.R.col(p).dot(j2.R.col(p)), sin_psi = j1.R.col(q).dot(j2.R.col(p));
        const S sin_e = sin_psi * cos(angle) - cos_psi * sin(angle);
        const S cos_e = cos_psi * cos(angle) + sin_psi * sin(angle);
        phi[5] = 2.0 * sin_e / (1.0 + cos_e);
      }
      return;
    }
    case ConstraintType::Prismatic: {  // (4-21): slide along e_i¹
      const Vec3T<S> s = j2.r - j1.r;
      phi[0] = s.dot(j1.R.col(p));
      phi[1] = s.dot(j1.R.col(q));
      lockRotation(phi + 2);
      if (law.drive) phi[5] = s.dot(j1.R.col(i)) - (*law.drive)(t, law.limit);
      return;
    }
    case ConstraintType::Distance: {
      using std::sqrt;
      phi[0] = sqrt(d.squaredNorm()) - (*law.drive)(t, law.limit);
      return;
    }
  }
}

/// The coordinate a constraint's drive prescribes, measured between its two joint frames: the
/// revolute's angle ψ in (−π, π], the prismatic's displacement along e_i¹, the distance.
inline double drivenCoordinate(const ConstraintLaw& law, const Frame& j1, const Frame& j2) {
  const int i = law.axis, p = (law.axis + 1) % 3, q = (law.axis + 2) % 3;
  switch (law.type) {
    case ConstraintType::Revolute:
      return std::atan2(j1.R.col(q).dot(j2.R.col(p)), j1.R.col(p).dot(j2.R.col(p)));
    case ConstraintType::Prismatic: return (j2.r - j1.r).dot(j1.R.col(i));
    case ConstraintType::Distance: return (j1.r - j2.r).norm();
    default: return 0.0;
  }
}

}  // namespace cranesim
