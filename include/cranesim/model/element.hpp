#pragma once
// The assembler's view of an element: equations of motion M(q) d(dq)/dt + F(q, dq, t) on a
// few nodes, with their Jacobians. KernelElement adapts any header-only kernel to it and
// obtains the Jacobians from the kernel's templated code: ∂/∂q by forward automatic
// differentiation, ∂/∂dq by the kernel's closed form or by polarization of the quadratic in dq
// (exact, see jacobian).
//
// Kernel contract (docs/architecture.md#the-element-kernel-contract). A kernel is a small struct with
//   static constexpr int kNq, kNv;                       local sizes of q_e and dq_e
//   template <class S> Matrix<S, kNv, kNv> massMatrix(const Matrix<S, kNq, 1>& q, double t) const;
//   template <class S> Matrix<S, kNv, 1> force(const Matrix<S, kNq, 1>& q,
//                                              const Matrix<S, kNv, 1>& dq, double t,
//                                              const Vec3& gravity) const;
//   double kineticEnergy(q, dq, t) const;      ½ dqᵀ M dq
//   double potentialEnergy(q, t, gravity) const;  gravity + strain energy
// so that its equations read M(q, t) d(dq)/dt + F(q, dq, t) = applied and constraint forces
// (3-26, 3-51). q_e and dq_e are the concatenated coordinates of the element's nodes, in order.
//
// Energy books. With E = T + V the equations give, along any motion,
//   dqᵀ(M d(dq)/dt + F) = dE/dt − P_time + P_diss,
// P_time the power of the element's explicit time dependence (a rope reeled by a winch) and
// P_diss ≥ 0 the power of its material damping. The default is P_time = 0, and P_diss = 0 unless
// the kernel says it is damped:
//   bool damped() const;   then P_diss = dqᵀ(F(q, dq) − F(q, −dq))/2 = dqᵀ D dq, exact when F is
//                          F₀(q) + D(q) dq + G(q; dq, dq) with dqᵀG = ½ dqᵀ Ṁ dq (inertia),
//                          or dqᵀ dampingForce(q, dq) when the kernel has D dq alone
// A kernel whose parameters follow time, or whose damping is not linear in dq, provides
//   double explicitTimePower(q, dq, t, gravity) const;   P_time
//   double dissipatedPower(q, dq, t, gravity) const;     P_diss
// and a kernel with explicitTimePower takes a fifth argument of force, ElementInput::rates: which
// rates of its parameters it is to use.
// Optionally, a kernel whose mass matrix is costly provides the fused residual
//   template <class S> Matrix<S, kNv, 1> residual(q, dq, a, t, gravity) const;   M(q) a + F
// which KernelElement then uses for the residual and its Jacobian.
// A kernel with a closed form of its velocity derivative provides the velocity tangent
//   Matrix<double, kNv, kNv> velocityTangent(q, dq, t, Matrix<double, kNv, kNv>& M) const;
//   ∂(M(q) a + F)/∂dq in closed form, and M(q)
// which KernelElement's jacobian then uses for the velocity columns, and
//   Matrix<double, kNv, kNq> coordinateTangent(q, dq, a, t, gravity) const;   ∂(M a + F)/∂q
// which coordinateJacobian then uses instead of forward AD over the whole kernel; a kernel with
// explicitTimePower takes ElementInput::rates as their last argument too. A frame-indifferent
// kernel with a velocity tangent takes M and the velocity tangent C instead
// (objective_tangent.hpp):
//   Matrix<double, kNv, kNq> coordinateTangent(q, dq, a, t, gravity, M, C) const;
// The templated functions must not branch on derivative parts and must not allocate, and F must
// be a polynomial of degree ≤ 2 in dq (inertial terms quadratic, damping linear): a force
// nonlinear in the velocities (drag, friction) would need its own ∂/∂dq.

#include <array>
#include <cmath>
#include <concepts>
#include <vector>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/profile.hpp"

namespace cranesim {

/// Points at which a rope element reports its tension: equally spaced over the element, ends
/// included.
inline constexpr int kTensionPoints = 9;

/// Global state vectors an element reads its local coordinates from.
struct ElementInput {
  const double* q;   // generalized coordinates
  const double* v;   // generalized velocities
  const double* a;   // generalized accelerations d(dq)/dt
  double t;
  Vec3 gravity;
  /// α of a mass-proportional damping force α M(q) dq, added to F (static relaxation only).
  double mass_damping = 0.0;
  /// The rates of the parameters that follow time (a rope's length): left-sided (integrating
  /// up to t), right-sided (starting from a breakpoint at t), or held at their values at t, rates
  /// 0 (statics and modes, whose equilibrium is that of the controls at t).
  ParameterRates rates = ParameterRates::Left;
  /// The factor on applied loads that statics ramps from 0 to 1 (gravity comes scaled already);
  /// elements that stand for applied loads (the wind, model/wind_elements.hpp) scale by it.
  double load_factor = 1.0;
};

class Element {
 public:
  virtual ~Element() = default;
  /// The element's nodes, and for each node the offsets of its coordinates in q and v.
  virtual const std::vector<int>& nodes() const = 0;
  /// Local size of dq: the number of equations the element contributes.
  virtual int size() const = 0;
  /// Global v indices of the local equations (and of the local velocities), in order.
  virtual const std::vector<int>& velocityIndices() const = 0;
  /// Global q indices of the local coordinates, in order.
  virtual const std::vector<int>& coordinateIndices() const = 0;
  /// r = M(q) (a + α v) + F(q, v, t), α = in.mass_damping.
  virtual void residual(const ElementInput& in, double* r) const = 0;
  /// J = [∂r/∂q | ∂r/∂v + cj M], column-major, size() × (nq_local + size()).
  virtual void jacobian(const ElementInput& in, double cj, double* J) const = 0;
  /// ∂r/∂q alone, column-major, size() × nq_local (v and a held): the statics' Jacobian and
  /// the q columns of `jacobian`, by forward AD in the nq_local coordinate directions.
  virtual void coordinateJacobian(const ElementInput& in, double* J) const = 0;
  /// Local mass matrix M(q), column-major, size() × size().
  virtual void mass(const ElementInput& in, double* M) const = 0;
  /// A sparse element's Jacobian as small dense blocks, each given by the local indices (of
  /// velocityIndices and coordinateIndices alike, which then have equal sizes) its rows and its
  /// columns share; a sparse element's mass matrix is diagonal. Empty, the default: one dense
  /// block of all (`jacobian`).
  virtual std::vector<std::vector<int>> jacobianBlocks() const { return {}; }
  /// A sparse element's blocks side by side, each b × 2b column-major over its b indices,
  /// [∂r/∂q | ∂r/∂dq + cj M]; with `coordinates_only` its dq columns 0.
  virtual void blockJacobian(const ElementInput&, double /*cj*/, bool /*coordinates_only*/, double* /*values*/) const {}
  virtual double kineticEnergy(const ElementInput& in) const = 0;
  virtual double potentialEnergy(const ElementInput& in) const = 0;
  /// Power the element's explicit time dependence puts into it at (q, dq, t) (the winch's
  /// power on a rope of varying length), W.
  virtual double explicitTimePower(const ElementInput&) const { return 0.0; }
  /// Power its material damping dissipates at (q, dq, t), ≥ 0, W.
  virtual double dissipatedPower(const ElementInput&) const { return 0.0; }
  /// An element with memory (a sheave's grip on its rope) moves it to the state a step was
  /// accepted at: its residual within the next step starts from there. The memory is the
  /// model's, as its inputs' signals: one run at a time.
  virtual void hold(const ElementInput&) const {}
  /// The memory as numbers (saved with a run's state) and back.
  virtual std::vector<double> memory() const { return {}; }
  virtual void setMemory(const double*) const {}
  /// Back to the memory it was compiled with.
  virtual void forgetMemory() const {}
  /// A beam's section forces [N, V_y, V_z, T, M_y, M_z] at its two ends (12 values, N, N·m) in
  /// its co-rotated frame, at (q, dq, d(dq)/dt); false for an element that is no beam.
  virtual bool sectionForces(const ElementInput&, double*) const { return false; }
  /// A rope's axial force (elastic, N ≥ 0) at kTensionPoints points of the element at (q, t);
  /// false for an element that is no rope.
  virtual bool tensions(const ElementInput&, double*) const { return false; }
};

/// A kernel that computes M(q) a + F(q, dq, t) in one call.
template <class K>
concept FusedResidualKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q,
                                       const Eigen::Matrix<double, K::kNv, 1>& v, const Vec3& g) {
  { k.template residual<double>(q, v, v, 0.0, g) } -> std::convertible_to<Eigen::Matrix<double, K::kNv, 1>>;
};

/// A kernel whose parameters follow time (explicitTimePower), or whose damping is not linear
/// in dq (dissipatedPower).
template <class K>
concept TimeDependentKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q,
                                       const Eigen::Matrix<double, K::kNv, 1>& v, const Vec3& g) {
  { k.explicitTimePower(q, v, 0.0, g) } -> std::convertible_to<double>;
};
template <class K>
concept DissipationKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q,
                                     const Eigen::Matrix<double, K::kNv, 1>& v, const Vec3& g) {
  { k.dissipatedPower(q, v, 0.0, g) } -> std::convertible_to<double>;
};
/// A kernel with damping linear in dq, which may be switched off.
template <class K>
concept LinearlyDampedKernel = requires(const K& k) {
  { k.damped() } -> std::convertible_to<bool>;
};
/// A kernel that computes its damping forces D(q) dq alone (cheaper than F twice).
template <class K>
concept DampingForceKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q,
                                      const Eigen::Matrix<double, K::kNv, 1>& v) {
  { k.template dampingForce<double>(q, v) } -> std::convertible_to<Eigen::Matrix<double, K::kNv, 1>>;
};

/// A beam kernel that reports its section forces.
template <class K>
concept SectionForceKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q,
                                      const Eigen::Matrix<double, K::kNv, 1>& v, const Vec3& g) {
  { k.sectionForces(q, v, v, g) } -> std::convertible_to<Eigen::Matrix<double, 12, 1>>;
};

/// A rope kernel that reports its tension at ξ ∈ [0, 1].
template <class K>
concept TensionKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q) {
  { k.tension(q, 0.0, 0.5) } -> std::convertible_to<double>;
};

/// A kernel that computes ∂(M a + F)/∂dq in closed form, with M beside it.
template <class K>
concept VelocityTangentKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q,
                                         const Eigen::Matrix<double, K::kNv, 1>& v, Eigen::Matrix<double, K::kNv, K::kNv>& M) {
  { k.velocityTangent(q, v, 0.0, M) } -> std::convertible_to<Eigen::Matrix<double, K::kNv, K::kNv>>;
};

/// A kernel that computes ∂(M a + F)/∂q itself.
template <class K>
concept CoordinateTangentKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q,
                                           const Eigen::Matrix<double, K::kNv, 1>& v, const Vec3& g) {
  { k.coordinateTangent(q, v, v, 0.0, g) } -> std::convertible_to<Eigen::Matrix<double, K::kNv, K::kNq>>;
};

/// A kernel that computes ∂(M a + F)/∂q from M and its velocity tangent (objective_tangent.hpp).
template <class K>
concept ObjectiveTangentKernel = requires(const K& k, const Eigen::Matrix<double, K::kNq, 1>& q,
                                          const Eigen::Matrix<double, K::kNv, 1>& v, const Vec3& g,
                                          const Eigen::Matrix<double, K::kNv, K::kNv>& M) {
  { k.coordinateTangent(q, v, v, 0.0, g, M, M) } -> std::convertible_to<Eigen::Matrix<double, K::kNv, K::kNq>>;
};

template <class Kernel> class KernelElement final : public Element {
 public:
  static constexpr int kNq = Kernel::kNq, kNv = Kernel::kNv;
  using Qd = Eigen::Matrix<double, kNq, 1>;
  using Vd = Eigen::Matrix<double, kNv, 1>;

  KernelElement(Kernel kernel, std::vector<int> nodes, std::vector<int> q_indices,
                std::vector<int> v_indices)
      : kernel_(std::move(kernel)), nodes_(std::move(nodes)), q_(std::move(q_indices)),
        v_(std::move(v_indices)) {}

  const Kernel& kernel() const { return kernel_; }
  const std::vector<int>& nodes() const override { return nodes_; }
  int size() const override { return kNv; }
  const std::vector<int>& velocityIndices() const override { return v_; }
  const std::vector<int>& coordinateIndices() const override { return q_; }

  void residual(const ElementInput& in, double* r) const override {
    Eigen::Map<Vd> out(r);
    out = residualAt(gatherQ(in.q), gatherV(in.v), gatherV(in.a), in);
  }

  /// ∂r/∂q by forward AD in the kNq coordinate directions (coordinateJacobian). ∂r/∂dq by the
  /// kernel's velocityTangent, or else by polarization: r is a polynomial of degree ≤ 2 in dq
  /// (kinetic energy is quadratic in the velocities, material damping linear; the kernel
  /// contract), so the central difference
  /// (r(dq + s e_j) − r(dq − s e_j)) / 2s is its exact derivative for any s, up to rounding
  /// (≈ ε‖r‖/s). s is kept small so that a kink in dq (a damped rope's max(ε + η ε̇, 0) at the
  /// verge of slack) lies between the probes only within s of it.
  void jacobian(const ElementInput& in, double cj, double* J) const override {
    const Qd q = gatherQ(in.q);
    const Vd v = gatherV(in.v), a = gatherV(in.a);
    Eigen::Map<Eigen::Matrix<double, kNv, kNv>> Jv(J + kNv * kNq);
    if constexpr (VelocityTangentKernel<Kernel>) {
      Eigen::Matrix<double, kNv, kNv> M;
      if constexpr (TimeDependentKernel<Kernel>)
        Jv = kernel_.velocityTangent(q, v, in.t, M, in.rates);
      else
        Jv = kernel_.velocityTangent(q, v, in.t, M);
      if constexpr (ObjectiveTangentKernel<Kernel>) {
        Eigen::Map<Eigen::Matrix<double, kNv, kNq>> Jq(J);
        Jq = kernel_.coordinateTangent(q, v, Vd(a + in.mass_damping * v), in.t, in.gravity, M,
                                       Eigen::Matrix<double, kNv, kNv>(Jv));
      } else {
        coordinateJacobian(in, J);
      }
      Jv += (cj + in.mass_damping) * M;
      return;
    }
    coordinateJacobian(in, J);
    for (int j = 0; j < kNv; ++j) {
      const double s = 1e-3 * (1.0 + std::abs(v(j)));
      Vd vp = v, vm = v;
      vp(j) += s, vm(j) -= s;
      Jv.col(j) = (residualAt(q, vp, a, in) - residualAt(q, vm, a, in)) / (2.0 * s);
    }
    Jv += cj * kernel_.template massMatrix<double>(q, in.t);
  }

  void coordinateJacobian(const ElementInput& in, double* J) const override {
    using D = Dual<double, kNq>;
    const Qd qd = gatherQ(in.q);
    const Vd vd = gatherV(in.v), ad = gatherV(in.a) + in.mass_damping * vd;
    if constexpr (ObjectiveTangentKernel<Kernel>) {
      Eigen::Matrix<double, kNv, kNv> M;
      const Eigen::Matrix<double, kNv, kNv> C = kernel_.velocityTangent(qd, vd, in.t, M);
      Eigen::Map<Eigen::Matrix<double, kNv, kNq>> Jq(J);
      Jq = kernel_.coordinateTangent(qd, vd, ad, in.t, in.gravity, M, C);
      return;
    } else if constexpr (CoordinateTangentKernel<Kernel>) {
      Eigen::Map<Eigen::Matrix<double, kNv, kNq>> Jq(J);
      if constexpr (TimeDependentKernel<Kernel>)
        Jq = kernel_.coordinateTangent(qd, vd, ad, in.t, in.gravity, in.rates);
      else
        Jq = kernel_.coordinateTangent(qd, vd, ad, in.t, in.gravity);
      return;
    } else {
      Eigen::Matrix<D, kNq, 1> q;
      for (int k = 0; k < kNq; ++k) q(k) = seeded<double, kNq>(qd(k), k);
      const Eigen::Matrix<D, kNv, 1> v = vd.template cast<D>(), a = ad.template cast<D>();
      Eigen::Matrix<D, kNv, 1> r;
      if constexpr (FusedResidualKernel<Kernel>)
        r = kernel_.template residual<D>(q, v, a, in.t, in.gravity);
      else
        r = kernel_.template massMatrix<D>(q, in.t) * a + forceAt<D>(q, v, in);
      storeDerivatives(r, J);
    }
  }

  void mass(const ElementInput& in, double* M) const override {
    Eigen::Map<Eigen::Matrix<double, kNv, kNv>> out(M);
    out = kernel_.template massMatrix<double>(gatherQ(in.q), in.t);
  }

  double kineticEnergy(const ElementInput& in) const override {
    return kernel_.kineticEnergy(gatherQ(in.q), gatherV(in.v), in.t);
  }
  double potentialEnergy(const ElementInput& in) const override {
    return kernel_.potentialEnergy(gatherQ(in.q), in.t, in.gravity);
  }

  double explicitTimePower(const ElementInput& in) const override {
    if constexpr (TimeDependentKernel<Kernel>)
      return kernel_.explicitTimePower(gatherQ(in.q), gatherV(in.v), in.t, in.gravity);
    else
      return 0.0;
  }

  /// By the kernel, or for damping linear in dq, dqᵀ D dq: from the kernel's damping forces, or
  /// by polarization: the terms of F even in dq (elastic, gravity, inertial) cancel in
  /// F(q, dq) − F(q, −dq), which leaves 2 D dq.
  bool sectionForces(const ElementInput& in, double* out) const override {
    if constexpr (SectionForceKernel<Kernel>) {
      Eigen::Map<Eigen::Matrix<double, 12, 1>> forces(out);
      forces = kernel_.sectionForces(gatherQ(in.q), gatherV(in.v), gatherV(in.a), in.gravity);
      return true;
    }
    return false;
  }

  bool tensions(const ElementInput& in, double* out) const override {
    if constexpr (TensionKernel<Kernel>) {
      const Qd q = gatherQ(in.q);
      for (int i = 0; i < kTensionPoints; ++i) out[i] = kernel_.tension(q, in.t, static_cast<double>(i) / (kTensionPoints - 1));
      return true;
    }
    return false;
  }

  double dissipatedPower(const ElementInput& in) const override {
    if constexpr (DissipationKernel<Kernel>) {
      return kernel_.dissipatedPower(gatherQ(in.q), gatherV(in.v), in.t, in.gravity);
    } else if constexpr (LinearlyDampedKernel<Kernel>) {
      if (!kernel_.damped()) return 0.0;
      const Qd q = gatherQ(in.q);
      const Vd v = gatherV(in.v);
      if constexpr (DampingForceKernel<Kernel>) return v.dot(kernel_.template dampingForce<double>(q, v));
      return 0.5 * v.dot(kernel_.template force<double>(q, v, in.t, in.gravity) -
                         kernel_.template force<double>(q, Vd(-v), in.t, in.gravity));
    } else {
      return 0.0;
    }
  }

 private:
  /// M(q) (a + α dq) + F(q, dq, t), α = in.mass_damping.
  Vd residualAt(const Qd& q, const Vd& v, const Vd& a, const ElementInput& in) const {
    const Vd acc = a + in.mass_damping * v;
    if constexpr (FusedResidualKernel<Kernel>)
      return kernel_.template residual<double>(q, v, acc, in.t, in.gravity);
    else
      return kernel_.template massMatrix<double>(q, in.t) * acc + forceAt<double>(q, v, in);
  }

  template <class S>
  Eigen::Matrix<S, kNv, 1> forceAt(const Eigen::Matrix<S, kNq, 1>& q, const Eigen::Matrix<S, kNv, 1>& v,
                                   const ElementInput& in) const {
    if constexpr (TimeDependentKernel<Kernel>)
      return kernel_.template force<S>(q, v, in.t, in.gravity, in.rates);
    else
      return kernel_.template force<S>(q, v, in.t, in.gravity);
  }

  template <class R> static void storeDerivatives(const R& r, double* J) {
    Eigen::Map<Eigen::Matrix<double, kNv, kNq>> Jm(J);
    for (int i = 0; i < kNv; ++i) Jm.row(i) = r(i).derivatives().transpose();
  }
  Qd gatherQ(const double* x) const {
    Qd out;
    for (int k = 0; k < kNq; ++k) out(k) = x[q_[k]];
    return out;
  }
  Vd gatherV(const double* x) const {
    Vd out;
    for (int k = 0; k < kNv; ++k) out(k) = x[v_[k]];
    return out;
  }

  Kernel kernel_;
  std::vector<int> nodes_, q_, v_;
};

}  // namespace cranesim
