// The 12-DOF truss elements on the thesis' type 2 section: the super truss (thesis 3.5,
// super_truss.hpp) and the condensed truss (condensed_truss.hpp). Both: exact rigid-body mass
// properties, objectivity of the elastic forces, forces as energy gradients, AD Jacobian, energy
// consistency of the inertial forces. Super truss: node kinematics. Condensed truss: the
// condensed stiffness' rigid modes and its linear limit.

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <type_traits>

#include "cranesim/elements/condensed_truss.hpp"
#include "cranesim/elements/super_truss.hpp"
#include "cranesim/model/kernel_elements.hpp"
#include "element_differences.hpp"
#include "random_states.hpp"

using namespace cranesim;

namespace {

using Q12 = Eigen::Matrix<double, 12, 1>;
using M12 = Eigen::Matrix<double, 12, 12>;

TrussTube tube(double outer, double inner) {
  TrussTube t;
  t.outer_radius = outer, t.inner_radius = inner;
  return t;
}

TrussNodePair pair(int a, int b) {
  TrussNodePair p;
  p.nodes = {a, b};
  return p;
}

/// The thesis' type 2 section (Table D-3, radii; E = 2.06e11, docs/thesis-crane.md).
TrussDescription type2() {
  TrussDescription d;
  d.name = "type2";
  d.length = 15.0;
  d.order = 6;
  for (auto& s : d.sections) {
    s.nodes = {{1.5, 1.4}, {-1.5, 1.4}, {-1.5, -1.4}, {1.5, -1.4}};
    s.cross_beams = {pair(0, 1), pair(1, 2), pair(2, 3), pair(3, 0)};
  }
  d.main_beams = {pair(0, 0), pair(1, 1), pair(2, 2), pair(3, 3)};
  d.lacing = LacingForm::Type1;
  d.main_tube = d.cross_tube = tube(0.1, 0.08);
  d.sub_tube = tube(0.05, 0.04);
  d.poisson_ratio = 0.25;
  d.material.density = 7800.0;
  d.material.youngs_modulus = 2.06e11;
  d.material.shear_modulus = 2.06e11 / 2.5;
  return d;
}

std::vector<int> range(int n) {
  std::vector<int> v(n);
  for (int i = 0; i < n; ++i) v[i] = i;
  return v;
}

using test::Rng;

Q12 coordinates(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2) {
  Q12 q;
  q << r1, rotationVector(R1), r2, rotationVector(R2);
  return q;
}

/// The undeformed truss placed by (r0, R0) (section 1 at r0).
Q12 rigidPlacement(double L, const Vec3& r0, const Mat3& R0) { return coordinates(r0, R0, r0 + L * R0.col(0), R0); }

/// A placed and deformed truss: section 2 displaced by ~`size` m and turned by ~`size` rad
/// relative to section 1 (bending, torsion, stretch together).
Q12 deformedState(Rng& rng, double L, double size) {
  const Vec3 r1 = rng.vec(5.0);
  const Mat3 R1 = rng.rotation(3.0);
  return coordinates(r1, R1, r1 + R1 * (L * Vec3::UnitX() + rng.vec(size)), R1 * rng.rotation(size));
}

/// q moved by the twist δ: r + δr, R exp(δθ̃).
Q12 twisted(const Q12& q, const Q12& delta) {
  Q12 p = q;
  for (int e = 0; e < 2; ++e) {
    p.segment<3>(6 * e) += delta.segment<3>(6 * e);
    p.segment<3>(6 * e + 3) = rotationVector(rotationMatrix<double>(Vec3(q.segment<3>(6 * e + 3))) *
                                             rotationMatrix<double>(Vec3(delta.segment<3>(6 * e + 3))));
  }
  return p;
}

/// dq of the rigid motion with origin velocity u and inertial angular velocity Ω.
Q12 rigidVelocity(const Q12& q, const Vec3& u, const Vec3& Omega) {
  Q12 v;
  for (int e = 0; e < 2; ++e) {
    v.segment<3>(6 * e) = u + Omega.cross(Vec3(q.segment<3>(6 * e)));
    v.segment<3>(6 * e + 3) = rotationMatrix<double>(Vec3(q.segment<3>(6 * e + 3))).transpose() * Omega;
  }
  return v;
}

/// Mass, centre and inertia tensor about the centre of the tubes as rigid thick-walled cylinders.
struct MassProperties {
  double mass = 0.0;
  Vec3 centre = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
};

MassProperties tubeMassProperties(const TrussGeometry& g) {
  MassProperties p;
  Vec3 first = Vec3::Zero();
  Mat3 about_origin = Mat3::Zero();
  for (const TrussMember& m : g.members) {
    const Vec3 a = g.nodes[m.node1].position, b = g.nodes[m.node2].position, x = (b - a).normalized();
    const double L = (b - a).norm(), mass = g.material.density * m.section.area * L;
    const double r2 = m.section.outer_radius * m.section.outer_radius + m.section.inner_radius * m.section.inner_radius;
    const Mat3 axial = x * x.transpose();
    const Mat3 own = mass * r2 / 2.0 * axial + mass * (3.0 * r2 + L * L) / 12.0 * (Mat3::Identity() - axial);
    const Vec3 c = 0.5 * (a + b);
    p.mass += mass;
    first += mass * c;
    about_origin += own + mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
  }
  p.centre = first / p.mass;
  p.inertia = about_origin - p.mass * (p.centre.squaredNorm() * Mat3::Identity() - p.centre * p.centre.transpose());
  return p;
}

const TrussGeometry& type2Geometry() {
  static const TrussGeometry g = buildTrussGeometry(type2());
  return g;
}

/// The thesis' type 1 transition piece (Table D-3): 2 nodes at end section 1, 4 at end section 2,
/// inclined chords, triangular faces (lacing tp_type1).
const TrussGeometry& transitionGeometry() {
  static const TrussGeometry g = [] {
    TrussDescription d = type2();
    d.name = "type1";
    d.length = 5.0;
    d.order = 3;
    d.sections[0].nodes = {{1.5, 0.0}, {-1.5, 0.0}};
    d.sections[0].cross_beams = {pair(0, 1)};
    d.main_beams = {pair(0, 0), pair(1, 1), pair(1, 2), pair(0, 3)};
    d.lacing = LacingForm::TPType1;
    return buildTrussGeometry(d);
  }();
  return g;
}

/// The kernel on a truss with its default quadrature and Kelvin–Voigt time η.
template <class Kernel> Kernel kernelOn(const TrussGeometry& g, double damping = 0.0) {
  if constexpr (std::is_same_v<Kernel, SuperTrussKernel>) return Kernel(g, 4, damping);
  else return Kernel(g, 3, damping);
}

template <class Kernel> Kernel type2Kernel(double damping = 0.0) { return kernelOn<Kernel>(type2Geometry(), damping); }

}  // namespace

TEST_CASE("Super truss: node velocity maps are the derivatives of the node frames", "[super_truss]") {
  const SuperTrussKernel k(type2Geometry());
  Rng rng(3);
  const Q12 q = deformedState(rng, k.length, 0.15);
  const double h = 1e-6;
  for (int n = 0; n < static_cast<int>(k.nodes.size()); ++n) {
    const auto s = k.template nodeState<double>(SuperTrussKernel::sectionFrames<double>(q), k.nodes[n]);
    Eigen::Matrix<double, 6, 12> fd;
    for (int j = 0; j < 12; ++j) {
      const Q12 e = Q12::Unit(j);
      const Frame p = k.nodeFrame(twisted(q, h * e), n), m = k.nodeFrame(twisted(q, -h * e), n);
      fd.col(j) << (p.r - m.r) / (2.0 * h), unskew(Mat3(s.R.transpose() * (p.R - m.R) / (2.0 * h)));
    }
    INFO("node " << n);
    CHECK((fd - s.map).norm() < 1e-6 * (1.0 + s.map.norm()));
  }
}

TEMPLATE_TEST_CASE("Truss elements: mass matrix SPD with the tubes' exact rigid-body mass properties (type 2, transition piece)", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  const bool transition = GENERATE(false, true);  // type 2, or the type 1 transition piece
  const TrussGeometry& g = transition ? transitionGeometry() : type2Geometry();
  const TestType k = kernelOn<TestType>(g);
  const MassProperties p = tubeMassProperties(g);
  INFO((transition ? "transition piece" : "type 2"));
  CHECK(k.mass() == Approx(p.mass).epsilon(1e-12));
  Rng rng(7);
  for (int trial = 0; trial < 3; ++trial) {
    const Vec3 r0 = rng.vec(10.0);
    const Mat3 R0 = trial == 0 ? axisAngle(Vec3(1.0, 1.0, 0.0), std::numbers::pi) : rng.rotation(3.0);
    const Q12 q = rigidPlacement(k.length, r0, R0);
    const M12 M = k.template massMatrix<double>(q);
    CHECK((M - M.transpose()).norm() < 1e-12 * M.norm());
    CHECK(Eigen::SelfAdjointEigenSolver<M12>(M).eigenvalues().minCoeff() > 0.0);
    const Vec3 u = rng.vec(2.0), Omega = rng.vec(1.5);
    const Vec3 c = r0 + R0 * p.centre;  // centre of mass in space
    const Q12 v = rigidVelocity(q, u, Omega);
    const Vec3 vc = u + Omega.cross(c);
    const double expected = 0.5 * p.mass * vc.squaredNorm() + 0.5 * Omega.dot(R0 * p.inertia * R0.transpose() * Omega);
    INFO("trial " << trial);
    CHECK(0.5 * v.dot(M * v) == Approx(expected).epsilon(1e-11));
    // Inertia about the truss axis through the centre of mass alone.
    const Vec3 axis = R0.col(0);
    const Q12 spin = rigidVelocity(q, -axis.cross(c), axis);
    CHECK(0.5 * spin.dot(M * spin) == Approx(0.5 * p.inertia(0, 0)).epsilon(1e-11));
  }
}

TEMPLATE_TEST_CASE("Truss elements: the mass matrix is the fused residual's acceleration columns at deformed states", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  // massMatrix (section_mass_matrix.hpp: station sums in the axes of end 1) against M e_k =
  // (r(q, dq, s e_k) − r(q, dq, 0)) / s of the residual (section_inertia_forces.hpp, linear in
  // the accelerations), with end rotations up to ~1 rad apart; type 2 and the transition piece.
  // s = 10⁸ keeps the elastic forces of these large deformations (~10⁶ × M) from cancelling.
  const Vec3 g(0.3, -0.2, -9.81);
  Rng rng(41);
  double worst = 0.0;
  for (const TrussGeometry* geometry : {&type2Geometry(), &transitionGeometry()}) {
    const TestType k = kernelOn<TestType>(*geometry, 0.02);
    for (int trial = 0; trial < 3; ++trial) {
      const Q12 q = deformedState(rng, k.length, 0.4 * (trial + 1)), v = 2.0 * Q12::Random();
      const Q12 r0 = k.template residual<double>(q, v, Q12::Zero(), 0.0, g);
      M12 columns;
      const double scale = 1e8;
      for (int c = 0; c < 12; ++c)
        columns.col(c) = (k.template residual<double>(q, v, Q12(scale * Q12::Unit(c)), 0.0, g) - r0) / scale;
      const M12 M = k.template massMatrix<double>(q);
      worst = std::max(worst, (M - columns).norm() / M.norm());
      CHECK((M - M.transpose()).norm() < 1e-13 * M.norm());
    }
  }
  std::printf("[truss] mass matrix vs the residual's acceleration columns: rel. err %.3g\n", worst);
  CHECK(worst < 1e-12);
}

TEMPLATE_TEST_CASE("Truss elements: no elastic force under rigid placements and rigid velocities", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  const TestType k = type2Kernel<TestType>(0.01);  // with Kelvin–Voigt damping
  Rng rng(11);
  Q12 q = deformedState(rng, k.length, 0.05);
  const double typical = k.template elasticForce<double>(q, Q12::Zero()).norm();  // 5 cm / 0.05 rad deformation
  for (int trial = 0; trial < 4; ++trial) {
    const Mat3 R0 = trial == 0 ? axisAngle(Vec3(0.0, 0.0, 1.0), std::numbers::pi) : rng.rotation(3.1);
    q = rigidPlacement(k.length, rng.vec(20.0), R0);
    const Q12 v = rigidVelocity(q, rng.vec(3.0), rng.vec(2.0));
    INFO("trial " << trial << ", typical force " << typical);
    CHECK(k.template elasticForce<double>(q, v).norm() < 1e-12 * typical);
    CHECK(k.strainEnergy(q) < 1e-12);
  }
}

TEMPLATE_TEST_CASE("Truss elements: elastic force is the twist gradient of the strain energy", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  const TestType k = type2Kernel<TestType>();
  Rng rng(5);
  const Q12 q = deformedState(rng, k.length, 0.1);
  const Q12 F = k.template elasticForce<double>(q, Q12::Zero());
  Q12 fd;
  for (int j = 0; j < 12; ++j) {
    const double h = j % 6 < 3 ? 1e-6 : 1e-7;
    fd(j) = (k.strainEnergy(twisted(q, h * Q12::Unit(j))) - k.strainEnergy(twisted(q, -h * Q12::Unit(j)))) / (2.0 * h);
  }
  INFO("F = " << F.transpose() << "\nfd = " << fd.transpose());
  CHECK((F - fd).norm() < 1e-6 * F.norm());
}

TEMPLATE_TEST_CASE("Truss elements: AD Jacobian matches finite differences", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  const TestType k = type2Kernel<TestType>(0.02);
  Rng rng(13);
  const Q12 q = deformedState(rng, k.length, 0.05);
  const Q12 v = rng.vec(1.0).replicate<4, 1>() + Q12::Random();
  const Q12 a = Q12::Random();
  const std::unique_ptr<Element> el = makeElement(k, {0, 1}, range(12), range(12));
  const Vec3 gravity(0.0, 0.0, -9.81);
  const double cj = 3.0;
  auto residual = [&](const Q12& qq, const Q12& vv) {
    Q12 r;
    const ElementInput in{qq.data(), vv.data(), a.data(), 0.0, gravity};
    el->residual(in, r.data());
    return r;
  };
  const ElementInput in{q.data(), v.data(), a.data(), 0.0, gravity};
  Eigen::Matrix<double, 12, 24> J;
  el->jacobian(in, cj, J.data());
  Eigen::Matrix<double, 12, 24> fd;
  for (int j = 0; j < 12; ++j) {
    const double h = 1e-6;
    const Q12 e = Q12::Unit(j);
    fd.col(j) = (residual(q + h * e, v) - residual(q - h * e, v)) / (2.0 * h);
    fd.col(12 + j) = (residual(q, v + h * e) - residual(q, v - h * e)) / (2.0 * h);
  }
  M12 M;
  el->mass(in, M.data());
  fd.rightCols<12>() += cj * M;
  for (int j = 0; j < 24; ++j) {
    INFO("column " << j);
    CHECK((J.col(j) - fd.col(j)).norm() < 1e-5 * (1.0 + fd.col(j).norm()));
  }
}

TEMPLATE_TEST_CASE("Truss elements: the closed-form velocity columns of the Jacobian equal forward AD to rounding", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  // velocityTangent (section_inertia_tangent.hpp) against ∂r/∂dq by forward AD in 12 directions,
  // at deformed, fast-turning states (the twist bracket terms grow with ω), with damping and the
  // relaxation's mass damping α M dq.
  const TestType k = type2Kernel<TestType>(0.02);
  const std::unique_ptr<Element> el = makeElement(k, {0, 1}, range(12), range(12));
  const Vec3 g(0.1, 0.2, -9.81);
  using D = Dual<double, 12>;
  Rng rng(23);
  double worst = 0.0, worst_q = 0.0;
  for (int trial = 0; trial < 4; ++trial) {
    const Q12 q = deformedState(rng, k.length, 0.05);
    const Q12 v = 5.0 * (rng.vec(1.0).replicate<4, 1>() + Q12::Random()), a = 50.0 * Q12::Random();
    const double alpha = trial % 2 ? 0.7 : 0.0, cj = 11.0;
    ElementInput in{q.data(), v.data(), a.data(), 0.0, g};
    in.mass_damping = alpha;
    Eigen::Matrix<double, 12, 24> J;
    el->jacobian(in, cj, J.data());
    Eigen::Matrix<D, 12, 1> vd;
    for (int i = 0; i < 12; ++i) vd(i) = seeded<double, 12>(v(i), i);
    const Eigen::Matrix<D, 12, 1> r = k.template residual<D>(q.cast<D>(), vd, Eigen::Matrix<D, 12, 1>(a.cast<D>() + vd * D(alpha)), 0.0, g);
    M12 Jad;
    for (int i = 0; i < 12; ++i) Jad.row(i) = r(i).derivatives().transpose();
    Jad += cj * k.template massMatrix<double>(q);
    worst = std::max(worst, (J.rightCols<12>() - Jad).norm() / Jad.norm());
    // The coordinate columns (the condensed truss splits them: inertia in the rotation
    // directions only) against forward AD of the whole residual in all twelve.
    Eigen::Matrix<D, 12, 1> qd;
    for (int i = 0; i < 12; ++i) qd(i) = seeded<double, 12>(q(i), i);
    const Eigen::Matrix<D, 12, 1> rq = k.template residual<D>(qd, v.cast<D>(), Eigen::Matrix<D, 12, 1>((a + alpha * v).cast<D>()), 0.0, g);
    for (int i = 0; i < 12; ++i) Jad.row(i) = rq(i).derivatives().transpose();
    worst_q = std::max(worst_q, (J.leftCols<12>() - Jad).norm() / Jad.norm());
  }
  std::printf("[truss] closed-form ∂r/∂dq vs forward AD: rel. err %.3g; ∂r/∂q: %.3g\n", worst, worst_q);
  CHECK(worst < 1e-12);
  CHECK(worst_q < 1e-12);
}

TEMPLATE_TEST_CASE("Truss elements: the coordinate columns by frame indifference equal forward AD, inertia dominating", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  // The DAE Jacobian's ∂r/∂q from end 2's six columns (objective_tangent.hpp) against forward AD
  // of the whole residual in all twelve, column block by column block, on tubes a million times
  // softer than steel so that the inertial, gravity and damping terms of the rigid-rotation
  // columns are not hidden under the stiffness; type 2 and the transition piece (inclined
  // chords), large end rotations, fast turning, mass damping.
  const Vec3 g(1.5, -2.0, -9.81);
  Rng rng(31);
  double worst = 0.0;
  for (const TrussGeometry* base : {&type2Geometry(), &transitionGeometry()}) {
    TrussGeometry soft = *base;
    soft.material.youngs_modulus *= 1e-6;
    soft.material.shear_modulus *= 1e-6;
    const TestType k = kernelOn<TestType>(soft, 0.05);
    const std::unique_ptr<Element> el = makeElement(k, {0, 1}, range(12), range(12));
    for (int trial = 0; trial < 3; ++trial) {
      const Q12 q = deformedState(rng, k.length, 0.3);
      const Q12 v = 3.0 * (rng.vec(1.0).replicate<4, 1>() + Q12::Random()), a = 20.0 * Q12::Random();
      const double alpha = trial == 1 ? 0.0 : 0.4;
      ElementInput in{q.data(), v.data(), a.data(), 0.0, g};
      in.mass_damping = alpha;
      Eigen::Matrix<double, 12, 24> J;
      el->jacobian(in, 7.0, J.data());
      const M12 Jad = coordinateDerivative(q, [&]<class S>(const Eigen::Matrix<S, 12, 1>& qs) {
        return k.template residual<S>(qs, v.cast<S>(), Eigen::Matrix<S, 12, 1>((a + alpha * v).cast<S>()), 0.0, g);
      });
      INFO("trial " << trial);
      const double error = test::worstColumnBlockError(J.leftCols<12>(), Jad);
      CHECK(error < 1e-10);
      worst = std::max(worst, error);
    }
  }
  std::printf("[truss] frame-indifferent ∂r/∂q vs forward AD (soft tubes): rel. err %.3g\n", worst);
}

TEMPLATE_TEST_CASE("Truss elements: inertial forces do no work (dqᵀ F_ine = ½ dqᵀ Ṁ dq)", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  const TestType k = type2Kernel<TestType>();
  Rng rng(17);
  for (int trial = 0; trial < 3; ++trial) {
    const Q12 q = deformedState(rng, k.length, 0.1);
    const Q12 v = Q12::Random() * 2.0;
    const Q12 Fine = k.template force<double>(q, v, 0.0, Vec3::Zero()) - k.template elasticForce<double>(q, v);
    const double h = 1e-6;
    const M12 Mdot = (k.template massMatrix<double>(twisted(q, h * v)) - k.template massMatrix<double>(twisted(q, -h * v))) / (2.0 * h);
    const double power = v.dot(Fine), expected = 0.5 * v.dot(Mdot * v);
    INFO("trial " << trial << ": " << power << " vs " << expected);
    CHECK(power == Approx(expected).epsilon(1e-6).margin(1e-7 * v.dot(k.template massMatrix<double>(q) * v)));
  }
}

TEMPLATE_TEST_CASE("Truss elements: gravity force is the gradient of the gravity potential", "[super_truss][condensed_truss]", SuperTrussKernel, CondensedTrussKernel) {
  const TestType k = type2Kernel<TestType>();
  Rng rng(19);
  const Q12 q = deformedState(rng, k.length, 0.1);
  const Vec3 g(1.0, -2.0, -9.81);
  const Q12 F = k.template force<double>(q, Q12::Zero(), 0.0, g);  // elastic + gravity at rest
  Q12 fd;
  for (int j = 0; j < 12; ++j) {
    const double h = j % 6 < 3 ? 1e-6 : 1e-7;
    fd(j) = (k.potentialEnergy(twisted(q, h * Q12::Unit(j)), 0.0, g) - k.potentialEnergy(twisted(q, -h * Q12::Unit(j)), 0.0, g)) /
            (2.0 * h);
  }
  CHECK((F - fd).norm() < 1e-6 * F.norm());
}

TEMPLATE_TEST_CASE("Truss elements: cost of force and Jacobian per call", "[super_truss][condensed_truss][.timing]", SuperTrussKernel, CondensedTrussKernel) {
  const TestType k = type2Kernel<TestType>();
  Rng rng(23);
  const Q12 q = deformedState(rng, k.length, 0.05), v = Q12::Random(), a = Q12::Random();
  const std::unique_ptr<Element> el = makeElement(k, {0, 1}, range(12), range(12));
  const ElementInput in{q.data(), v.data(), a.data(), 0.0, Vec3(0.0, 0.0, -9.81)};
  Q12 r;
  Eigen::Matrix<double, 12, 24> J;
  using Clock = std::chrono::steady_clock;
  const int n = 1000;
  auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) el->residual(in, r.data());
  auto t1 = Clock::now();
  for (int i = 0; i < n / 10; ++i) el->jacobian(in, 1.0, J.data());
  auto t2 = Clock::now();
  std::printf("%s, type 2: residual %.1f us, jacobian %.1f us per call\n",
              std::is_same_v<TestType, SuperTrussKernel> ? "super truss" : "condensed truss",
              std::chrono::duration<double, std::micro>(t1 - t0).count() / n,
              std::chrono::duration<double, std::micro>(t2 - t1).count() / (n / 10));
  SUCCEED();
}

TEST_CASE("Condensed truss: the condensed stiffness has the six rigid modes as null space", "[condensed_truss]") {
  const CondensedTrussKernel k = type2Kernel<CondensedTrussKernel>();
  const Eigen::SelfAdjointEigenSolver<M12> eig(k.stiffness);
  const double largest = eig.eigenvalues().maxCoeff();
  INFO("eigenvalues " << eig.eigenvalues().transpose());
  CHECK(eig.eigenvalues().head<6>().cwiseAbs().maxCoeff() < 1e-14 * largest);
  CHECK(eig.eigenvalues()(6) > 1e-3 * largest);
  // The rigid modes themselves: translations and rotations about the origin of section 1.
  for (int j = 0; j < 6; ++j) {
    Q12 mode = Q12::Zero();
    const Vec3 e = Vec3::Unit(j % 3);
    if (j < 3) {
      mode.segment<3>(0) = mode.segment<3>(6) = e;
    } else {
      mode.segment<3>(3) = mode.segment<3>(9) = e;
      mode.segment<3>(6) = e.cross(Vec3(k.length, 0.0, 0.0));
    }
    CHECK((k.stiffness * mode).norm() < 1e-12 * largest);
  }
}

TEST_CASE("Condensed truss: its linearisation at any rigid placement is the condensed stiffness", "[condensed_truss]") {
  const CondensedTrussKernel k = type2Kernel<CondensedTrussKernel>();
  Rng rng(29);
  for (int trial = 0; trial < 3; ++trial) {
    const Mat3 R0 = trial == 0 ? Mat3::Identity() : rng.rotation(3.0);
    const Q12 q = rigidPlacement(k.length, rng.vec(10.0), R0);
    M12 K;
    for (int j = 0; j < 12; ++j) {
      const double h = j % 6 < 3 ? 1e-7 : 1e-8;
      K.col(j) = (k.template elasticForce<double>(twisted(q, h * Q12::Unit(j)), Q12::Zero()) -
                  k.template elasticForce<double>(twisted(q, -h * Q12::Unit(j)), Q12::Zero())) /
                 (2.0 * h);
    }
    // Twist [δr, δθ]: δr inertial, δθ in the section frames (truss axes). The truss-axes
    // displacements are R0ᵀ δr, so K_twist = T K_red Tᵀ with T = diag(R0, I, R0, I).
    M12 T = M12::Identity();
    T.block<3, 3>(0, 0) = T.block<3, 3>(6, 6) = R0;
    INFO("trial " << trial);
    CHECK((K - T * k.stiffness * T.transpose()).norm() < 1e-6 * k.stiffness.norm());
  }
}
