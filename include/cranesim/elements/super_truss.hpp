#pragma once
// Super truss element (thesis 3.5): a whole lattice section (chords, lacing, end-section cross
// beams; model/truss_geometry.hpp) on its two end-section frames, q_e = [r¹, φ¹, r², φ²] (3-86),
// twelve DOF whatever the number of tubes. End-section nodes are rigid with their section
// (3-87..3-89); chords are cubic Hermite splines with tangents turned with the sections (3-92);
// internal nodes take the spline beam's section frames; every tube is a Timoshenko beam whose
// mass and forces are mapped by the node velocity maps, M_e = Σ T_kᵀ M_k T_k,
// F_e = Σ T_kᵀ (F_k + M_k Ṫ_k dq_e) (3-97, 3-99, 3-102).
// Thesis deviation kept here: the chord's stretch s = ‖rˡ − rᵏ‖ / L_c scales both tangents; the
// thesis keeps s = 1, which stretches a chord as 6ξ(1 − ξ) and stiffens it.
// Derivation and evaluation (thread scratch, parallel members): docs/elements.md#super-truss.

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include "cranesim/elements/parts/objective_tangent.hpp"
#include "cranesim/elements/spline_beam.hpp"
#include "cranesim/elements/timoshenko_beam.hpp"
#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/hermite.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/truss_geometry.hpp"

namespace cranesim {

struct SuperTrussKernel {
  static constexpr int kNodes = 2;
  static constexpr int kNq = 12;
  static constexpr int kNv = 12;
  template <class S> using Q = Eigen::Matrix<S, kNq, 1>;
  template <class S> using V = Eigen::Matrix<S, kNv, 1>;
  template <class S> using Vec6T = Eigen::Matrix<S, 6, 1>;
  template <class S> using NodeMap = Eigen::Matrix<S, 6, kNv>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;

  /// How a truss node follows the end sections.
  struct NodeModel {
    int section = -1;  // 0/1: end-section node, rigid with that section; −1: internal node
    Vec3 offset;       // end-section node: position in its section frame
    int chord = -1;    // internal node: its chord and station ξ on it
    double xi = 0.0;
    Mat3 frame;  // reference node frame in the truss frame: I (section node) or the chord frame R_c
  };
  struct ChordModel {
    Vec3 offset[2];           // end nodes in their section frames
    Vec3 tangent;             // t: unit reference direction in the section frames
    Mat3 frame;               // R_c, x axis = t
    SplineBeamKernel spline;  // its length L_c is the chord's arc length (only the kinematics are used)
  };
  struct MemberModel {
    int node[2];
    Mat3 relative[2];  // R_rel: member node frame in the node frame (3-83, 3-85)
    TimoshenkoBeamKernel beam;
    Mat12 stiffness;   // beam.localStiffness()
  };
  /// Mass of the members that move rigidly with one end section, about its origin, section axes.
  struct RigidPart {
    double mass = 0.0;
    Vec3 first_moment = Vec3::Zero();  // s = m c
    Mat3 inertia = Mat3::Zero();       // J about the section origin
  };

  static constexpr std::size_t kMembersPerTask = 8;  // tubes per parallel task (~0.2 ms of AD Jacobian)

  double length = 0.0;
  std::vector<NodeModel> nodes;
  std::vector<ChordModel> chords;
  std::vector<MemberModel> members;  // the flexible ones
  std::array<RigidPart, 2> rigid;

  SuperTrussKernel() = default;

  bool damped() const {
    return std::any_of(members.begin(), members.end(), [](const MemberModel& m) { return m.beam.damped(); });
  }

  /// Builds the kernel from a truss geometry. `mass_points`: Gauss points of each tube's mass
  /// (Timoshenko default 4); `damping`: Kelvin–Voigt retardation time η of every tube, s.
  explicit SuperTrussKernel(const TrussGeometry& g, int mass_points = 4, double damping = 0.0);

  // ---------------------------------------------------------------------------------------------
  // Node kinematics

  template <class T> struct SectionFrames {
    Vec3T<T> r[2];
    Mat3T<T> R[2];
  };
  /// A node's position, frame and velocity map [ṙ; ω] = map dq_e (ω in the node frame).
  template <class T> struct NodeState {
    Vec3T<T> r;
    Mat3T<T> R;
    NodeMap<T> map;
  };

  template <class S> static SectionFrames<S> sectionFrames(const Q<S>& q) {
    return {{q.template segment<3>(0), q.template segment<3>(6)},
            {rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3))), rotationMatrix<S>(Vec3T<S>(q.template segment<3>(9)))}};
  }

  /// What the internal nodes of one chord share: its end nodes rᵏ = r¹ + R₁pₖ, rˡ = r² + R₂pₗ,
  /// its frame at node k, Rᵏ = R₁R_c, the deformation seen from there (with the chord's stretch s
  /// as both end stretches), the row of ṡ = row · dq_e, and the end sections' R_i p̃, R_i t̃ and
  /// R_i t for the chord's end offsets p = pₖ, pₗ and its reference direction t.
  template <class T> struct ChordState {
    Vec3T<T> r[2];
    Mat3T<T> Rk;
    typename SplineBeamKernel::Relative<T> rel;
    Eigen::Matrix<T, 1, kNv> stretch_rate;
    Mat3T<T> Rp[2], Rt[2];
    Vec3T<T> t[2];
  };

  template <class T> [[gnu::flatten]] ChordState<T> chordState(const SectionFrames<T>& s, const ChordModel& c) const {
    ChordState<T> out;
    for (int i = 0; i < 2; ++i) {
      out.r[i] = s.r[i] + s.R[i] * c.offset[i];
      out.Rp[i] = s.R[i] * skew<double>(c.offset[i]);
      out.Rt[i] = s.R[i] * skew<double>(c.tangent);
      out.t[i] = s.R[i] * c.tangent;
    }
    out.Rk = s.R[0] * c.frame;
    // Both end tangents are stretched by the chord's stretch s = ‖rˡ − rᵏ‖ / L_c: the chord
    // keeps no axial degree of freedom of its own, but a uniformly stretched chord is
    // represented exactly (with s = 1 the spline would stretch as 6ξ(1 − ξ), 25 % too stiff).
    const Vec3T<T> chord = out.r[1] - out.r[0];
    const T chord_length = chord.norm();
    const T stretch = chord_length / c.spline.length;
    out.rel = {out.Rk.transpose() * chord, out.Rk.transpose() * Mat3T<T>(s.R[1] * c.frame), stretch, stretch};
    // ṡ = ĉᵀ(ṙˡ − ṙᵏ) / L_c with ṙᵏ = ṙ¹ − R₁ p̃ₖ ω¹, ṙˡ = ṙ² − R₂ p̃ₗ ω².
    const Eigen::Matrix<T, 1, 3> c_hat = (chord / (chord_length * T(c.spline.length))).transpose();
    out.stretch_rate.template segment<3>(0) = -c_hat;
    out.stretch_rate.template segment<3>(3) = c_hat * out.Rp[0];
    out.stretch_rate.template segment<3>(6) = c_hat;
    out.stretch_rate.template segment<3>(9) = -(c_hat * out.Rp[1]);
    return out;
  }

  /// The chords' shared parts (chordState) in the calling thread's scratch buffer.
  template <class T> const std::vector<ChordState<T>>& chordStates(const SectionFrames<T>& s) const {
    std::vector<ChordState<T>>& out = scratch<ChordState<T>>(chords.size());
    for (std::size_t c = 0; c < chords.size(); ++c) out[c] = chordState<T>(s, chords[c]);
    return out;
  }

  /// Node n's state from the chords' shared parts.
  template <class T>
  NodeState<T> nodeState(const SectionFrames<T>& s, const NodeModel& n, const std::vector<ChordState<T>>& chord) const {
    return nodeState<T>(s, n, n.section >= 0 ? nullptr : &chord[n.chord]);
  }

  /// A single node's state (its chord's shared part formed for it alone).
  template <class T> NodeState<T> nodeState(const SectionFrames<T>& s, const NodeModel& n) const {
    if (n.section >= 0) return nodeState<T>(s, n, nullptr);
    const ChordState<T> chord = chordState<T>(s, chords[n.chord]);
    return nodeState<T>(s, n, &chord);
  }

  /// Node n's state; `chord`: its chord's shared part (internal nodes).
  template <class T> [[gnu::flatten]] NodeState<T> nodeState(const SectionFrames<T>& s, const NodeModel& n, const ChordState<T>* chord) const {
    NodeState<T> out;
    out.map.setZero();
    if (n.section >= 0) {  // (3-87..3-89)
      const int i = n.section;
      out.r = s.r[i] + s.R[i] * n.offset;
      out.R = s.R[i];
      out.map.template block<3, 3>(0, 6 * i).setIdentity();
      out.map.template block<3, 3>(0, 6 * i + 3) = -(s.R[i] * skew<double>(n.offset));
      out.map.template block<3, 3>(3, 6 * i + 3).setIdentity();
      return out;
    }
    const ChordModel& c = chords[n.chord];
    const ChordState<T>& cs = *chord;
    const HermiteBasis b = hermiteBasis(n.xi, c.spline.length);
    // Position (3-92 with A-9), r = N₀¹ rᵏ + N₁¹ s R₁t + N₀² rˡ + N₁² s R₂t, and its map: ∂r/∂θⁱ
    // = −Rᵢ (N pᵢ + N' s t)~, and ∂r/∂s = N₁¹ R₁t + N₁² R₂t along ṡ.
    const T& stretch = cs.rel.s1;
    const T w1 = b.N[1] * stretch, w2 = b.N[3] * stretch;
    out.r = b.N[0] * cs.r[0] + b.N[2] * cs.r[1] + w1 * cs.t[0] + w2 * cs.t[1];
    for (int k = 0; k < 3; ++k) out.map(k, k) = T(b.N[0]), out.map(k, 6 + k) = T(b.N[2]);
    out.map.template block<3, 3>(0, 3) = -(b.N[0] * cs.Rp[0] + w1 * cs.Rt[0]);
    out.map.template block<3, 3>(0, 9) = -(b.N[2] * cs.Rp[1] + w2 * cs.Rt[1]);
    const Vec3T<T> dr_dstretch = b.N[1] * cs.t[0] + b.N[3] * cs.t[1];
    out.map.template topRows<3>() += dr_dstretch * cs.stretch_rate;
    // Frame R = Rᵏ C(α) (3-64..3-67) and ω = Cᵀωᵏ + T_C ∂α/∂δ_local Λ dq_chord (3-69), T_C (B-17)
    // = [1, 0, −sψ; 0, cφ, sφcψ; 0, −sφ, cφcψ] applied row by row.
    using std::cos, std::sin;
    const auto sd = c.spline.template sectionDerivatives<T>(cs.rel, n.xi, false);
    const T sf = sin(sd.alpha(0)), cf = cos(sd.alpha(0)), sp = sin(sd.alpha(1)), cp = cos(sd.alpha(1));
    const Mat3T<T> C = SplineBeamKernel::cardanMatrix<T>(sf, cf, sp, cp, sin(sd.alpha(2)), cos(sd.alpha(2)));
    out.R = cs.Rk * C;
    Eigen::Matrix<T, 3, SplineBeamKernel::kLocal> TD;
    const T sf_cp = sf * cp, cf_cp = cf * cp;
    TD.row(0) = sd.dalpha.row(0) - sp * sd.dalpha.row(2);
    TD.row(1) = cf * sd.dalpha.row(1) + sf_cp * sd.dalpha.row(2);
    TD.row(2) = cf_cp * sd.dalpha.row(2) - sf * sd.dalpha.row(1);
    const Mat3T<T> Td = TD.template leftCols<3>(), Tchi = TD.template middleCols<3>(3);
    const Mat3T<T> B = Td * cs.Rk.transpose();
    out.map.template block<3, 3>(3, 0) = -B;
    out.map.template block<3, 3>(3, 3) =
        B * cs.Rp[0] + Mat3T<T>(Mat3T<T>(C.transpose()) + Td * skew<T>(cs.rel.d) - Tchi * cs.rel.R12.transpose()) * c.frame.transpose();
    out.map.template block<3, 3>(3, 6) = B;
    out.map.template block<3, 3>(3, 9) = Tchi * c.frame.transpose() - B * cs.Rp[1];
    out.map.template bottomRows<3>() += Vec3T<T>(TD.col(6) + TD.col(7)) * cs.stretch_rate;
    return out;
  }

  /// Position and frame of truss node n.
  Frame nodeFrame(const Q<double>& q, int n) const;

  // ---------------------------------------------------------------------------------------------
  // Kernel contract (element.hpp)

  /// M_e = Σ T_kᵀ M_k T_k (3-97, 3-99, 3-102) + the rigid parts of the end sections.
  template <class S> Eigen::Matrix<S, kNv, kNv> massMatrix(const Q<S>& q, double = 0.0) const {
    const SectionFrames<S> s = sectionFrames<S>(q);
    const std::vector<ChordState<S>>& chord = chordStates<S>(s);
    std::vector<NodeState<S>>& state = scratch<NodeState<S>>(nodes.size());
    for (std::size_t n = 0; n < nodes.size(); ++n) state[n] = nodeState<S>(s, nodes[n], chord);
    Eigen::Matrix<S, kNv, kNv> M = Eigen::Matrix<S, kNv, kNv>::Zero();
    for (int i = 0; i < 2; ++i) {
      const RigidPart& p = rigid[i];
      for (int k = 0; k < 3; ++k) M(6 * i + k, 6 * i + k) = S(p.mass);
      const Mat3T<S> Rs = s.R[i] * skew<S>(Vec3T<S>(p.first_moment.cast<S>()));
      M.template block<3, 3>(6 * i, 6 * i + 3) = -Rs;
      M.template block<3, 3>(6 * i + 3, 6 * i) = -Rs.transpose();
      M.template block<3, 3>(6 * i + 3, 6 * i + 3) = p.inertia.cast<S>();
    }
    for (const MemberModel& m : members) {
      const NodeState<S>& a = state[m.node[0]];
      const NodeState<S>& b = state[m.node[1]];
      const Eigen::Matrix<S, 12, kNv> T = memberMap<S>(m, a, b);
      const Eigen::Matrix<S, 12, 12> Mk = m.beam.template massMatrix<S>(memberEndFrames<S>(m, a, b));
      M.noalias() += T.transpose() * (Mk * T);
    }
    return M;
  }

  /// F_e = Σ T_kᵀ (F_k + M_k Ṫ_k dq_e) + the rigid parts' inertial and gravity forces.
  template <class S> V<S> force(const Q<S>& q, const V<S>& v, double, const Vec3& gravity) const {
    return forces<S>(q, v, nullptr, gravity, Terms::All);
  }

  /// M_e a + F_e = Σ T_kᵀ (F_k + M_k (T_k a + Ṫ_k dq_e)) + the rigid parts' terms, in one pass over
  /// the members (element.hpp: a kernel's optional fused residual). Cheaper than massMatrix and
  /// force apart, which would evaluate every member's mass matrix twice.
  template <class S> V<S> residual(const Q<S>& q, const V<S>& v, const V<S>& a, double, const Vec3& gravity) const {
    return forces<S>(q, v, &a, gravity, Terms::All);
  }

  /// Elastic and damping forces alone (zero for rigid placements and rigid velocities).
  template <class S> V<S> elasticForce(const Q<S>& q, const V<S>& v) const {
    return forces<S>(q, v, nullptr, Vec3::Zero(), Terms::Elastic);
  }

  /// The tubes' damping forces alone (their power is the Kelvin–Voigt dissipation).
  template <class S> V<S> dampingForce(const Q<S>& q, const V<S>& v) const {
    return forces<S>(q, v, nullptr, Vec3::Zero(), Terms::Damping);
  }

  /// F(q, 0, t): elastic forces and gravity, without the velocity path of the inertial terms
  /// (the statics' Jacobian differentiates this, coordinateTangent).
  template <class S> V<S> staticForce(const Q<S>& q, double, const Vec3& gravity) const {
    return forces<S>(q, V<S>(V<S>::Zero()), nullptr, gravity, Terms::AtRest);
  }

  /// ∂(M_e a + F_e)/∂q_e (element.hpp) from M_e and the velocity tangent C (objective_tangent.hpp):
  /// forward AD of the residual in end 2's six directions — at rest (the statics) of the force at
  /// rest alone, without the velocity path of the inertial terms.
  Mat12 coordinateTangent(const Q<double>& q, const V<double>& v, const V<double>& a, double, const Vec3& gravity,
                          const Mat12& M, const Mat12& C) const;

  /// ∂(M_e a + F_e)/∂dq_e in closed form and M_e beside it (element.hpp). Member k adds
  /// T_kᵀ (G_k T_k + M_k ∂(Ṫ_k dq_e)/∂dq_e), G_k its beam's velocity tangent; every node's velocity
  /// map obeys the same twist bracket as a beam section (section_inertia_tangent.hpp):
  ///     ∂(Ṫ_n dq_e)/∂dq_e = 2Ṫ_n − T_n C(dq_e) + [0; ω̃_n T_n^ω],
  /// ω_n the node's angular velocity and T_n^ω the angular rows of its map.
  Mat12 velocityTangent(const Q<double>& q, const V<double>& v, double, Mat12& M) const;

  double kineticEnergy(const Q<double>& q, const V<double>& v, double = 0.0) const;

  /// Σ ½ dᵀ K d of the flexible members (3-77 for each Timoshenko tube).
  double strainEnergy(const Q<double>& q) const;

  /// Gravity potential of all tubes + strain energy.
  double potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const;

  /// Total mass of the tubes.
  double mass() const {
    double m = rigid[0].mass + rigid[1].mass;
    for (const MemberModel& k : members) m += k.beam.material.density * k.beam.section.area * k.beam.length;
    return m;
  }

 private:
  static Vec3 sectionOffset(const TrussGeometry& g, int node, int section);

  /// The smallest rotation taking e_x onto the unit vector t (t·e_x > −1).
  static Mat3 alignX(const Vec3& t);

  template <class Item> static std::vector<Item>& scratchBuffer() {
    thread_local std::vector<Item> buffer;
    return buffer;
  }
  /// The calling thread's buffer of at least `count` items (one per node or per chord).
  template <class Item> std::vector<Item>& scratch(std::size_t count) const {
    std::vector<Item>& buffer = scratchBuffer<Item>();
    if (buffer.size() < count) buffer.resize(count);
    return buffer;
  }

  /// Σ ½ dᵀ K d of the flexible members and, with `gravity`, their gravity potential; every
  /// node's state formed once (a node is shared by several tubes).
  double memberEnergy(const SectionFrames<double>& s, const Vec3* gravity) const;

  /// T_k: member node velocities [ṙ_a, ω_a, ṙ_b, ω_b] (member node frames) = T_k dq_e.
  template <class S>
  static Eigen::Matrix<S, 12, kNv> memberMap(const MemberModel& m, const NodeState<S>& a, const NodeState<S>& b) {
    Eigen::Matrix<S, 12, kNv> T;
    const NodeState<S>* end[2] = {&a, &b};
    for (int e = 0; e < 2; ++e) {
      T.template middleRows<3>(6 * e) = end[e]->map.template topRows<3>();
      T.template middleRows<3>(6 * e + 3) = m.relative[e].transpose().cast<S>() * end[e]->map.template bottomRows<3>();
    }
    return T;
  }

  template <class S>
  static typename TimoshenkoBeamKernel::EndFrames<S> memberEndFrames(const MemberModel& m, const NodeState<S>& a,
                                                                     const NodeState<S>& b) {
    return m.beam.endFrames<S>(a.r, Mat3T<S>(a.R * m.relative[0].cast<S>()), b.r, Mat3T<S>(b.R * m.relative[1].cast<S>()));
  }

  /// The section frames along the path r(τ) = r + τṙ, R(τ) = R(I + τω̃) (first order): the
  /// derivative parts of anything computed from them are its rates at d(dq)/dt = 0.
  template <class S> static SectionFrames<Dual<S, 1>> framesAlongMotion(const SectionFrames<S>& s, const V<S>& v) {
    using P = Dual<S, 1>;
    SectionFrames<P> path;
    for (int i = 0; i < 2; ++i) {
      const Mat3T<S> dR = s.R[i] * skew<S>(Vec3T<S>(v.template segment<3>(6 * i + 3)));
      for (int j = 0; j < 3; ++j) {
        path.r[i](j) = P(s.r[i](j), Eigen::Matrix<S, 1, 1>(v(6 * i + j)));
        for (int k = 0; k < 3; ++k) path.R[i](j, k) = P(s.R[i](j, k), Eigen::Matrix<S, 1, 1>(dR(j, k)));
      }
    }
    return path;
  }

  /// The values of a node state computed along the motion (framesAlongMotion) and, with `rate`,
  /// the rate of its map, ṁap.
  template <class S> static NodeState<S> valuesOf(const NodeState<Dual<S, 1>>& p, NodeMap<S>* rate = nullptr) {
    NodeState<S> out;
    for (int i = 0; i < 3; ++i) {
      out.r(i) = p.r(i).value();
      for (int j = 0; j < 3; ++j) out.R(i, j) = p.R(i, j).value();
    }
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < kNv; ++j) {
        out.map(i, j) = p.map(i, j).value();
        if (rate) (*rate)(i, j) = p.map(i, j).derivatives()(0);
      }
    return out;
  }

  /// A node's state, its velocity v = map dq and ∂(ṁap dq)/∂dq (velocityTangent).
  struct NodeTangent {
    NodeState<double> state;
    Vec6T<double> v;
    NodeMap<double> acceleration_tangent;
  };

  /// A node's state with its velocity v = map dq and its acceleration at d(dq)/dt = 0, a0 = ṁap dq.
  template <class S> struct NodeMotion {
    NodeState<S> state;
    Vec6T<S> v, a0;
  };

  /// Which terms forces() computes: all of F_e (+ M_e a), F_e at rest (dq = 0: elastic forces and
  /// gravity, no velocity path), the elastic and damping forces alone, or the damping forces alone.
  enum class Terms { All, AtRest, Elastic, Damping };

  /// F_e (+ M_e a when `a` is given), or the part of it that `terms` names.
  template <class S> V<S> forces(const Q<S>& q, const V<S>& v, const V<S>* a, const Vec3& gravity, Terms terms) const {
    using P = Dual<S, 1>;
    const SectionFrames<S> s = sectionFrames<S>(q);
    const SectionFrames<P> path = framesAlongMotion<S>(s, v);
    const Eigen::Matrix<P, kNv, 1> vp = v.template cast<P>();
    std::vector<NodeMotion<S>>& motion = scratch<NodeMotion<S>>(nodes.size());
    // The chords' shared parts: at the section frames, or along the motion for all terms.
    const std::vector<ChordState<S>>* chord = terms == Terms::All ? nullptr : &chordStates<S>(s);
    const std::vector<ChordState<P>>* chord_path = terms == Terms::All ? &chordStates<P>(path) : nullptr;
    const auto nodeMotion = [&](std::size_t n) {
      NodeMotion<S>& out = motion[n];
      if (terms != Terms::All) {
        out.state = nodeState<S>(s, nodes[n], *chord);
        out.v = out.state.map * v;
        return;
      }
      const NodeState<P> p = nodeState<P>(path, nodes[n], *chord_path);
      const Vec6T<P> vn = p.map * vp;
      out.state = valuesOf<S>(p);
      for (int i = 0; i < 6; ++i) {
        out.v(i) = vn(i).value();
        out.a0(i) = vn(i).derivatives()(0);
      }
      if (a) out.a0.noalias() += out.state.map * *a;  // node accelerations T_n a + Ṫ_n dq_e
    };

    V<S> F = V<S>::Zero();
    if (terms == Terms::All || terms == Terms::AtRest) {
      const Vec3T<S> g = gravity.cast<S>();
      for (int i = 0; i < 2; ++i) {
        const RigidPart& p = rigid[i];
        const Vec3T<S> w = v.template segment<3>(6 * i + 3), c = p.first_moment.cast<S>();
        F.template segment<3>(6 * i) += s.R[i] * Vec3T<S>(w.cross(w.cross(c))) - S(p.mass) * g;
        F.template segment<3>(6 * i + 3) += w.cross(Vec3T<S>(p.inertia.cast<S>() * w)) - c.cross(Vec3T<S>(s.R[i].transpose() * g));
        if (!a) continue;
        const Vec3T<S> linear = a->template segment<3>(6 * i), angular = a->template segment<3>(6 * i + 3);
        F.template segment<3>(6 * i) += S(p.mass) * linear + s.R[i] * Vec3T<S>(angular.cross(c));
        F.template segment<3>(6 * i + 3) += c.cross(Vec3T<S>(s.R[i].transpose() * linear)) + p.inertia.cast<S>() * angular;
      }
    }
    // T_kᵀ (F_k + M_k (T_k a + Ṫ_k dq_e)) of member k, added to G.
    const auto addMember = [&](const MemberModel& m, V<S>& G) {
      const NodeMotion<S>* end[2] = {&motion[m.node[0]], &motion[m.node[1]]};
      const auto e = memberEndFrames<S>(m, end[0]->state, end[1]->state);
      Eigen::Matrix<S, 12, 1> vk, ak;
      for (int k = 0; k < 2; ++k) {
        vk.template segment<3>(6 * k) = end[k]->v.template head<3>();
        vk.template segment<3>(6 * k + 3) = m.relative[k].transpose().cast<S>() * end[k]->v.template tail<3>();
      }
      Eigen::Matrix<S, 12, 1> Fk = terms == Terms::Damping
                                       ? m.beam.template dampingForce<S>(e.r1, e.R1, e.r2, e.R2, vk, m.stiffness)
                                       : m.beam.template elasticForce<S>(e.r1, e.R1, e.r2, e.R2, vk, m.stiffness);
      if (terms == Terms::AtRest) Fk += m.beam.template gravityForce<S>(e, gravity);
      if (terms == Terms::All) {
        for (int k = 0; k < 2; ++k) {
          ak.template segment<3>(6 * k) = end[k]->a0.template head<3>();
          ak.template segment<3>(6 * k + 3) = m.relative[k].transpose().cast<S>() * end[k]->a0.template tail<3>();
        }
        Fk += m.beam.template inertialAndGravityForce<S>(e.r1, e.R1, e.r2, e.R2, vk, gravity, &ak);
      }
      // T_kᵀ F_k, node by node.
      for (int k = 0; k < 2; ++k) {
        Vec6T<S> f;
        f << Fk.template segment<3>(6 * k), m.relative[k].cast<S>() * Fk.template segment<3>(6 * k + 3);
        G.noalias() += end[k]->state.map.transpose() * f;
      }
    };
    // Nodes, then members, in parallel. Isolated: while this thread waits for its own tasks it
    // must not pick up another element's call, which would reuse its node scratch buffer. The
    // deterministic reduction keeps the sum's order, so results do not depend on the threads.
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(std::size_t{0}, nodes.size(), nodeMotion);
      F += tbb::parallel_deterministic_reduce(
          tbb::blocked_range<std::size_t>(0, members.size(), kMembersPerTask), V<S>(V<S>::Zero()),
          [&](const tbb::blocked_range<std::size_t>& range, V<S> G) {
            for (std::size_t k = range.begin(); k != range.end(); ++k) addMember(members[k], G);
            return G;
          },
          [](const V<S>& x, const V<S>& y) -> V<S> { return x + y; });
    });
    return F;
  }
};

}  // namespace cranesim
