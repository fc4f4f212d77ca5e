// Transverse damping of the spline rope (elements/spline_rope.hpp, `transverse_damping: c`):
// the turning of the centre line against the element's chord is damped, a rope turning as a
// whole is not. Kernel level: rigid turns across the chord carry no damping force also where
// the rope sags; the force's power is the dissipated power c ∫ ‖w‖² ds, and with reeling the
// rest is booked as the winch's; the Jacobian against central differences. Scene level: a
// pendulum's swing on a damped rope keeps its energy and its balance closes, and a taut string's
// vibration decays at the first mode's damping ratio ζ₁ = c (π/ℓ) / (2 √(T ρA)).

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cranesim/elements/spline_rope.hpp"
#include "cranesim/model/kernel_elements.hpp"
#include "element_differences.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

using Q = SplineRopeKernel::Q<double>;

SplineRopeKernel dampedRope(double length, double c) {
  SplineRopeKernel k;
  k.total_length = Profile(ConstantProfile{length});
  k.section = Section::circular(0.01, 0.0, 0.3);
  k.material = {7800.0, 1.0e11, 4.0e10};
  k.transverse_damping = c;
  return k;
}

/// One 4 m element along x, stretched by 1e-3, sagging: its slopes tilted down at the start and
/// up at the end by 0.1 rad.
Q saggingElement() {
  const double s = 1.001, a = 0.1;
  Q q;
  q << Vec3::Zero(), s * Vec3(std::cos(a), 0.0, -std::sin(a)), Vec3(4.004, 0.0, 0.0), s * Vec3(std::cos(a), 0.0, std::sin(a));
  return q;
}

/// The velocities of the element's coordinates in a rigid turn ω about the origin.
Q turning(const Q& q, const Vec3& omega) {
  Q v;
  for (int k = 0; k < 4; ++k) v.segment<3>(3 * k) = omega.cross(Vec3(q.segment<3>(3 * k)));
  return v;
}

Q dampingForce(const SplineRopeKernel& k, const Q& q, const Q& v, double t = 0.0) {
  const Vec3 g = Vec3::Zero();
  return k.force<double>(q, v, t, g) - k.force<double>(q, Q::Zero(), t, g);
}

}  // namespace

TEST_CASE("Transverse damping: no force in rigid turns across the chord, power = dissipation", "[rope][energy]") {
  const SplineRopeKernel k = dampedRope(4.0, 500.0);
  const Q q = saggingElement();
  // Turns about axes across the chord (x): a pendulum's swing, a slewing crane's rope.
  for (const Vec3& omega : {Vec3(0, 0, 0.7), Vec3(0, -0.4, 0), Vec3(0, 0.3, 0.5)})
    CHECK(dampingForce(k, q, turning(q, omega)).norm() < 1e-12 * 500.0);
  // A spin about the chord turns the sag about it: damped (the one rigid motion that is).
  CHECK(dampingForce(k, q, turning(q, Vec3(0.5, 0, 0))).norm() > 1.0);
  // A sideways vibration: the first slope turning alone.
  Q v = Q::Zero();
  v.segment<3>(3) = Vec3(0.0, 0.2, 0.05);
  const Q F = dampingForce(k, q, v);
  const double dissipated = k.dissipatedPower(q, v, 0.0, Vec3::Zero());
  CHECK(dissipated > 0.0);
  CHECK(v.dot(F) == Approx(dissipated).epsilon(1e-12));
  // Twice the rate, four times the power (the force is linear in dq).
  CHECK(k.dissipatedPower(q, Q(2.0 * v), 0.0, Vec3::Zero()) == Approx(4.0 * dissipated).epsilon(1e-12));
}

TEST_CASE("Transverse damping while reeling: the winch books what the damper does not dissipate", "[rope][energy]") {
  SplineRopeKernel k = dampedRope(4.0, 500.0), undamped = dampedRope(4.0, 0.0);
  k.total_length = undamped.total_length = Profile(RampProfile{4.0, -0.6, 0.0});
  const double t = 0.5;
  const Q q = saggingElement();
  Q v = Q::Zero();
  v.segment<3>(3) = Vec3(0.0, 0.2, 0.05);
  v.segment<3>(6) = Vec3(0.1, -0.3, 0.2);
  // dqᵀF_c = P_dissipated − P_winch,c: the damper's share of dqᵀF split between the two books.
  const Vec3 g = Vec3::Zero();
  const double force_power = v.dot(k.force<double>(q, v, t, g) - undamped.force<double>(q, v, t, g));
  const double winch_share = k.explicitTimePower(q, v, t, Vec3::Zero()) - undamped.explicitTimePower(q, v, t, Vec3::Zero());
  const double dissipated = k.dissipatedPower(q, v, t, Vec3::Zero());
  CHECK(winch_share != 0.0);
  CHECK(force_power == Approx(dissipated - winch_share).epsilon(1e-10));
}

TEST_CASE("Transverse damping: the element Jacobian against central differences", "[rope][jacobian]") {
  const SplineRopeKernel k = dampedRope(4.0, 800.0);
  const Q q = saggingElement();
  Q v;
  v << 0.1, -0.2, 0.3, 0.05, 0.1, -0.02, -0.2, 0.1, 0.4, 0.03, -0.05, 0.1;
  std::vector<int> idx(12);
  for (int i = 0; i < 12; ++i) idx[i] = i;
  const std::unique_ptr<Element> element = makeElement(k, {}, idx, idx);
  const Q a = Q::Zero();
  const Vec3 g(0, 0, -9.81);
  const double cj = 5.0;
  Eigen::Matrix<double, 12, 24> J;
  const ElementInput in{q.data(), v.data(), a.data(), 0.0, g};
  element->jacobian(in, cj, J.data());
  const Eigen::Matrix<double, 12, 24> fd = test::centralDifferenceJacobian(*element, in, cj);
  CHECK((J - fd).cwiseAbs().maxCoeff() < 1e-6 * J.cwiseAbs().maxCoeff());
}

TEST_CASE("A pendulum's swing on a transversely damped rope is not damped, the balance closes", "[rope][energy][scenes]") {
  Scene damped = test::loadScene("rope_pendulum.yaml"), plain = damped;
  for (Scene* s : {&damped, &plain}) {
    s->solver.t_end = 3.3;  // half a swing
    s->solver.rtol = 1e-9;
    s->solver.atol = AbsoluteTolerance::uniform(1e-11);
  }
  damped.members[0].segments = plain.members[0].segments = 1;
  damped.members[0].transverse_damping = 2000.0;  // ζ₁ ≈ 0.5 for the rope's own sideways modes
  const test::SimulationRun a(damped), b(plain);
  REQUIRE(a.outcome.complete);
  REQUIRE(b.outcome.complete);
  const auto& xa = a.jointPositions("ball.origin");
  const auto& xb = b.jointPositions("ball.origin");
  // The ball's swing: the same to a millimetre on a 10 m pendulum, and the damper takes less than
  // 1e-4 of the swing's energy m g ℓ (1 − cos 30°) (it damps the rope's own sideways ringing).
  double worst = 0.0;
  for (std::size_t k = 0; k < xa.size(); ++k) worst = std::max(worst, std::abs(xa[k] - xb[k]));
  const double swing = 1000.0 * 9.81 * 10.0 * (1.0 - std::cos(std::numbers::pi / 6.0));
  INFO("largest difference of the ball's path " << worst << " m; dissipated " << a.recorder.dissipated().back() << " J");
  CHECK(worst < 1e-3);
  CHECK(a.recorder.dissipated().back() < 1e-4 * swing);
  CHECK(a.recorder.relativeBalanceDrift() < 1e-6);
}

TEST_CASE("A taut string's vibration decays at the first mode's damping ratio", "[rope][energy][scenes]") {
  // A 10 m steel rope (r = 1 cm), one element, between two fixed points, pretensioned by its
  // unstretched length (T = EA ε), released straight under a sideways gravity of 1 m/s²: the load
  // has the parabolic shape of the element's symmetric (first) mode, so it swings about its sag
  // in that mode alone.
  const double L = 10.0, EA = 1e11 * std::numbers::pi * 1e-4, rhoA = 7800.0 * std::numbers::pi * 1e-4;
  const double eps = 1e-3, T = EA * eps, c = 60.0;
  const double omega1 = std::numbers::pi / L * std::sqrt(T / rhoA);
  const double zeta1 = c * (std::numbers::pi / L) / (2.0 * std::sqrt(T * rhoA));
  Scene scene = parseScene(fmt::format(R"(name: taut string
gravity: [0, 1, 0]
ground:
  joints: [{{name: a}}, {{name: b, position: [{L}, 0, 0]}}]
members:
  - {{name: string, type: rope, start: [0, 0, 0], end: [{L}, 0, 0], length: {length:.17g},
     section: {{radius: 0.01}}, material: {{density: 7800, youngs_modulus: 1.0e11}}, transverse_damping: {c}}}
constraints:
  - {{name: left, type: spherical, joints: [ground.a, string.start]}}
  - {{name: right, type: spherical, joints: [ground.b, string.end]}}
solver: {{t_end: 4, rtol: 1.0e-9, atol: 1.0e-12}}
output: {{interval: 0.002}}
)",
                                       fmt::arg("L", L), fmt::arg("length", L / (1.0 + eps)), fmt::arg("c", c)),
                           "<test>");
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  // The energy of the swing about the sag, E = T + V − V_sag (V_sag: the last sample's, the swing
  // then 1e-4 of its start), decays as e^{−2ζ₁ω₁t}.
  const auto& t = run.recorder.time();
  const double settled = run.recorder.potentialEnergy().back();
  const auto energy = [&](double at) {
    std::size_t k = 0;
    while (t[k] < at) ++k;
    return run.recorder.kineticEnergy()[k] + run.recorder.potentialEnergy()[k] - settled;
  };
  const double t1 = 0.2, t2 = 1.2;
  const double measured = std::log(energy(t1) / energy(t2)) / (2.0 * omega1 * (t2 - t1));
  INFO("ζ₁ measured " << measured << ", predicted " << zeta1 << " (ω₁ = " << omega1 << " rad/s); balance drift "
                      << run.recorder.relativeBalanceDrift());
  CHECK(measured == Approx(zeta1).epsilon(0.05));
  CHECK(run.recorder.relativeBalanceDrift() < 1e-6);
}
