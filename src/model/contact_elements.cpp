#include "cranesim/model/contact_elements.hpp"

#include <cmath>

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/forward_tangents.hpp"

namespace cranesim {

ContactElement::ContactElement(std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices)
    : nodes_(std::move(nodes)), q_(std::move(q_indices)), v_(std::move(v_indices)) {}

ContactElement::Local ContactElement::gather(const double* x, const std::vector<int>& at) const {
  Local out(static_cast<Eigen::Index>(at.size()));
  for (std::size_t k = 0; k < at.size(); ++k) out(static_cast<Eigen::Index>(k)) = x[at[k]];
  return out;
}

void ContactElement::residual(const ElementInput& in, double* r) const {
  force(gather(in.q, q_), gather(in.v, v_), r);
  for (int i = 0; i < size(); ++i) r[i] = -r[i];
}

void ContactElement::jacobian(const ElementInput& in, double, double* J) const {
  const int n = size();
  tangents(gather(in.q, q_), gather(in.v, v_), J, J + n * n);
  for (int i = 0; i < 2 * n * n; ++i) J[i] = -J[i];
}

void ContactElement::coordinateJacobian(const ElementInput& in, double* J) const {
  const int n = size();
  double Qv[12 * 12];
  tangents(gather(in.q, q_), gather(in.v, v_), J, Qv);
  for (int i = 0; i < n * n; ++i) J[i] = -J[i];
}

void ContactElement::mass(const ElementInput&, double* M) const { std::fill(M, M + size() * size(), 0.0); }

double ContactElement::dissipatedPower(const ElementInput& in) const {
  const Local q = gather(in.q, q_), v = gather(in.v, v_);
  double moving[12] = {}, resting[12] = {};  // force() fills the first size()
  force(q, v, moving);
  force(q, Local::Zero(v.size()), resting);
  double p = 0.0;
  for (int i = 0; i < size(); ++i) p += (resting[i] - moving[i]) * v(i);
  return p;
}

GroundContactElement::GroundContactElement(const GroundSurface& ground, double radius, const Vec3& point, bool rotates, int node,
                                           std::vector<int> q_indices, std::vector<int> v_indices)
    : ContactElement({node}, std::move(q_indices), std::move(v_indices)), ground_(ground), radius_(radius), point_(point),
      rotates_(rotates) {}

Eigen::Matrix<double, 6, 1> GroundContactElement::padded(const Local& x) const {
  Eigen::Matrix<double, 6, 1> out = Eigen::Matrix<double, 6, 1>::Zero();
  out.head(x.size()) = x;
  return out;
}

template <class S> Vec3T<S> GroundContactElement::contactPoint(const Eigen::Matrix<S, 6, 1>& q) const {
  if (!rotates_) return q.template head<3>();
  return q.template head<3>() + rotationMatrix<S>(q.template tail<3>()) * point_.cast<S>();
}

template <class S>
Eigen::Matrix<S, 6, 1> GroundContactElement::generalizedForce(const Eigen::Matrix<S, 6, 1>& q, const Eigen::Matrix<S, 6, 1>& v) const {
  using std::sqrt;
  const Mat3T<S> R = rotates_ ? rotationMatrix<S>(q.template tail<3>()) : Mat3T<S>::Identity();
  const Vec3T<S> p = point_.cast<S>();
  const Vec3T<S> at = q.template head<3>() + R * p;
  const Vec3T<S> moving = v.template head<3>() + R * (v.template tail<3>().cross(p));
  const Vec3T<S> up = ground_.up.cast<S>();
  const S along = up.dot(moving);
  const S normal = penaltyForce<S>(S(ground_.height + radius_) - up.dot(at), -along, ground_.law);
  const Vec3T<S> sliding = moving - up * along;
  const S slip = sqrt(sliding.squaredNorm() + S(ground_.friction_speed * ground_.friction_speed));
  const Vec3T<S> F = up * normal - sliding * (normal * ground_.friction / slip);
  Eigen::Matrix<S, 6, 1> Q;
  Q << F, p.cross(R.transpose() * F);
  return Q;
}

void GroundContactElement::force(const Local& q, const Local& v, double* Q) const {
  const Eigen::Matrix<double, 6, 1> all = generalizedForce<double>(padded(q), padded(v));
  for (int i = 0; i < size(); ++i) Q[i] = all(i);
}

void GroundContactElement::tangents(const Local& q, const Local& v, double* Qq, double* Qv) const {
  double all_q[36], all_v[36];
  forwardTangents<6>(padded(q), padded(v), [&](const auto& qd, const auto& vd) { return generalizedForce(qd, vd); }, all_q, all_v);
  const int n = size();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) Qq[i + n * j] = all_q[i + 6 * j], Qv[i + n * j] = all_v[i + 6 * j];
}

double GroundContactElement::closureAt(const Local& q) const {
  return ground_.height + radius_ - ground_.up.dot(contactPoint<double>(padded(q)));
}

double GroundContactElement::energy(const Local& q) const { return penaltyEnergy(closureAt(q), ground_.law); }

double GroundContactElement::normalForceAt(const Local& q, const Local& v) const {
  return generalizedForce<double>(padded(q), padded(v)).head<3>().dot(ground_.up);
}

BackstopElement::BackstopElement(const Hinge& hinge, const PenaltyLaw& law, int slewing, int boom, std::vector<int> q_indices,
                                 std::vector<int> v_indices)
    : ContactElement({slewing, boom}, std::move(q_indices), std::move(v_indices)), hinge_(hinge), law_(law) {}

template <class S> S BackstopElement::turnOf(const Eigen::Matrix<S, 12, 1>& q) const {
  using std::atan2;
  const Mat3T<S> Rs = rotationMatrix<S>(q.template segment<3>(3)), Rb = rotationMatrix<S>(q.template segment<3>(9));
  const Vec3T<S> a = Rs * hinge_.axis.cast<S>(), u = Rs * hinge_.drawn.cast<S>();
  const Vec3T<S> d = q.template segment<3>(6) + Rb * hinge_.point.cast<S>() - q.template head<3>() - Rs * hinge_.foot.cast<S>();
  return atan2(a.dot(u.cross(d)), u.dot(d));
}

template <class S>
Eigen::Matrix<S, 12, 1> BackstopElement::generalizedForce(const Eigen::Matrix<S, 12, 1>& q, const Eigen::Matrix<S, 12, 1>& v) const {
  const Mat3T<S> Rs = rotationMatrix<S>(q.template segment<3>(3)), Rb = rotationMatrix<S>(q.template segment<3>(9));
  const Vec3T<S> a = Rs * hinge_.axis.cast<S>();
  const Vec3T<S> B = q.template segment<3>(6) + Rb * hinge_.point.cast<S>();
  const Vec3T<S> d = B - q.template head<3>() - Rs * hinge_.foot.cast<S>();
  const Vec3T<S> across = d - a * a.dot(d);
  const S reach2 = across.squaredNorm();
  // θ̇: B's velocity relative to the slewing body, turning about a, less nothing of the body's own
  // turn (u and a turn with it).
  const Vec3T<S> ws = Rs * v.template segment<3>(3), wb = Rb * v.template segment<3>(9);
  const Vec3T<S> B_dot = v.template segment<3>(6) + wb.cross(Rb * hinge_.point.cast<S>());
  const Vec3T<S> F_dot = v.template head<3>() + ws.cross(Rs * hinge_.foot.cast<S>());
  const Vec3T<S> relative = B_dot - F_dot - ws.cross(d);
  const S turning = a.dot(across.cross(relative)) / reach2;
  const S moment = penaltyForce<S>(turnOf(q) * hinge_.sense - hinge_.engaged, turning * hinge_.sense, law_);
  const Vec3T<S> on_boom = a.cross(across) * (moment * -hinge_.sense / reach2);
  Eigen::Matrix<S, 12, 1> Q;
  Q.template segment<3>(0) = -on_boom;
  Q.template segment<3>(3) = Rs.transpose() * (B - q.template head<3>()).cross(-on_boom);
  Q.template segment<3>(6) = on_boom;
  Q.template segment<3>(9) = hinge_.point.cast<S>().cross(Rb.transpose() * on_boom);
  return Q;
}

void BackstopElement::force(const Local& q, const Local& v, double* Q) const {
  Eigen::Map<Eigen::Matrix<double, 12, 1>> out(Q);
  out = generalizedForce<double>(q.head<12>(), v.head<12>());
}

void BackstopElement::tangents(const Local& q, const Local& v, double* Qq, double* Qv) const {
  forwardTangents<12>(Eigen::Matrix<double, 12, 1>(q.head<12>()), Eigen::Matrix<double, 12, 1>(v.head<12>()),
                      [&](const auto& qd, const auto& vd) { return generalizedForce(qd, vd); }, Qq, Qv);
}

double BackstopElement::closureAt(const Local& q) const {
  return turnOf<double>(q.head<12>()) * hinge_.sense - hinge_.engaged;
}

double BackstopElement::energy(const Local& q) const { return penaltyEnergy(closureAt(q), law_); }

double BackstopElement::normalForceAt(const Local& q, const Local& v) const {
  const Eigen::Matrix<double, 12, 1> x = q.head<12>();
  const Mat3 Rs = rotationMatrix<double>(Vec3(x.segment<3>(3))), Rb = rotationMatrix<double>(Vec3(x.segment<3>(9)));
  const Vec3 a = Rs * hinge_.axis;
  const Vec3 d = x.segment<3>(6) + Rb * hinge_.point - x.head<3>() - Rs * hinge_.foot;
  return generalizedForce<double>(x, v.head<12>()).segment<3>(6).norm() * (d - a * a.dot(d)).norm();
}

}  // namespace cranesim
