// Strut tie (3.2), cubic spline rope (7.2.1, C.5) and two-node cable kernels: mass, elastic
// forces against the strain energy, Jacobians against finite differences, energy consistency,
// tension-only behaviour, and the rope against the elastic catenary.

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <numbers>
#include <random>

#include "cranesim/elements/cable.hpp"
#include "cranesim/elements/parts/quadratic_velocity.hpp"
#include "cranesim/elements/spline_rope.hpp"
#include "cranesim/elements/strut_tie.hpp"
#include "cranesim/model/kernel_elements.hpp"
#include "cranesim/solvers/statics.hpp"
#include "elastic_catenary.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kSteelE = 2.06e11;

Material steel() { return {7800.0, kSteelE, kSteelE / 2.5}; }

StrutTieKernel strut(bool constant_volume, double smoothing) {
  StrutTieKernel k;
  k.length = 2.0;
  k.section = Section::circular(0.05, 0.04, 0.25);
  k.material = steel();
  k.constant_volume = constant_volume;
  k.smoothing = smoothing;
  return k;
}

SplineRopeKernel rope(double length) {
  SplineRopeKernel k;
  k.total_length = Profile(ConstantProfile{length});
  k.section = Section::circular(0.01, 0.0, 0.3);
  k.material = {7800.0, 1.0e11, 4.0e10};
  return k;
}

template <class Kernel> using Vq = Eigen::Matrix<double, Kernel::kNq, 1>;

/// Central differences of the element residual against KernelElement's AD Jacobian.
template <class Kernel> double jacobianDeviation(const Kernel& kernel, const Vq<Kernel>& q, const Vq<Kernel>& v,
                                                 const Vq<Kernel>& a) {
  constexpr int n = Kernel::kNq;
  std::vector<int> idx(n);
  for (int k = 0; k < n; ++k) idx[k] = k;
  const std::unique_ptr<Element> element = makeElement(kernel, {}, idx, idx);
  const Vec3 g(0, 0, -9.81);
  const double cj = 7.0, t = 0.3;
  Eigen::Matrix<double, n, 2 * n> J;
  element->jacobian({q.data(), v.data(), a.data(), t, g}, cj, J.data());
  double worst = 0.0, scale = J.cwiseAbs().maxCoeff();
  for (int c = 0; c < 2 * n; ++c) {
    const double h = 1e-7 * (1.0 + (c < n ? std::abs(q(c)) : std::abs(v(c - n))));
    Vq<Kernel> qp = q, qm = q, vp = v, vm = v;
    if (c < n) qp(c) += h, qm(c) -= h;
    else vp(c - n) += h, vm(c - n) -= h;
    Vq<Kernel> rp, rm;
    element->residual({qp.data(), vp.data(), a.data(), t, g}, rp.data());
    element->residual({qm.data(), vm.data(), a.data(), t, g}, rm.data());
    Vq<Kernel> fd = (rp - rm) / (2 * h);
    if (c >= n) {  // ∂/∂v + cj ∂/∂a: a enters through M
      Eigen::Matrix<double, n, n> M;
      element->mass({q.data(), v.data(), a.data(), t, g}, M.data());
      fd += cj * M.col(c - n);
    }
    worst = std::max(worst, (J.col(c) - fd).cwiseAbs().maxCoeff());
  }
  return worst / scale;
}

}  // namespace

TEST_CASE("Strut tie: mass, rigid motion, energy gradient and Jacobians", "[elements][strut]") {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const bool constant_volume : {true, false}) {
    const StrutTieKernel k = strut(constant_volume, 0.0);
    Vq<StrutTieKernel> q;
    q << 0.1, 0.2, -0.3, 1.3, 1.2, 0.9;  // length ≈ 2.0: slightly strained
    const double l = (q.tail<3>() - q.head<3>()).norm();
    const auto M = k.massMatrix<double>(q);
    CHECK(Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(M).eigenvalues().minCoeff() > 0.0);
    CHECK(M.sum() == Approx(3.0 * k.material.density * k.section.area * k.length).epsilon(1e-12));  // translation: m
    // Elastic force = gradient of the strain energy (no gravity, at rest).
    const Vec3 zero = Vec3::Zero();
    const auto F = k.force<double>(q, Vq<StrutTieKernel>::Zero(), 0.0, zero);
    for (int i = 0; i < 6; ++i) {
      const double h = 1e-7;
      Vq<StrutTieKernel> qp = q, qm = q;
      qp(i) += h, qm(i) -= h;
      CHECK(F(i) == Approx((k.potentialEnergy(qp, 0.0, zero) - k.potentialEnergy(qm, 0.0, zero)) / (2 * h)).epsilon(1e-6));
    }
    // The axial force of the constant-volume rod: E A L/ℓ · ε.
    const double eps = l / k.length - 1.0, EA = kSteelE * k.section.area;
    const Vec3 e = (q.tail<3>() - q.head<3>()) / l;
    CHECK(F.tail<3>().dot(e) == Approx(constant_volume ? EA * eps * k.length / l : EA * eps).epsilon(1e-9));
    // Unstrained and moving rigidly (translation + rotation about the centre): no elastic force;
    // the remaining force is the centripetal inertia of the rotary mass, energy-consistent.
    Vq<StrutTieKernel> q0;
    q0 << 0, 0, 0, 2, 0, 0;
    Vq<StrutTieKernel> v0;
    v0 << 0.3, -1.0, 0.2, 0.3, 1.0, 0.2;
    const auto F0 = k.force<double>(q0, v0, 0.0, zero);
    CHECK(F0.head<3>().dot(Vec3::UnitX()) == Approx(-F0.tail<3>().dot(Vec3::UnitX())));
    CHECK(std::abs(F0.dot(v0)) < 1e-12);  // rigid rotation: no power
    Vq<StrutTieKernel> v, a;
    for (int i = 0; i < 6; ++i) v(i) = u(rng), a(i) = u(rng);
    CHECK(jacobianDeviation(k, q, v, a) < 1e-6);
  }
  const StrutTieKernel smoothed = strut(true, 1e-3);
  Vq<StrutTieKernel> q, v, a;
  q << 0.1, 0.2, -0.3, 1.3, 1.2, 0.9;
  for (int i = 0; i < 6; ++i) v(i) = u(rng), a(i) = u(rng);
  CHECK(jacobianDeviation(smoothed, q, v, a) < 1e-6);
}

TEST_CASE("Strut tie: closed-form rotary inertia forces and velocity tangent", "[elements][strut]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  using V6 = Vq<StrutTieKernel>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  const Vec3 zero = Vec3::Zero();
  // ∂F/∂dq by forward AD in the six velocity directions.
  const auto velocityAD = [&](const StrutTieKernel& k, const V6& q, const V6& v) {
    using D = Dual<double, 6>;
    Eigen::Matrix<D, 6, 1> vd;
    for (int i = 0; i < 6; ++i) vd(i) = seeded<double, 6>(v(i), i);
    const Eigen::Matrix<D, 6, 1> F = k.force<D>(q.cast<D>(), vd, 0.0, zero);
    Mat6 C;
    for (int i = 0; i < 6; ++i) C.row(i) = F(i).derivatives().transpose();
    return C;
  };
  for (int trial = 0; trial < 5; ++trial) {
    V6 q, v;
    for (int i = 0; i < 6; ++i) q(i) = u(rng), v(i) = 3.0 * u(rng);
    q.tail<3>() += Vec3(2.0, 0.0, 0.0);
    // Undamped: the velocity terms are the rotary inertia's alone, against Lagrange by AD on its
    // mass matrix (quadratic_velocity.hpp) and against AD of the closed form. Without stiffness,
    // so that F(dq) − F(0) is not the difference of two large elastic forces.
    StrutTieKernel k = strut(true, 0.0);
    k.material.youngs_modulus = 0.0;
    const V6 quadratic = k.force<double>(q, v, 0.0, zero) - k.force<double>(q, V6::Zero(), 0.0, zero);
    const V6 lagrange = quadraticVelocityForces<6, double>([&](const auto& x) { return k.massMatrix(x); }, q, v);
    CHECK((quadratic - lagrange).cwiseAbs().maxCoeff() < 1e-12 * lagrange.cwiseAbs().maxCoeff());
    // Its power is ½ dqᵀ Ṁ dq (Ṁ by central differences along dq, a step large enough that the
    // translational mass' rounding does not swamp the rotary part's change).
    const double h = 1e-4;
    const Mat6 Mdot = (k.massMatrix<double>(V6(q + h * v)) - k.massMatrix<double>(V6(q - h * v))) / (2.0 * h);
    CHECK(quadratic.dot(v) == Approx(0.5 * v.dot(Mdot * v)).epsilon(1e-6));
    Mat6 M;
    Mat6 C = k.velocityTangent(q, v, 0.0, M);
    Mat6 ad = velocityAD(k, q, v);
    CHECK((C - ad).cwiseAbs().maxCoeff() < 1e-12 * ad.cwiseAbs().maxCoeff());
    CHECK((M - k.massMatrix<double>(q)).cwiseAbs().maxCoeff() == 0.0);
    // Smoothed and damped: the axial force's ε̇ and ε̈ terms too, on a soft rod so that they do
    // not hide the rotary terms.
    StrutTieKernel soft = strut(true, 2e-3);
    soft.damping = 1e-3;
    soft.material.youngs_modulus = 1e3;
    C = soft.velocityTangent(q, v, 0.0, M);
    ad = velocityAD(soft, q, v);
    CHECK((C - ad).cwiseAbs().maxCoeff() < 1e-12 * ad.cwiseAbs().maxCoeff());
    CHECK((C - velocityAD(k, q, v)).cwiseAbs().maxCoeff() > 1e-3 * ad.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("Spline rope: constant mass, tension only, energy gradient and Jacobians", "[elements][rope]") {
  const SplineRopeKernel k = rope(3.0);
  // Straight and stretched 1 %: tension EA·0.01 along the rope, equal and opposite at the ends.
  Vq<SplineRopeKernel> q;
  q << 0, 0, 0, 1.01, 0, 0, 3.03, 0, 0, 1.01, 0, 0;
  const Vec3 zero = Vec3::Zero();
  const auto F = k.force<double>(q, Vq<SplineRopeKernel>::Zero(), 0.0, zero);
  const double EA = k.material.youngs_modulus * k.section.area;
  CHECK(F(0) == Approx(-0.01 * EA).epsilon(1e-9));
  CHECK(F(6) == Approx(0.01 * EA).epsilon(1e-9));
  CHECK(k.tension(q, 0.0, 0.5) == Approx(0.01 * EA).epsilon(1e-9));
  // Compressed: no force at all (7-1).
  Vq<SplineRopeKernel> qc;
  qc << 0, 0, 0, 0.9, 0, 0, 2.7, 0, 0, 0.9, 0, 0;
  CHECK(k.force<double>(qc, Vq<SplineRopeKernel>::Zero(), 0.0, zero).norm() == 0.0);
  CHECK(k.potentialEnergy(qc, 0.0, zero) == 0.0);
  // Mass: total ρ A L for a rigid translation.
  const auto M = k.massMatrix<double>(q, 0.0);
  Vq<SplineRopeKernel> translate = Vq<SplineRopeKernel>::Zero();
  translate(0) = translate(6) = 1.0;
  CHECK(translate.dot(M * translate) == Approx(k.material.density * k.section.area * 3.0).epsilon(1e-12));
  // A general bent, stretched state.
  Vq<SplineRopeKernel> qb;
  qb << 0, 0, 0, 0.8, 0.3, -0.7, 2.9, 0.4, -0.2, 1.0, -0.2, 0.5;
  const auto Fb = k.force<double>(qb, Vq<SplineRopeKernel>::Zero(), 0.0, zero);
  for (int i = 0; i < 12; ++i) {
    const double h = 1e-7;
    Vq<SplineRopeKernel> qp = qb, qm = qb;
    qp(i) += h, qm(i) -= h;
    CHECK(Fb(i) == Approx((k.potentialEnergy(qp, 0.0, zero) - k.potentialEnergy(qm, 0.0, zero)) / (2 * h)).epsilon(1e-5).margin(1e-3));
  }
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vq<SplineRopeKernel> v, a;
  for (int i = 0; i < 12; ++i) v(i) = u(rng), a(i) = u(rng);
  CHECK(jacobianDeviation(k, qb, v, a) < 1e-6);
  // Damped and 2e-5 from slack, stretching slowly (η ε̇ ≈ 3e-6): the tension's kink
  // max(ε + η ε̇, 0) lies close, and the Jacobian's velocity columns must still be the taut
  // branch's derivative, not a secant across the kink.
  SplineRopeKernel damped = k;
  damped.damping = 1e-3;
  Vq<SplineRopeKernel> qs;
  qs << 0, 0, 0, 1.00002, 0, 0, 3.00006, 0, 0, 1.00002, 0, 0;
  const Vq<SplineRopeKernel> vs = 0.01 * v;
  CHECK(jacobianDeviation(damped, qs, vs, a) < 1e-6);
  // Snapping taut while stretching at ε̇ = 0.1/s: the damped tension EA max(ε + η ε̇, 0) is
  // continuous where ε crosses 0 (a jump of EA η ε̇ there stalled IDAS at steps of 1e-12 s).
  const auto straight = [](double strain) {
    Vq<SplineRopeKernel> qe;
    qe << 0, 0, 0, 1 + strain, 0, 0, 3 * (1 + strain), 0, 0, 1 + strain, 0, 0;
    return qe;
  };
  Vq<SplineRopeKernel> stretching = Vq<SplineRopeKernel>::Zero();
  stretching(3) = 0.1, stretching(6) = 0.3, stretching(9) = 0.1;  // ṙ'¹, ṙ², ṙ'²
  const auto taut = damped.force<double>(straight(1e-9), stretching, 0.0, zero);
  const auto slack = damped.force<double>(straight(-1e-9), stretching, 0.0, zero);
  CHECK(taut(6) == Approx(EA * 1e-4).epsilon(1e-4));
  CHECK((taut - slack).norm() < 1e-4 * taut.norm());
  CHECK(damped.force<double>(straight(-2e-4), stretching, 0.0, zero).norm() == 0.0);  // below −η ε̇: slack
  // Reeling: the mass follows the unstretched length.
  SplineRopeKernel reeled = k;
  reeled.total_length = Profile(RampProfile{3.0, -0.5, 0.0});
  CHECK(translate.dot(reeled.massMatrix<double>(q, 2.0) * translate) ==
        Approx(k.material.density * k.section.area * 2.0).epsilon(1e-12));
}

TEST_CASE("Cable: the rod's mass and inertia, tension only, energy gradient, Jacobians, reeling", "[elements][rope][cable]") {
  CableKernel k;
  k.total_length = Profile(ConstantProfile{3.0});
  k.section = Section::circular(0.01, 0.0, 0.3);
  k.material = {7800.0, 1.0e11, 4.0e10};
  const double EA = k.material.youngs_modulus * k.section.area, m = k.material.density * k.section.area * 3.0;
  using V6 = Vq<CableKernel>;
  V6 q;
  q << 0, 0, 0, 3.03, 0, 0;  // straight along x, stretched 1 %
  const Vec3 zero = Vec3::Zero();
  const auto F = k.force<double>(q, V6::Zero(), 0.0, zero);
  CHECK(F(0) == Approx(-0.01 * EA).epsilon(1e-12));
  CHECK(F(3) == Approx(0.01 * EA).epsilon(1e-12));
  CHECK(k.tension(q, 0.0) == Approx(0.01 * EA).epsilon(1e-12));
  V6 qc;
  qc << 0, 0, 0, 2.9, 0, 0;
  CHECK(k.force<double>(qc, V6::Zero(), 0.0, zero).norm() == 0.0);  // compressed: slack
  // Mass and rotary inertia of a uniform rod: m for a translation, m ℓ²/12 turning about its centre.
  const auto M = k.massMatrix<double>(q, 0.0);
  V6 translate, spin;
  translate << 1, 0, 0, 1, 0, 0;
  spin << 0, -1, 0, 0, 1, 0;  // ends moving ±1 m/s across: ω = 2/ℓ about the centre
  CHECK(translate.dot(M * translate) == Approx(m).epsilon(1e-14));
  CHECK(0.5 * spin.dot(M * spin) == Approx(0.5 * m * 3.03 * 3.03 / 12 * std::pow(2 / 3.03, 2)).epsilon(1e-12));
  // Gravity: half the weight on each node.
  const Vec3 g(0, 0, -9.81);
  CHECK(k.force<double>(qc, V6::Zero(), 0.0, g)(2) == Approx(0.5 * m * 9.81).epsilon(1e-14));
  // A general stretched state: forces = the strain energy's gradient; Jacobians by AD and polarization.
  V6 qb;
  qb << 0.1, -0.2, 0.3, 1.9, 1.6, -1.2;
  const auto Fb = k.force<double>(qb, V6::Zero(), 0.0, zero);
  for (int i = 0; i < 6; ++i) {
    const double h = 1e-7;
    V6 qp = qb, qm = qb;
    qp(i) += h, qm(i) -= h;
    CHECK(Fb(i) == Approx((k.potentialEnergy(qp, 0.0, zero) - k.potentialEnergy(qm, 0.0, zero)) / (2 * h)).epsilon(1e-6));
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  V6 v, a;
  for (int i = 0; i < 6; ++i) v(i) = u(rng), a(i) = u(rng);
  CableKernel damped = k;
  damped.damping = 1e-3;
  damped.total_length = Profile(RampProfile{3.0, -0.5, 0.0});  // reeled in at 0.5 m/s
  CHECK(jacobianDeviation(k, qb, v, a) < 1e-6);
  CHECK(jacobianDeviation(damped, qb, v, a) < 1e-6);
  // Reeled at constant stretch (ℓ/L fixed: the ends close at the reeling rate times the stretch):
  // the material does not stretch, so damping adds no tension.
  const double t = 1.0, L = 2.5, stretch = 1.01;
  V6 qr, vr = V6::Zero();
  qr << 0, 0, 0, stretch * L, 0, 0;
  vr(3) = -0.5 * stretch;
  CableKernel undamped = damped;
  undamped.damping = 0.0;
  CHECK(damped.force<double>(qr, vr, t, zero)(3) == Approx(0.01 * EA).epsilon(1e-10));
  CHECK(damped.force<double>(qr, vr, t, zero)(3) == Approx(undamped.force<double>(qr, vr, t, zero)(3)).epsilon(1e-12));
  CHECK(damped.dissipatedPower(qr, vr, t, zero) == Approx(0.0).margin(1e-9));
  // The mass follows the unstretched length: ρA L(t).
  CHECK(translate.dot(damped.massMatrix<double>(qr, t) * translate) == Approx(m * L / 3.0).epsilon(1e-14));
}

TEST_CASE("A rope hanging between two points takes the elastic catenary", "[elements][rope][statics]") {
  // Supports 20 m apart at equal height, unstretched length 22 m, steel wire r = 1 cm, soft
  // E = 1e9 so that stretch matters. Irvine's elastic catenary gives H and the sag.
  const double span = 20.0, L0 = 22.0, radius = 0.01, E = 1e9, rho = 7800.0, g = 9.81;
  const int segments = 16;
  const std::string yaml = fmt::format(R"(
name: catenary
gravity: [0, 0, {}]
ground:
  joints: [{{name: left, position: [0, 0, 0]}}, {{name: right, position: [{}, 0, 0]}}]
members:
  - {{name: rope, type: rope, start: [0, 0, 0], end: [{}, 0, 0], segments: {}, length: {},
     section: {{radius: {}}}, material: {{density: {}, youngs_modulus: {}}}}}
constraints:
  - {{name: a, type: spherical, joints: [ground.left, rope.start]}}
  - {{name: b, type: spherical, joints: [ground.right, rope.end]}}
solver: {{t_end: 1}}
)", -g, span, span, segments, L0, radius, rho, E);
  const Model model = test::loadYaml(yaml);
  // Start from a parabola of the right length: a straight slack rope has no stiffness.
  VecX q = model.q0;
  const double sag_guess = std::sqrt(3.0 * span * (L0 - span) / 8.0);
  for (const Node& n : model.nodes) {
    const double x = q(n.q);
    q(n.q + 2) = -4.0 * sag_guess * x * (span - x) / (span * span);
    const Vec3 slope(1.0, 0.0, -4.0 * sag_guess * (span - 2.0 * x) / (span * span));
    q.segment<3>(n.q + 3) = slope.normalized();
  }
  const StaticResult eq = solveStatics(model, q, 0.0);
  INFO(eq.message);
  REQUIRE(eq.converged);
  const double A = std::numbers::pi * radius * radius;
  const auto [H, sag] = test::elasticCatenary(span, L0, rho * A * g, E * A);
  const Node& mid = model.nodes[segments / 2];
  const double computed = -eq.q(mid.q + 2);
  INFO("sag: computed " << computed << " m, elastic catenary " << sag << " m; H = " << H << " N");
  CHECK(computed == Approx(sag).epsilon(1e-4));
  // Horizontal tension: the support reaction along x.
  CHECK(std::abs(eq.lambda(0)) == Approx(H).epsilon(1e-3));
}
