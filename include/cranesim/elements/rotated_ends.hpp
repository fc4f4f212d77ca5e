#pragma once
// A Timoshenko beam (timoshenko_beam.hpp) on two frame nodes whose axes differ from the beam's
// section axes by constant rotations (the rigid connection of assumption 3, 3.5.1): the section
// frame of end e is R_e = R(φ_e) O_e with O_e fixed. Beams of different directions can then
// share one frame node, as every joint of a truss does in the full-member model.
//
// With T = diag(I, O₁ᵀ, I, O₂ᵀ) the beam's velocities are dq_b = T dq (the body angular velocity
// of the section frame is O_eᵀ ω_e), so by virtual power M = Tᵀ M_b T and F = Tᵀ F_b, and the
// velocity tangent is Tᵀ C_b T. The beam is evaluated from its end frames as matrices, so no
// rotation vector of the section frames is ever formed. The offsets turn with the nodes, so the
// element stays frame-indifferent: its coordinate columns come from end 2's six
// (objective_tangent.hpp), as the beam's own.

#include <array>

#include "cranesim/elements/timoshenko_beam.hpp"

namespace cranesim {

struct RotatedEndsBeamKernel {
  static constexpr int kNodes = 2;
  static constexpr int kNq = 12;
  static constexpr int kNv = 12;
  template <class S> using Q = Eigen::Matrix<S, kNq, 1>;
  template <class S> using V = Eigen::Matrix<S, kNv, 1>;
  using Mat12 = TimoshenkoBeamKernel::Mat12;

  RotatedEndsBeamKernel(TimoshenkoBeamKernel beam, const Mat3& offset1, const Mat3& offset2)
      : beam_(std::move(beam)), offset_{offset1, offset2}, stiffness_(beam_.localStiffness()) {}

  const TimoshenkoBeamKernel& beam() const { return beam_; }
  bool damped() const { return beam_.damped(); }

  template <class S> Mat3T<S> sectionRotation(const Q<S>& q, int end) const {
    return rotationMatrix<S>(Vec3T<S>(q.template segment<3>(6 * end + 3))) * offset_[end].template cast<S>();
  }

  /// T v: the angular velocities turned into the section axes.
  template <class S> V<S> beamVelocities(const V<S>& v) const {
    V<S> b = v;
    for (int e = 0; e < 2; ++e) b.template segment<3>(6 * e + 3) = offset_[e].transpose().template cast<S>() * v.template segment<3>(6 * e + 3);
    return b;
  }

  /// Tᵀ X for a generalized force X of the beam (or columns of them): its rotation rows turned
  /// into the nodes' axes.
  template <class Derived> typename Derived::PlainObject nodeRows(const Eigen::MatrixBase<Derived>& X) const {
    using S = typename Derived::Scalar;
    typename Derived::PlainObject Y = X;
    for (int e = 0; e < 2; ++e) Y.template middleRows<3>(6 * e + 3) = offset_[e].template cast<S>() * X.template middleRows<3>(6 * e + 3);
    return Y;
  }
  /// Tᵀ X T for a matrix X of the beam (mass, velocity tangent): its rotation rows and columns
  /// turned by the offsets, 3 × 3 block by block (T is the identity elsewhere; as dense 12 × 12
  /// products these took about half of the element's velocity tangent).
  template <class S> Eigen::Matrix<S, 12, 12> toNodeAxes(const Eigen::Matrix<S, 12, 12>& X) const {
    Eigen::Matrix<S, 12, 12> Y = nodeRows(X);
    for (int e = 0; e < 2; ++e) {
      const Mat3T<S> Ot = offset_[e].transpose().template cast<S>();
      Y.template middleCols<3>(6 * e + 3) = (Y.template middleCols<3>(6 * e + 3) * Ot).eval();
    }
    return Y;
  }

  template <class S> typename TimoshenkoBeamKernel::EndFrames<S> endFrames(const Q<S>& q) const {
    return beam_.endFrames<S>(Vec3T<S>(q.template segment<3>(0)), sectionRotation<S>(q, 0), Vec3T<S>(q.template segment<3>(6)),
                              sectionRotation<S>(q, 1));
  }

  template <class S> Eigen::Matrix<S, 12, 12> massMatrix(const Q<S>& q, double = 0.0) const {
    return toNodeAxes<S>(beam_.massMatrix<S>(endFrames<S>(q)));
  }

  template <class S> V<S> force(const Q<S>& q, const V<S>& v, double, const Vec3& gravity) const {
    const Vec3T<S> r1 = q.template segment<3>(0), r2 = q.template segment<3>(6);
    const Mat3T<S> R1 = sectionRotation<S>(q, 0), R2 = sectionRotation<S>(q, 1);
    const V<S> vb = beamVelocities<S>(v);
    return nodeRows(V<S>(beam_.inertialAndGravityForce<S>(r1, R1, r2, R2, vb, gravity) +
                             beam_.elasticForce<S>(r1, R1, r2, R2, vb, stiffness_)));
  }

  /// M a + F in one pass over the beam's Gauss points (element.hpp: fused residual).
  template <class S> V<S> residual(const Q<S>& q, const V<S>& v, const V<S>& a, double, const Vec3& gravity) const {
    return inertialAndGravityForce<S>(q, v, a, gravity) + elasticForce<S>(q, v);
  }

  /// ∂(M a + F)/∂dq = Tᵀ C_b T in closed form (timoshenko_beam.hpp) and M = Tᵀ M_b T beside it.
  Mat12 velocityTangent(const Q<double>& q, const V<double>& v, double, Mat12& M) const;

  /// ∂(M a + F)/∂q (element.hpp) from M and the velocity tangent C (objective_tangent.hpp), as the
  /// beam's (end 2's elastic columns in closed form, corotated_elastic_tangent.hpp, turned into its
  /// node's axes; the inertia's columns of end 2's rotation, section_inertia_coordinate_tangent.hpp).
  Mat12 coordinateTangent(const Q<double>& q, const V<double>& v, const V<double>& a, double, const Vec3& gravity,
                          const Mat12& M, const Mat12& C) const;

  /// The beam's damping forces alone (timoshenko_beam.hpp).
  template <class S> V<S> dampingForce(const Q<S>& q, const V<S>& v) const {
    return nodeRows(V<S>(beam_.dampingForce<S>(q.template segment<3>(0), sectionRotation<S>(q, 0), q.template segment<3>(6),
                                                   sectionRotation<S>(q, 1), beamVelocities<S>(v), stiffness_)));
  }

  /// The beam's section forces in its own co-rotated frame (timoshenko_beam.hpp).
  Eigen::Matrix<double, 12, 1> sectionForces(const Q<double>& q, const V<double>& v, const V<double>& a, const Vec3& gravity) const;

  double kineticEnergy(const Q<double>& q, const V<double>& v, double = 0.0) const;

  /// Gravity potential + strain energy ½ dᵀ K d.
  double potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const;

 private:
  /// Tᵀ (M_b T a + F_ine,b + F_g,b): the inertial and gravity forces, M a among them.
  template <class S> V<S> inertialAndGravityForce(const Q<S>& q, const V<S>& v, const V<S>& a, const Vec3& gravity) const {
    const V<S> ab = beamVelocities<S>(a);
    return nodeRows(V<S>(beam_.inertialAndGravityForce<S>(q.template segment<3>(0), sectionRotation<S>(q, 0),
                                                              q.template segment<3>(6), sectionRotation<S>(q, 1),
                                                              beamVelocities<S>(v), gravity, &ab)));
  }

  /// Tᵀ F_el,b: the elastic and damping forces.
  template <class S> V<S> elasticForce(const Q<S>& q, const V<S>& v) const {
    return nodeRows(V<S>(beam_.elasticForce<S>(q.template segment<3>(0), sectionRotation<S>(q, 0), q.template segment<3>(6),
                                                   sectionRotation<S>(q, 1), beamVelocities<S>(v), stiffness_)));
  }

  TimoshenkoBeamKernel beam_;
  std::array<Mat3, 2> offset_;
  Mat12 stiffness_;
};

}  // namespace cranesim
