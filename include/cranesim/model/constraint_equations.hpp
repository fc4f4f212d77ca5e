#pragma once
// Constraint equations Φ(J1, J2, t) = 0 between two joint frames (thesis 4.4), written once
// and templated on the scalar: B (4-11) and Γ (4-14, 4-19, 4-22) follow by automatic
// differentiation (see assembly/constraint_evaluation.hpp), the second derivatives of the DAE
// Jacobian in closed form through the equations' primitives (constraint_second_derivatives.hpp).
// e_i^k = R_Jk g_i are the joint axes.

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

/// The vectors the equations are made of: the separation d = r_J¹ − r_J² of the joint origins,
/// the joint axes e_k¹ = R_J1 g_k and e_k² = R_J2 g_k, and the inertial axes g_k.
enum class ConstraintVector { Separation, Axis1, Axis2, Inertial };
struct ConstraintVectorRef {
  ConstraintVector kind = ConstraintVector::Inertial;
  int index = 0;  // k of an axis
};

/// Every equation is a function of dot products of two such vectors (its primitives) and of
/// time: Φ = h(p, t), p_a = x_a · y_a. The derivatives of Φ follow from those of the frames
/// through the primitives (assembly/constraint_second_derivatives.hpp).
inline constexpr int kMaxConstraintPrimitives = 7;
struct ConstraintPrimitives {
  int count = 0;
  ConstraintVectorRef x[kMaxConstraintPrimitives], y[kMaxConstraintPrimitives];
};

inline ConstraintPrimitives constraintPrimitives(const ConstraintLaw& law) {
  const int i = law.axis, p = (law.axis + 1) % 3, q = (law.axis + 2) % 3;
  using enum ConstraintVector;
  ConstraintPrimitives out;
  const auto add = [&](ConstraintVectorRef x, ConstraintVectorRef y) {
    out.x[out.count] = x;
    out.y[out.count++] = y;
  };
  const auto separation = [&] {
    for (int k = 0; k < 3; ++k) add({Separation, 0}, {Inertial, k});
  };
  // Relative orientation locked: e_y¹·e_z², e_z¹·e_x², e_x¹·e_y² vanish for equal frames (4-13).
  const auto lockRotation = [&] {
    add({Axis1, 1}, {Axis2, 2});
    add({Axis1, 2}, {Axis2, 0});
    add({Axis1, 0}, {Axis2, 1});
  };
  switch (law.type) {
    case ConstraintType::Spherical: separation(); break;  // (4-24)
    case ConstraintType::Fixed:  // (4-13)
      separation();
      lockRotation();
      break;
    case ConstraintType::Revolute:  // (4-15): axes e_i¹ ∥ e_i²
      separation();
      add({Axis1, i}, {Axis2, p});
      add({Axis1, i}, {Axis2, q});
      if (law.drive) {  // cos ψ = e_p¹·e_p², sin ψ = e_q¹·e_p²
        add({Axis1, p}, {Axis2, p});
        add({Axis1, q}, {Axis2, p});
      }
      break;
    case ConstraintType::Prismatic:  // (4-21): slide along e_i¹; d·e¹ = −(r_J² − r_J¹)·e¹
      add({Separation, 0}, {Axis1, p});
      add({Separation, 0}, {Axis1, q});
      lockRotation();
      if (law.drive) add({Separation, 0}, {Axis1, i});
      break;
    case ConstraintType::Distance: add({Separation, 0}, {Separation, 0}); break;
  }
  return out;
}

/// Whether h (constraintFromPrimitives) is linear in the primitives and independent of time:
/// every undriven joint but the distance.
inline bool constraintIsLinear(const ConstraintLaw& law) {
  return !law.drive && law.type != ConstraintType::Distance;
}

/// Φ = h(p, t) from the primitives p (constraintPrimitives) and time.
template <class S> void constraintFromPrimitives(const ConstraintLaw& law, const S* prim, const S& t, S* phi) {
  switch (law.type) {
    case ConstraintType::Spherical:
    case ConstraintType::Fixed:
      for (int k = 0; k < constraintRows(law.type, false); ++k) phi[k] = prim[k];
      return;
    case ConstraintType::Revolute: {
      for (int k = 0; k < 5; ++k) phi[k] = prim[k];
      if (law.drive) {
        // Angle ψ of J2 about e_i relative to J1. With the angle error e = ψ − ψ_d(t) the
        // equation is 2 tan(e/2) = 2 sin e / (1 + cos e) = 0: one root per turn, slope 1 there,
        // and Newton on it maps e to e − sin e, into the root from anywhere within half a turn.
        // (sin e = 0 alone has a false root at e = π and no slope at e = ±π/2.)
        using std::cos, std::sin;
        const S angle = (*law.drive)(t, law.limit);
        const S &cos_psi = prim[5], &sin_psi = prim[6];
        const S sin_e = sin_psi * cos(angle) - cos_psi * sin(angle);
        const S cos_e = cos_psi * cos(angle) + sin_psi * sin(angle);
        phi[5] = 2.0 * sin_e / (1.0 + cos_e);
      }
      return;
    }
    case ConstraintType::Prismatic:
      phi[0] = -prim[0];
      phi[1] = -prim[1];
      for (int k = 2; k < 5; ++k) phi[k] = prim[k];
      if (law.drive) phi[5] = -prim[5] - (*law.drive)(t, law.limit);
      return;
    case ConstraintType::Distance: {
      using std::sqrt;
      phi[0] = sqrt(prim[0]) - (*law.drive)(t, law.limit);
      return;
    }
  }
}

template <class S>
void constraintEquations(const ConstraintLaw& law, const FrameT<S>& j1, const FrameT<S>& j2, const S& t, S* phi) {
  const ConstraintPrimitives primitives = constraintPrimitives(law);
  const Vec3T<S> d = j1.r - j2.r;
  // The three components of a vector of the equations (not Inertial), in place: d or a column
  // of a joint frame (column-major, contiguous).
  const auto components = [&](ConstraintVectorRef ref) -> const S* {
    switch (ref.kind) {
      case ConstraintVector::Axis1: return j1.R.col(ref.index).data();
      case ConstraintVector::Axis2: return j2.R.col(ref.index).data();
      default: return d.data();
    }
  };
  S prim[kMaxConstraintPrimitives];
  for (int a = 0; a < primitives.count; ++a) {
    const ConstraintVectorRef y = primitives.y[a];
    const S* x = components(primitives.x[a]);
    if (y.kind == ConstraintVector::Inertial) {
      prim[a] = x[y.index];  // x · g_k = x_k
    } else {
      const S* z = components(y);
      prim[a] = x[0] * z[0] + x[1] * z[1] + x[2] * z[2];
    }
  }
  constraintFromPrimitives(law, prim, t, phi);
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
