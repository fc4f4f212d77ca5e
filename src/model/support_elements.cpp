#include "cranesim/model/support_elements.hpp"

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/forward_tangents.hpp"

namespace cranesim {

SupportPointElement::SupportPointElement(const SupportBed& bed, const Vec3& point, int node, std::vector<int> q_indices,
                                         std::vector<int> v_indices)
    : ContactElement({node}, std::move(q_indices), std::move(v_indices)), bed_(bed), point_(point) {}

template <class S>
Eigen::Matrix<S, 6, 1> SupportPointElement::generalizedForce(const Eigen::Matrix<S, 6, 1>& q, const Eigen::Matrix<S, 6, 1>& v) const {
  const Mat3T<S> R = rotationMatrix<S>(q.template tail<3>());
  const Vec3T<S> p = point_.cast<S>(), up = bed_.up.cast<S>();
  const Vec3T<S> at = q.template head<3>() + R * p;
  const Vec3T<S> moving = v.template head<3>() + R * (v.template tail<3>().cross(p));
  const S rising = up.dot(moving);
  const S normal = penaltyForce<S>(S(bed_.level) - up.dot(at), -rising, bed_.law);
  const Vec3T<S> shift = at - bed_.anchor.cast<S>();
  const Vec3T<S> F = up * normal - (shift - up * up.dot(shift)) * bed_.shear_stiffness - (moving - up * rising) * bed_.shear_damping;
  Eigen::Matrix<S, 6, 1> Q;
  Q << F, p.cross(R.transpose() * F);
  return Q;
}

Vec3 SupportPointElement::pointAt(const Local& q) const {
  return q.head<3>() + rotationMatrix<double>(Vec3(q.segment<3>(3))) * point_;
}

void SupportPointElement::force(const Local& q, const Local& v, double* Q) const {
  Eigen::Map<Eigen::Matrix<double, 6, 1>> out(Q);
  out = generalizedForce<double>(q.head<6>(), v.head<6>());
}

void SupportPointElement::tangents(const Local& q, const Local& v, double* Qq, double* Qv) const {
  forwardTangents<6>(Eigen::Matrix<double, 6, 1>(q.head<6>()), Eigen::Matrix<double, 6, 1>(v.head<6>()),
                     [&](const auto& qd, const auto& vd) { return generalizedForce(qd, vd); }, Qq, Qv);
}

double SupportPointElement::closureAt(const Local& q) const { return bed_.level - bed_.up.dot(pointAt(q)); }

double SupportPointElement::energy(const Local& q) const {
  const Vec3 shift = pointAt(q) - bed_.anchor;
  const Vec3 across = shift - bed_.up * bed_.up.dot(shift);
  return penaltyEnergy(closureAt(q), bed_.law) + 0.5 * bed_.shear_stiffness * across.squaredNorm();
}

double SupportPointElement::normalForceAt(const Local& q, const Local& v) const {
  const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(3)));
  const Vec3 moving = v.head<3>() + R * (Vec3(v.segment<3>(3)).cross(point_));
  return penaltyForce<double>(closureAt(q), -bed_.up.dot(moving), bed_.law);
}

}  // namespace cranesim
