// The super truss's members that are not templates (super_truss.hpp): compiled here once, so
// that a file including the kernel does not instantiate its tangents.
#include "cranesim/elements/super_truss.hpp"

namespace cranesim {

SuperTrussKernel::SuperTrussKernel(const TrussGeometry& g, int mass_points, double damping) : length(g.length) {
  for (const auto& c : g.chords) {
    ChordModel m;
    for (int e = 0; e < 2; ++e) m.offset[e] = sectionOffset(g, c[e], e);
    const Vec3 chord = m.offset[1] + length * Vec3::UnitX() - m.offset[0];
    m.tangent = chord.normalized();
    m.frame = alignX(m.tangent);
    m.spline.length = chord.norm();
    chords.push_back(m);
  }
  for (int n = 0; n < static_cast<int>(g.nodes.size()); ++n) {
    const TrussNode& t = g.nodes[n];
    NodeModel m;
    m.frame = Mat3::Identity();
    if (t.end_section >= 0) {
      m.section = t.end_section;
      m.offset = sectionOffset(g, n, t.end_section);
    } else {
      if (t.chord < 0 || t.chord >= static_cast<int>(chords.size()))
        throw std::invalid_argument("super truss: an internal node does not lie on a main beam");
      const ChordModel& c = chords[t.chord];
      m.chord = t.chord;
      m.xi = t.xi;
      m.frame = c.frame;
      const Vec3 on_chord = c.offset[0] + t.xi * c.spline.length * c.tangent;
      if ((on_chord - t.position).norm() > 1e-9 * (1.0 + length))
        throw std::invalid_argument("super truss: an internal node is not at its station on the main beam");
    }
    nodes.push_back(m);
  }
  Mat6 lumped[2] = {Mat6::Zero(), Mat6::Zero()};
  const SectionFrames<double> reference = {{Vec3::Zero(), length * Vec3::UnitX()}, {Mat3::Identity(), Mat3::Identity()}};
  for (const TrussMember& tm : g.members) {
    MemberModel m;
    m.node[0] = tm.node1, m.node[1] = tm.node2;
    const Vec3 axis = g.nodes[tm.node2].position - g.nodes[tm.node1].position;
    const Mat3 R = tubeAxes(axis, tm.z_axis);
    for (int e = 0; e < 2; ++e) m.relative[e] = nodes[m.node[e]].frame.transpose() * R;
    m.beam.length = axis.norm();
    m.beam.section = tm.section;
    m.beam.material = g.material;
    m.beam.mass_points = mass_points;
    m.beam.damping = damping;
    m.stiffness = m.beam.localStiffness();
    const int s0 = nodes[m.node[0]].section, s1 = nodes[m.node[1]].section;
    if (s0 >= 0 && s0 == s1) {  // moves rigidly with section s0: mass only
      const NodeState<double> a = nodeState<double>(reference, nodes[m.node[0]]);
      const NodeState<double> b = nodeState<double>(reference, nodes[m.node[1]]);
      const Mat12 T = memberMap<double>(m, a, b);
      lumped[s0] += (T.transpose() * m.beam.massMatrix<double>(memberEndFrames<double>(m, a, b)) * T)
                        .block<6, 6>(6 * s0, 6 * s0);
    } else {
      members.push_back(m);
    }
  }
  for (int s = 0; s < 2; ++s) {
    rigid[s].mass = lumped[s](0, 0);
    rigid[s].first_moment = unskew(lumped[s].block<3, 3>(3, 0));
    rigid[s].inertia = lumped[s].block<3, 3>(3, 3);
  }
}

auto SuperTrussKernel::nodeFrame(const Q<double>& q, int n) const -> Frame {
  const NodeState<double> s = nodeState<double>(sectionFrames<double>(q), nodes[n]);
  return {s.r, s.R};
}

auto SuperTrussKernel::coordinateTangent(const Q<double>& q, const V<double>& v, const V<double>& a, double, const Vec3& gravity,
                                         const Mat12& M, const Mat12& C) const -> Mat12 {
  if (v.isZero(0.0) && a.isZero(0.0))
    return objectiveCoordinateTangent({q, v, a, gravity, M, C},
                                      [&]<class S>(const Q<S>& qs) { return staticForce<S>(qs, 0.0, gravity); });
  return objectiveCoordinateTangent({q, v, a, gravity, M, C}, [&]<class S>(const Q<S>& qs) {
                                    const V<S> as = a.cast<S>();
                                    return forces<S>(qs, v.cast<S>(), &as, gravity, Terms::All);
                                    });
}

auto SuperTrussKernel::velocityTangent(const Q<double>& q, const V<double>& v, double, Mat12& M) const -> Mat12 {
  using P = Dual<double, 1>;
  const SectionFrames<double> s = sectionFrames<double>(q);
  const SectionFrames<P> path = framesAlongMotion<double>(s, v);
  // C(dq_e) u = [dq_e, u]: the blocks ω̃ⁱ on the end sections' rotations, zero elsewhere.
  const Mat3 W[2] = {skew<double>(Vec3(v.segment<3>(3))), skew<double>(Vec3(v.segment<3>(9)))};
  const std::vector<ChordState<P>>& chord = chordStates<P>(path);
  std::vector<NodeTangent>& node = scratch<NodeTangent>(nodes.size());
  const auto nodeTangent = [&](std::size_t n) {
    NodeTangent& out = node[n];
    NodeMap<double> rate;
    out.state = valuesOf<double>(nodeState<P>(path, nodes[n], chord), &rate);
    out.v.noalias() = out.state.map * v;
    out.acceleration_tangent = 2.0 * rate;
    for (int i = 0; i < 2; ++i)
      out.acceleration_tangent.middleCols<3>(6 * i + 3).noalias() -= out.state.map.middleCols<3>(6 * i + 3) * W[i];
    out.acceleration_tangent.bottomRows<3>().noalias() += skew<double>(Vec3(out.v.tail<3>())) * out.state.map.bottomRows<3>();
  };
  // [M_e | ∂r/∂dq_e] of member k, added to MG.
  using Tangent = Eigen::Matrix<double, 12, 24>;
  const auto addMember = [&](const MemberModel& m, Tangent& MG) {
    const NodeTangent* end[2] = {&node[m.node[0]], &node[m.node[1]]};
    const Mat12 T = memberMap<double>(m, end[0]->state, end[1]->state);
    Mat12 D;  // ∂(Ṫ_k dq_e)/∂dq_e in the member's node frames
    for (int e = 0; e < 2; ++e) {
      D.middleRows<3>(6 * e) = end[e]->acceleration_tangent.topRows<3>();
      D.middleRows<3>(6 * e + 3).noalias() = m.relative[e].transpose() * end[e]->acceleration_tangent.bottomRows<3>();
    }
    Mat12 Mk;
    const Mat12 Gk = m.beam.velocityTangent(end[0]->state.r, Mat3(end[0]->state.R * m.relative[0]), end[1]->state.r,
                                            Mat3(end[1]->state.R * m.relative[1]), Eigen::Matrix<double, 12, 1>(T * v),
                                            m.stiffness, Mk);
    // Coefficient-based products: at 12 × 12 Eigen's general product spends about as much on
    // packing its operands as on the sums (1.5× slower here).
    const Mat12 MkT = Mk.lazyProduct(T);
    const Mat12 GkT_MkD = Gk.lazyProduct(T) + Mk.lazyProduct(D);
    MG.leftCols<12>().noalias() += T.transpose().lazyProduct(MkT);
    MG.rightCols<12>().noalias() += T.transpose().lazyProduct(GkT_MkD);
  };
  Tangent MG = Tangent::Zero();
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(std::size_t{0}, nodes.size(), nodeTangent);
    MG = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, members.size(), kMembersPerTask), Tangent(Tangent::Zero()),
        [&](const tbb::blocked_range<std::size_t>& range, Tangent sum) {
          for (std::size_t k = range.begin(); k != range.end(); ++k) addMember(members[k], sum);
          return sum;
        },
        [](const Tangent& x, const Tangent& y) -> Tangent { return x + y; });
  });
  M = MG.leftCols<12>();
  Mat12 G = MG.rightCols<12>();
  // The rigid parts: M = [[m I, −R s̃], [s̃ Rᵀ, J]], quadratic forces [R(ω × (ω × s)); ω × Jω].
  for (int i = 0; i < 2; ++i) {
    const RigidPart& p = rigid[i];
    const Vec3 w = v.segment<3>(6 * i + 3), c = p.first_moment;
    const Mat3 Rs = s.R[i] * skew<double>(c), W = skew<double>(w);
    M.block<3, 3>(6 * i, 6 * i).diagonal().array() += p.mass;
    M.block<3, 3>(6 * i, 6 * i + 3) -= Rs;
    M.block<3, 3>(6 * i + 3, 6 * i) -= Rs.transpose();
    M.block<3, 3>(6 * i + 3, 6 * i + 3) += p.inertia;
    G.block<3, 3>(6 * i, 6 * i + 3) -= s.R[i] * (skew<double>(Vec3(w.cross(c))) + W * skew<double>(c));
    G.block<3, 3>(6 * i + 3, 6 * i + 3) += W * p.inertia - skew<double>(Vec3(p.inertia * w));
  }
  return G;
}

double SuperTrussKernel::kineticEnergy(const Q<double>& q, const V<double>& v, double) const {
  return 0.5 * v.dot(massMatrix<double>(q) * v);
}

double SuperTrussKernel::strainEnergy(const Q<double>& q) const { return memberEnergy(sectionFrames<double>(q), nullptr); }

double SuperTrussKernel::potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const {
  const SectionFrames<double> s = sectionFrames<double>(q);
  double V = memberEnergy(s, &gravity);
  for (int i = 0; i < 2; ++i) V -= gravity.dot(rigid[i].mass * s.r[i] + s.R[i] * rigid[i].first_moment);
  return V;
}

Vec3 SuperTrussKernel::sectionOffset(const TrussGeometry& g, int node, int section) {
  if (node < 0 || node >= static_cast<int>(g.nodes.size()) || g.nodes[node].end_section != section)
    throw std::invalid_argument("super truss: a main beam does not start and end at end-section nodes");
  return g.nodes[node].position - (section * g.length) * Vec3::UnitX();
}

Mat3 SuperTrussKernel::alignX(const Vec3& t) {
  const Mat3 K = skew<double>(Vec3(Vec3::UnitX().cross(t)));
  return Mat3::Identity() + K + K * K / (1.0 + t.x());
}

double SuperTrussKernel::memberEnergy(const SectionFrames<double>& s, const Vec3* gravity) const {
  const std::vector<ChordState<double>>& chord = chordStates<double>(s);
  std::vector<NodeState<double>>& state = scratch<NodeState<double>>(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n) state[n] = nodeState<double>(s, nodes[n], chord);
  double V = 0.0;
  for (const MemberModel& m : members) {
    const auto e = memberEndFrames<double>(m, state[m.node[0]], state[m.node[1]]);
    const Eigen::Matrix<double, 12, 1> d = m.beam.coRotate<double>(e.r1, e.R1, e.r2, e.R2).d;
    V += 0.5 * d.dot(m.stiffness * d);
    if (gravity) V += m.beam.gravityPotential(e, *gravity);
  }
  return V;
}

}  // namespace cranesim
