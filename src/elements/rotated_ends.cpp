// The rotated-ends beam's members that are not templates (rotated_ends.hpp), compiled here once.
#include "cranesim/elements/rotated_ends.hpp"

namespace cranesim {

auto RotatedEndsBeamKernel::velocityTangent(const Q<double>& q, const V<double>& v, double, Mat12& M) const -> Mat12 {
  Mat12 Mb;
  const Mat12 Cb = beam_.velocityTangent(q.segment<3>(0), sectionRotation<double>(q, 0), q.segment<3>(6),
                                         sectionRotation<double>(q, 1), beamVelocities<double>(v), stiffness_, Mb);
  M = toNodeAxes<double>(Mb);
  return toNodeAxes<double>(Cb);
}

auto RotatedEndsBeamKernel::coordinateTangent(const Q<double>& q, const V<double>& v, const V<double>& a, double, const Vec3& gravity,
                                              const Mat12& M, const Mat12& C) const -> Mat12 {
  using D = SectionInertiaCoordinateTangent::D;
  const V<double> vb = beamVelocities<double>(v);
  const V<D> ab = beamVelocities<double>(a).cast<D>();
  const Mat3 R1 = sectionRotation<double>(q, 0);
  SectionInertiaCoordinateTangent inertia(R1.cast<D>(), Mat3T<D>(rotationMatrix<D>(seededSecondRotation(q)) * offset_[1].cast<D>()),
                                          vb.cast<D>(), &ab, gravity, beam_.length);
  beam_.addMassPoints(inertia);
  CoRotatedElasticTangent elastic = coRotatedElasticTangent(beam_.length, beam_.damping, q.segment<3>(0), R1, q.segment<3>(6),
                                                            sectionRotation<double>(q, 1), vb, stiffness_);
  elastic.alongRotationVector(q.segment<3>(9), offset_[1]);
  return objectiveCoordinateTangent({q, v, a, gravity, M, C}, nodeRows(elastic.force),
                                    nodeRows(elastic.second_end), nodeRows(inertia.forces()));
}

Eigen::Matrix<double, 12, 1> RotatedEndsBeamKernel::sectionForces(const Q<double>& q, const V<double>& v, const V<double>& a, const Vec3& gravity) const {
  return beam_.sectionForces(q.segment<3>(0), sectionRotation<double>(q, 0), q.segment<3>(6), sectionRotation<double>(q, 1),
                             beamVelocities<double>(v), beamVelocities<double>(a), gravity, stiffness_);
}

double RotatedEndsBeamKernel::kineticEnergy(const Q<double>& q, const V<double>& v, double) const {
  return 0.5 * v.dot(massMatrix<double>(q) * v);
}

double RotatedEndsBeamKernel::potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const {
  const Vec3 r1 = q.segment<3>(0), r2 = q.segment<3>(6);
  const auto d = beam_.coRotate<double>(r1, sectionRotation<double>(q, 0), r2, sectionRotation<double>(q, 1)).d;
  return beam_.gravityPotential(endFrames<double>(q), gravity) + 0.5 * d.dot(stiffness_ * d);
}

}  // namespace cranesim
