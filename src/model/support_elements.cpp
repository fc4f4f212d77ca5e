#include "cranesim/model/support_elements.hpp"

#include <algorithm>
#include <limits>

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/forward_tangents.hpp"

namespace cranesim {
namespace {

/// Where a point of the body is and how fast it moves.
struct PointState {
  Vec3 at, moving;
};

PointState pointState(const Eigen::Matrix<double, 6, 1>& q, const Eigen::Matrix<double, 6, 1>& v, const Mat3& R, const Vec3& p) {
  return {q.head<3>() + R * p, v.head<3>() + R * Vec3(v.tail<3>()).cross(p)};
}

/// The bed's vertical force on the point.
double verticalForce(const PointState& s, const SupportBed& bed) {
  return penaltyForce<double>(bed.level - bed.up.dot(s.at), -bed.up.dot(s.moving), bed.law);
}

}  // namespace

SupportElement::SupportElement(std::vector<SupportPoint> points, int node, std::vector<int> q_indices, std::vector<int> v_indices)
    : ContactElement({node}, std::move(q_indices), std::move(v_indices)), points_(std::move(points)) {}

template <class S>
Eigen::Matrix<S, 6, 1> SupportElement::generalizedForce(const Eigen::Matrix<S, 6, 1>& q, const Eigen::Matrix<S, 6, 1>& v) const {
  const Mat3T<S> R = rotationMatrix<S>(q.template tail<3>());
  Eigen::Matrix<S, 6, 1> Q = Eigen::Matrix<S, 6, 1>::Zero();
  for (const SupportPoint& s : points_) {
    const SupportBed& bed = s.bed;
    const Vec3T<S> p = s.point.cast<S>(), up = bed.up.cast<S>();
    const Vec3T<S> at = q.template head<3>() + R * p;
    const Vec3T<S> moving = v.template head<3>() + R * (v.template tail<3>().cross(p));
    const S rising = up.dot(moving);
    const S normal = penaltyForce<S>(S(bed.level) - up.dot(at), -rising, bed.law);
    const Vec3T<S> F = up * normal;
    Q.template head<3>() += F;
    Q.template tail<3>() += p.cross(R.transpose() * F);
  }
  return Q;
}

std::vector<double> SupportElement::pointForces(const ElementInput& in) const {
  const Local ql = gather(in.q, coordinateIndices()), vl = gather(in.v, velocityIndices());
  const Eigen::Matrix<double, 6, 1> q = ql.head<6>(), v = vl.head<6>();
  const Mat3 R = rotationMatrix<double>(Vec3(q.tail<3>()));
  std::vector<double> out;
  for (const SupportPoint& s : points_) out.push_back(verticalForce(pointState(q, v, R, s.point), s.bed));
  return out;
}

std::vector<Vec3> SupportElement::pointPositions(const ElementInput& in) const {
  const Local ql = gather(in.q, coordinateIndices());
  const Mat3 R = rotationMatrix<double>(Vec3(ql.segment<3>(3)));
  std::vector<Vec3> out;
  for (const SupportPoint& s : points_) out.push_back(Vec3(ql.head<3>()) + R * s.point);
  return out;
}

void SupportElement::force(const Local& q, const Local& v, double* Q) const {
  Eigen::Map<Eigen::Matrix<double, 6, 1>> out(Q);
  out = generalizedForce<double>(q.head<6>(), v.head<6>());
}

void SupportElement::tangents(const Local& q, const Local& v, double* Qq, double* Qv) const {
  forwardTangents<6>(Eigen::Matrix<double, 6, 1>(q.head<6>()), Eigen::Matrix<double, 6, 1>(v.head<6>()),
                     [&](const auto& qd, const auto& vd) { return generalizedForce(qd, vd); }, Qq, Qv);
}

double SupportElement::closureAt(const Local& q) const {
  const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(3)));
  double deepest = -std::numeric_limits<double>::infinity();
  for (const SupportPoint& s : points_) deepest = std::max(deepest, s.bed.level - s.bed.up.dot(Vec3(q.head<3>()) + R * s.point));
  return deepest;
}

double SupportElement::energy(const Local& q) const {
  const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(3)));
  double sum = 0.0;
  for (const SupportPoint& s : points_) {
    const SupportBed& bed = s.bed;
    const Vec3 at = Vec3(q.head<3>()) + R * s.point;
    sum += penaltyEnergy(bed.level - bed.up.dot(at), bed.law);
  }
  return sum;
}

double SupportElement::normalForceAt(const Local& q, const Local& v) const {
  const Eigen::Matrix<double, 6, 1> q6 = q.head<6>(), v6 = v.head<6>();
  const Mat3 R = rotationMatrix<double>(Vec3(q6.tail<3>()));
  double sum = 0.0;
  for (const SupportPoint& s : points_) sum += verticalForce(pointState(q6, v6, R, s.point), s.bed);
  return sum;
}

}  // namespace cranesim
