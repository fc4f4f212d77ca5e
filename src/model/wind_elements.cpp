#include "cranesim/model/wind_elements.hpp"

#include "cranesim/elements/wind_drag.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {
namespace {

constexpr int kMaxLocal = 14;

template <int N> using D = Dual<double, N>;

/// ∂Q/∂q of the N generalized forces `force(q)` of N coordinates, by forward AD (column-major).
template <int N, class Coordinates, class Force> void forwardJacobian(const Coordinates& q, const Force& force, double* Qq) {
  Eigen::Matrix<D<N>, N, 1> qd;
  for (int k = 0; k < N; ++k) qd(k) = seeded<double, N>(q(k), k);
  const Eigen::Matrix<D<N>, N, 1> Qd = force(qd);
  Eigen::Map<Eigen::Matrix<double, N, N>> dq(Qq);
  for (int i = 0; i < N; ++i) dq.row(i) = Qd(i).derivatives().transpose();
}

/// The wind's forces on a cylinder of drag coefficient `coefficient` (½ ρ c d) along the chord
/// r1 → r2 moving at v1, v2 at its ends (linearly between), lumped on the ends with the linear
/// weights: [f₁, f₂] (LineWindElement).
template <class S>
Eigen::Matrix<S, 6, 1> cylinderEndForces(const WindField& wind, double coefficient, const GaussRule& rule, const Vec3T<S>& r1,
                                         const Vec3T<S>& r2, const Vec3T<S>& v1, const Vec3T<S>& v2, double t) {
  using std::sqrt;
  const Vec3T<S> chord = r2 - r1;
  const S length = sqrt(chord.squaredNorm());
  const Vec3T<S> axis = chord / length;
  Eigen::Matrix<S, 6, 1> Q = Eigen::Matrix<S, 6, 1>::Zero();
  for (int g = 0; g < rule.points; ++g) {
    const double xi = rule.xi[g];
    const Vec3T<S> at = r1 + chord * xi;
    const Vec3T<S> moving = v1 * (1.0 - xi) + v2 * xi;
    const Vec3T<S> f = quadraticDrag<S>(normalPart<S>(Vec3T<S>(wind.velocity<S>(at, t) - moving), axis), coefficient) *
                       (length * rule.weight[g]);
    Q.template head<3>() += f * (1.0 - xi);
    Q.template tail<3>() += f * xi;
  }
  return Q;
}

}  // namespace

WindElement::WindElement(std::shared_ptr<const WindField> wind, std::vector<int> nodes, std::vector<int> q_indices,
                         std::vector<int> v_indices)
    : wind_(std::move(wind)), nodes_(std::move(nodes)), q_(std::move(q_indices)), v_(std::move(v_indices)) {}

WindElement::Local WindElement::gather(const double* x, const std::vector<int>& at) const {
  Local out(static_cast<Eigen::Index>(at.size()));
  for (std::size_t k = 0; k < at.size(); ++k) out(static_cast<Eigen::Index>(k)) = x[at[k]];
  return out;
}

void WindElement::residual(const ElementInput& in, double* r) const {
  force(gather(in.q, q_), gather(in.v, v_), in.t, r);
  for (int i = 0; i < size(); ++i) r[i] *= -in.load_factor;
}

void WindElement::jacobian(const ElementInput& in, double cj, double* J) const {
  (void)cj;  // no mass
  const int n = size();
  double Qq[kMaxLocal * kMaxLocal], Qv[kMaxLocal * kMaxLocal];
  tangents(gather(in.q, q_), gather(in.v, v_), in.t, Qq, Qv);
  for (int i = 0; i < n * n; ++i) J[i] = -in.load_factor * Qq[i], J[n * n + i] = -in.load_factor * Qv[i];
}

void WindElement::coordinateJacobian(const ElementInput& in, double* J) const {
  const int n = size();
  double Qv[kMaxLocal * kMaxLocal];
  tangents(gather(in.q, q_), gather(in.v, v_), in.t, J, Qv);
  for (int i = 0; i < n * n; ++i) J[i] *= -in.load_factor;
}

void WindElement::mass(const ElementInput&, double* M) const { std::fill(M, M + size() * size(), 0.0); }

double WindElement::power(const ElementInput& in) const {
  const Local v = gather(in.v, v_);
  double Q[kMaxLocal];
  force(gather(in.q, q_), v, in.t, Q);
  double p = 0.0;
  for (int i = 0; i < size(); ++i) p += Q[i] * v(i);
  return in.load_factor * p;
}

BodyWindElement::BodyWindElement(std::shared_ptr<const WindField> wind, double drag_area, const Vec3& point, int node,
                                 std::vector<int> q_indices, std::vector<int> v_indices)
    : WindElement(std::move(wind), {node}, std::move(q_indices), std::move(v_indices)),
      coefficient_(0.5 * wind_->spec().air_density * drag_area), point_(point) {}

template <class S>
Eigen::Matrix<S, 6, 1> BodyWindElement::generalizedForce(const Eigen::Matrix<S, 6, 1>& q, const Eigen::Matrix<double, 6, 1>& v,
                                                         double t) const {
  const Mat3T<S> R = rotationMatrix<S>(q.template tail<3>());
  const Vec3T<S> p = point_.cast<S>();
  const Vec3T<S> at = q.template head<3>() + R * p;
  const Vec3T<S> moving = v.head<3>().cast<S>() + R * (v.tail<3>().cast<S>().cross(p));
  const Vec3T<S> F = quadraticDrag<S>(wind_->velocity<S>(at, t) - moving, coefficient_);
  Eigen::Matrix<S, 6, 1> Q;
  Q << F, p.cross(R.transpose() * F);
  return Q;
}

void BodyWindElement::force(const Local& q, const Local& v, double t, double* Q) const {
  Eigen::Map<Eigen::Matrix<double, 6, 1>> out(Q);
  out = generalizedForce<double>(q.head<6>(), v.head<6>(), t);
}

Vec3 BodyWindElement::resultantForce(const ElementInput& in) const {
  double Q[6];
  force(gather(in.q, coordinateIndices()), gather(in.v, velocityIndices()), in.t, Q);
  return in.load_factor * Vec3(Q[0], Q[1], Q[2]);
}

/// ∂Q/∂dq: with u = w − ṙ − R (ω × p) and D = ½ρcA ∂(|u|u)/∂u, ∂F/∂ṙ = −D, ∂F/∂ω = D R p̃;
/// the moment p̃ Rᵀ F follows.
void BodyWindElement::tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const {
  forwardJacobian<6>(q, [&](const auto& qd) { return generalizedForce<D<6>>(qd, v.head<6>(), t); }, Qq);
  Eigen::Map<Eigen::Matrix<double, 6, 6>> dv(Qv);

  const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(3)));
  const Vec3 moving = v.head<3>() + R * (Vec3(v.segment<3>(3)).cross(point_));
  const Mat3 Dm = coefficient_ * quadraticDragTangent(wind_->velocity<double>(Vec3(q.head<3>() + R * point_), t) - moving);
  const Mat3 P = skew<double>(point_);
  const Mat3 F_r = -Dm, F_w = Dm * R * P;
  dv.block<3, 3>(0, 0) = F_r;
  dv.block<3, 3>(0, 3) = F_w;
  dv.block<3, 3>(3, 0) = P * R.transpose() * F_r;
  dv.block<3, 3>(3, 3) = P * R.transpose() * F_w;
}

LineWindElement::LineWindElement(std::shared_ptr<const WindField> wind, double drag_diameter, int points, int node1,
                                 int node2, int second_node_offset, std::vector<int> q_indices, std::vector<int> v_indices)
    : WindElement(std::move(wind), {node1, node2}, std::move(q_indices), std::move(v_indices)),
      coefficient_(0.5 * wind_->spec().air_density * drag_diameter), rule_(gaussLegendre(points)),
      second_(second_node_offset) {}

template <class S>
Eigen::Matrix<S, 6, 1> LineWindElement::endForces(const Vec3T<S>& r1, const Vec3T<S>& r2, const Vec3& v1, const Vec3& v2,
                                                  double t) const {
  return cylinderEndForces<S>(*wind_, coefficient_, rule_, r1, r2, v1.cast<S>(), v2.cast<S>(), t);
}

void LineWindElement::force(const Local& q, const Local& v, double t, double* Q) const {
  std::fill(Q, Q + size(), 0.0);
  const Eigen::Matrix<double, 6, 1> ends =
      endForces<double>(q.head<3>(), q.segment<3>(second_), v.head<3>(), v.segment<3>(second_), t);
  for (int k = 0; k < 3; ++k) Q[k] = ends(k), Q[second_ + k] = ends(3 + k);
}

Vec3 LineWindElement::resultantForce(const ElementInput& in) const {
  double Q[kMaxLocal];
  force(gather(in.q, coordinateIndices()), gather(in.v, velocityIndices()), in.t, Q);
  return in.load_factor * Vec3(Q[0] + Q[second_], Q[1] + Q[second_ + 1], Q[2] + Q[second_ + 2]);
}

/// ∂Q/∂q by forward AD in the six position directions; ∂Q/∂dq: with u⊥ = (I − e eᵀ)(w − ṙ(ξ)),
/// ṙ(ξ) = N₁ ṙ₁ + N₂ ṙ₂, each Gauss point adds −½ρcd ℓ w_g N_a N_b ∂(|u⊥|u⊥)/∂u⊥ (I − e eᵀ).
void LineWindElement::tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const {
  const int n = size();
  std::fill(Qq, Qq + n * n, 0.0);
  std::fill(Qv, Qv + n * n, 0.0);
  Vec3T<D<6>> r1, r2;
  for (int k = 0; k < 3; ++k) r1(k) = seeded<double, 6>(q(k), k), r2(k) = seeded<double, 6>(q(second_ + k), 3 + k);
  const Eigen::Matrix<D<6>, 6, 1> ends = endForces<D<6>>(r1, r2, v.head<3>(), v.segment<3>(second_), t);
  const int offset[2] = {0, second_};
  Eigen::Map<MatX> dq(Qq, n, n), dv(Qv, n, n);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) dq(offset[i / 3] + i % 3, offset[j / 3] + j % 3) = ends(i).derivatives()(j);

  const Vec3 a = q.head<3>(), b = q.segment<3>(second_), va = v.head<3>(), vb = v.segment<3>(second_);
  const double length = (b - a).norm();
  const Vec3 axis = (b - a) / length;
  const Mat3 across = Mat3::Identity() - axis * axis.transpose();
  for (int g = 0; g < rule_.points; ++g) {
    const double xi = rule_.xi[g], N[2] = {1.0 - xi, xi};
    const Vec3 u = across * (wind_->velocity<double>(Vec3(a + xi * (b - a)), t) - (N[0] * va + N[1] * vb));
    const Mat3 block = -coefficient_ * length * rule_.weight[g] * quadraticDragTangent(u) * across;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) dv.block<3, 3>(offset[i], offset[j]) += N[i] * N[j] * block;
  }
}

LatticeWindElement::LatticeWindElement(std::shared_ptr<const WindField> wind, std::vector<Vec3> points,
                                       std::vector<WindTube> tubes, double length, int gauss_points, int section1,
                                       int section2, std::vector<int> q_indices, std::vector<int> v_indices)
    : WindElement(std::move(wind), {section1, section2}, std::move(q_indices), std::move(v_indices)),
      points_(std::move(points)), tubes_(std::move(tubes)), length_(length), rule_(gaussLegendre(gauss_points)),
      half_density_(0.5 * wind_->spec().air_density) {}

/// Per node: its place, velocity and wind, then the wind's force on it; per section the sums of
/// the nodes' forces and moments (p × Rᵀ F = Rᵀ (R p × F)).
template <class S>
Eigen::Matrix<S, 12, 1> LatticeWindElement::generalizedForce(const Eigen::Matrix<S, 12, 1>& q, const Q12& v, double t) const {
  using std::sqrt;
  struct NodeState {
    Vec3T<S> arm1, arm2, place, velocity, wind, force;
  };
  thread_local std::vector<NodeState> nodes;
  nodes.resize(points_.size());
  const Mat3T<S> R1 = rotationMatrix<S>(q.template segment<3>(3)), R2 = rotationMatrix<S>(q.template segment<3>(9));
  const Vec3T<S> w1 = R1 * v.segment<3>(3).cast<S>(), w2 = R2 * v.segment<3>(9).cast<S>();  // inertial ω
  for (std::size_t n = 0; n < points_.size(); ++n) {
    const double s = points_[n].x() / length_;
    NodeState& node = nodes[n];
    node.arm1 = R1 * points_[n].cast<S>();
    node.arm2 = R2 * (points_[n] - Vec3(length_, 0.0, 0.0)).cast<S>();
    node.place = (q.template head<3>() + node.arm1) * S(1.0 - s) + (q.template segment<3>(6) + node.arm2) * S(s);
    node.velocity = (v.head<3>().cast<S>() + w1.cross(node.arm1)) * S(1.0 - s) + (v.segment<3>(6).cast<S>() + w2.cross(node.arm2)) * S(s);
    node.wind = wind_->velocity<S>(node.place, t);
    node.force.setZero();
  }
  for (const WindTube& tube : tubes_) {
    NodeState &a = nodes[tube.from], &b = nodes[tube.to];
    const Vec3T<S> chord = b.place - a.place;
    const S length = sqrt(chord.squaredNorm());
    const Vec3T<S> axis = chord / length;
    for (int g = 0; g < rule_.points; ++g) {
      const double xi = rule_.xi[g];
      const Vec3T<S> relative = (a.wind - a.velocity) * S(1.0 - xi) + (b.wind - b.velocity) * S(xi);
      const Vec3T<S> f = quadraticDrag<S>(normalPart<S>(relative, axis), half_density_ * tube.drag_diameter) *
                         (length * rule_.weight[g]);
      a.force += f * (1.0 - xi);
      b.force += f * xi;
    }
  }
  Vec3T<S> F1 = Vec3T<S>::Zero(), F2 = Vec3T<S>::Zero(), M1 = Vec3T<S>::Zero(), M2 = Vec3T<S>::Zero();
  for (std::size_t n = 0; n < points_.size(); ++n) {
    const double s = points_[n].x() / length_;
    const NodeState& node = nodes[n];
    F1 += node.force * S(1.0 - s);
    M1 += node.arm1.cross(node.force) * S(1.0 - s);
    F2 += node.force * S(s);
    M2 += node.arm2.cross(node.force) * S(s);
  }
  Eigen::Matrix<S, 12, 1> Q;
  Q << F1, R1.transpose() * M1, F2, R2.transpose() * M2;
  return Q;
}

Eigen::Matrix<double, 3, 12> LatticeWindElement::nodeVelocityMap(const Mat3& R1, const Mat3& R2, int n) const {
  const double s = points_[n].x() / length_;
  Eigen::Matrix<double, 3, 12> A;
  A.block<3, 3>(0, 0) = (1.0 - s) * Mat3::Identity();
  A.block<3, 3>(0, 3) = (s - 1.0) * R1 * skew<double>(points_[n]);
  A.block<3, 3>(0, 6) = s * Mat3::Identity();
  A.block<3, 3>(0, 9) = -s * R2 * skew<double>(Vec3(points_[n] - Vec3(length_, 0.0, 0.0)));
  return A;
}

void LatticeWindElement::force(const Local& q, const Local& v, double t, double* Q) const {
  Eigen::Map<Q12> out(Q);
  out = generalizedForce<double>(q.head<12>(), v.head<12>(), t);
}

Vec3 LatticeWindElement::resultantForce(const ElementInput& in) const {
  double Q[12];
  force(gather(in.q, coordinateIndices()), gather(in.v, velocityIndices()), in.t, Q);
  return in.load_factor * Vec3(Q[0] + Q[6], Q[1] + Q[7], Q[2] + Q[8]);
}

/// ∂Q/∂q by forward AD; ∂Q/∂dq: node n moves at A_n dq (nodeVelocityMap) and passes A_nᵀ F_n on,
/// so a tube's Gauss point adds −½ρcd ℓ w_g N_i N_j A_iᵀ ∂(|u⊥|u⊥)/∂u⊥ (I − e eᵀ) A_j.
void LatticeWindElement::tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const {
  forwardJacobian<12>(q, [&](const auto& qd) { return generalizedForce<D<12>>(qd, v.head<12>(), t); }, Qq);
  Eigen::Map<Eigen::Matrix<double, 12, 12>> dv(Qv);

  const Mat3 R1 = rotationMatrix<double>(Vec3(q.segment<3>(3))), R2 = rotationMatrix<double>(Vec3(q.segment<3>(9)));
  const Q12 dqv = v.head<12>();
  const auto place = [&](int n) {
    const double s = points_[n].x() / length_;
    return Vec3((1.0 - s) * (q.head<3>() + R1 * points_[n]) + s * (q.segment<3>(6) + R2 * (points_[n] - Vec3(length_, 0.0, 0.0))));
  };
  dv.setZero();
  for (const WindTube& tube : tubes_) {
    const Eigen::Matrix<double, 3, 12> A[2] = {nodeVelocityMap(R1, R2, tube.from), nodeVelocityMap(R1, R2, tube.to)};
    const Vec3 a = place(tube.from), b = place(tube.to), chord = b - a;
    const Vec3 ua = wind_->velocity<double>(a, t) - A[0] * dqv, ub = wind_->velocity<double>(b, t) - A[1] * dqv;
    const double length = chord.norm();
    const Vec3 axis = chord / length;
    const Mat3 across = Mat3::Identity() - axis * axis.transpose();
    for (int g = 0; g < rule_.points; ++g) {
      const double xi = rule_.xi[g], N[2] = {1.0 - xi, xi};
      const Vec3 u = across * (N[0] * ua + N[1] * ub);
      const Mat3 block = -half_density_ * tube.drag_diameter * length * rule_.weight[g] * quadraticDragTangent(u) * across;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) dv += (N[i] * N[j]) * A[i].transpose() * block * A[j];
    }
  }
}

PathLineWindElement::PathLineWindElement(std::shared_ptr<const WindField> wind, double drag_diameter, int points, RopePath ends,
                                         std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices)
    : WindElement(std::move(wind), std::move(nodes), std::move(q_indices), std::move(v_indices)),
      coefficient_(0.5 * wind_->spec().air_density * drag_diameter), rule_(gaussLegendre(points)), ends_(std::move(ends)) {}

template <class S>
Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1> PathLineWindElement::generalizedForce(
    const Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1>& q,
    const Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1>& v, double t, Vec3T<S>* resultant) const {
  std::array<Vec3T<S>, 2> x, xd;
  RopePath::Rotations<S> R;
  ends_.place<S>(q, v, x, xd, R);
  const Eigen::Matrix<S, 6, 1> f = cylinderEndForces<S>(*wind_, coefficient_, rule_, x[0], x[1], xd[0], xd[1], t);
  const std::array<Vec3T<S>, 2> on_ends = {Vec3T<S>(f.template head<3>()), Vec3T<S>(f.template tail<3>())};
  if (resultant) *resultant = on_ends[0] + on_ends[1];
  Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1> Q = Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1>::Zero(size());
  ends_.gather(R, on_ends, Q);
  return Q;
}

void PathLineWindElement::force(const Local& q, const Local& v, double t, double* Q) const {
  const Local out = generalizedForce<double>(q, v, t);
  std::copy(out.data(), out.data() + size(), Q);
}

Vec3 PathLineWindElement::resultantForce(const ElementInput& in) const {
  Vec3 resultant;
  generalizedForce<double>(gather(in.q, coordinateIndices()), gather(in.v, velocityIndices()), in.t, &resultant);
  return in.load_factor * resultant;
}

/// ∂Q/∂q and ∂Q/∂dq by forward AD in every local direction (at most two nodes of 7).
void PathLineWindElement::tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const {
  using Seeded = Eigen::Matrix<D<kMaxLocal>, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1>;
  const int n = size();
  Seeded qd = q.cast<D<kMaxLocal>>(), vd = v.cast<D<kMaxLocal>>();
  for (int k = 0; k < n; ++k) qd(k) = seeded<double, kMaxLocal>(q(k), k);
  const Seeded by_q = generalizedForce<D<kMaxLocal>>(qd, vd, t);
  qd = q.cast<D<kMaxLocal>>();
  for (int k = 0; k < n; ++k) vd(k) = seeded<double, kMaxLocal>(v(k), k);
  const Seeded by_v = generalizedForce<D<kMaxLocal>>(qd, vd, t);
  Eigen::Map<MatX> dq(Qq, n, n), dv(Qv, n, n);
  for (int i = 0; i < n; ++i) {
    dq.row(i) = by_q(i).derivatives().head(n).transpose();
    dv.row(i) = by_v(i).derivatives().head(n).transpose();
  }
}

}  // namespace cranesim
