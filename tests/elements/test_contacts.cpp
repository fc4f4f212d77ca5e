// Contacts and the crane's envelope: the penalty law against its energy, the ground's, the
// supports' and the backstop's Jacobians against finite differences, a body resting on the
// ground and a boom pressed onto its backstop against hand statics, a bounce without losses, and
// the hard case of a hoist rope paid out fast on the thesis crane with and without its backstop.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <random>

#include "cranesim/model/contact_elements.hpp"
#include "cranesim/model/support_elements.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "element_differences.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// ∂r/∂q and ∂r/∂dq of element e at (q, v) by central differences, beside its Jacobian.
void checkJacobian(const Element& e, const VecX& q, const VecX& v) {
  const VecX a = VecX::Zero(e.size());
  test::checkMasslessJacobian(e, ElementInput{q.data(), v.data(), a.data(), 0.0, Vec3(0, 0, -9.81)}, 1e-7);
}

/// A frame node's coordinates [r, φ] turned by h about its body axis k (so that a change of
/// energy along it is the work of the body-frame moment Q_ω,k).
VecX turnedAbout(const VecX& q, int offset, int k, double h) {
  VecX out = q;
  const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(offset + 3))) * Eigen::AngleAxisd(h, Vec3::Unit(k)).toRotationMatrix();
  out.segment<3>(offset + 3) = rotationVector(R);
  return out;
}

/// The contact's spring force is its energy's gradient: Q(q, 0) · δq = −δV along every
/// translation and every body-frame turn of its frame nodes.
void checkEnergyGradient(const ContactElement& e, const VecX& q, const std::vector<int>& frame_offsets) {
  const int n = e.size();
  const VecX zero = VecX::Zero(n);
  const ElementInput in{q.data(), zero.data(), zero.data(), 0.0, Vec3(0, 0, -9.81)};
  VecX r(n);
  e.residual(in, r.data());
  const VecX Q = -r;
  const auto energyAt = [&](const VecX& x) { return e.potentialEnergy({x.data(), zero.data(), zero.data(), 0.0, Vec3(0, 0, -9.81)}); };
  const double h = 1e-6;
  for (const int offset : frame_offsets)
    for (int k = 0; k < 3; ++k) {
      VecX up = q, down = q;
      up(offset + k) += h, down(offset + k) -= h;
      CHECK(-(energyAt(up) - energyAt(down)) / (2 * h) == Approx(Q(offset + k)).margin(1e-6 * Q.norm()));
      if (n == 3) continue;
      const double turned = -(energyAt(turnedAbout(q, offset, k, h)) - energyAt(turnedAbout(q, offset, k, -h))) / (2 * h);
      CHECK(turned == Approx(Q(offset + 3 + k)).margin(1e-6 * Q.norm()));
    }
}

/// The power identity of a contact on one frame node moving with v = [ṙ, ω]: the work rate of its
/// force is what its energy loses and it dissipates, Q(q, dq) · dq = −dV/dt − P_diss, dV/dt by
/// central differences along the motion (r + h ṙ, R exp(h ω̂)).
void checkPowerBalance(const ContactElement& e, const VecX& q, const VecX& v) {
  const VecX a = VecX::Zero(6);
  const ElementInput in{q.data(), v.data(), a.data(), 0.0, Vec3(0, 0, -9.81)};
  VecX r(6);
  e.residual(in, r.data());
  const auto moved = [&](double h) {
    VecX x = q;
    x.head<3>() += h * v.head<3>();
    const Vec3 w = v.tail<3>();
    const Mat3 R = rotationMatrix<double>(Vec3(q.tail<3>())) * Eigen::AngleAxisd(h * w.norm(), w.normalized()).toRotationMatrix();
    x.tail<3>() = rotationVector(R);
    return e.potentialEnergy({x.data(), v.data(), a.data(), 0.0, Vec3(0, 0, -9.81)});
  };
  const double h = 1e-6, energy_rate = (moved(h) - moved(-h)) / (2 * h);
  const double power = -r.dot(v);
  CAPTURE(power, energy_rate, e.dissipatedPower(in));
  CHECK(power == Approx(-energy_rate - e.dissipatedPower(in)).margin(1e-6 * r.norm() * v.norm()));
}

/// A bar of 1000 kg and 10 m on a turntable, hinged about y at its foot and drawn at 80°, raised
/// by a torque T about its foot against its weight onto a backstop at 85° (stiffness k). JOINTS
/// orders the hinge's joints.
std::string barOnBackstop(double torque, double stiffness, const std::string& joints) {
  return fmt::format(R"(
name: bar on its backstop
gravity: [0, 0, -9.81]
ground:
  joints: [{{name: ring}}]
bodies:
  - {{name: turntable, mass: 100, inertia: [10, 10, 10], joints: [{{name: foot}}]}}
  - name: bar
    mass: 1000
    centroid: [5, 0, 0]
    inertia: [10, 8343, 8343]
    rotation: {{axis: [0, 1, 0], angle_deg: -80}}
    joints: [{{name: foot}}, {{name: tip, position: [10, 0, 0]}}]
constraints:
  - {{name: slewing, type: revolute, joints: [ground.ring, turntable.origin], axis: z, drive: 0}}
  - {{name: boom_foot, type: revolute, joints: {}, axis: y}}
loads:
  - {{name: raise, joint: bar.foot, torque: [0, {}, 0]}}
crane:
  slewing: slewing
  boom_foot: boom_foot
  boom_head: bar.tip
  hook: bar.tip
  backstop: {{angle: 85, stiffness: {}, damping: 0}}
solver: {{t_end: 1, rtol: 1.0e-8, atol: 1.0e-10, statics: {{method: relaxation}}}}
)",
                     joints, -torque, stiffness);
}

/// A 1000 kg ball on a vertical rail (a prismatic joint along z) at height z0, resting on the
/// ground at 0 as a sphere of 0.5 m: stiffness k, damping c, no friction. The works are in the
/// error test: the damper's power comes in pulses of a few steps.
std::string ballOnRail(double z0, double stiffness, double damping, double t_end) {
  return fmt::format(R"(
name: ball on a rail
gravity: [0, 0, -9.81]
ground:
  joints: [{{name: rail}}]
  surface:
    height: 0
    stiffness: {}
    damping: {}
    friction: 0
    contacts: [{{body: ball, radius: 0.5}}]
bodies:
  - {{name: ball, mass: 1000, inertia: [100, 100, 100], position: [0, 0, {}]}}
constraints:
  - {{name: rail, type: prismatic, joints: [ground.rail, ball.origin], axis: z}}
solver: {{t_end: {}, rtol: 1.0e-8, atol: 1.0e-10, work_error_control: true}}
output: {{interval: 0.001}}
)",
                     stiffness, damping, z0, t_end);
}

}  // namespace

TEST_CASE("The penalty law's force is its energy's derivative, continuous with its slope", "[contact]") {
  const PenaltyLaw law{2.0e6, 0.0, 0.01};
  for (const double d : {-0.01, 0.0, 0.002, 0.0099, 0.01, 0.0101, 0.05}) {
    const double h = 1e-7;
    CHECK((penaltyEnergy(d + h, law) - penaltyEnergy(d - h, law)) / (2 * h) == Approx(penaltySpringForce(d, law)).margin(1e-3));
  }
  const double eps = law.smoothing, tiny = 1e-12;
  CHECK(penaltySpringForce(eps - tiny, law) == Approx(penaltySpringForce(eps + tiny, law)).epsilon(1e-9));
  const auto slope = [&](double d) { return (penaltySpringForce(d + 1e-9, law) - penaltySpringForce(d - 1e-9, law)) / 2e-9; };
  CHECK(slope(eps - 1e-6) == Approx(slope(eps + 1e-6)).epsilon(1e-3));
  CHECK(slope(1e-7) <= 1e-4 * law.stiffness);
  CHECK(penaltyForce(0.05, -1e3, PenaltyLaw{2.0e6, 1.0e5, 0.01}) == 0.0);  // opening faster than it relaxes: no pull
}

TEST_CASE("The contact elements' Jacobians match finite differences", "[contact]") {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const GroundSurface ground{-0.5, Vec3(0, 0, 1), {3.0e6, 2.0e4, 0.01}, 0.6, 0.05};
  SECTION("a body's sphere sliding and pressed in, off its origin") {
    const GroundContactElement e(ground, 0.8, Vec3(0.4, -0.3, 0.2), true, 0, {0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4, 5});
    VecX q(6), v(6);
    q << 1.0, 2.0, 0.0, 0.3 * uniform(random), 0.3 * uniform(random), 0.3 * uniform(random);
    for (int k = 0; k < 6; ++k) v(k) = 0.2 * uniform(random);
    CAPTURE(q.transpose(), e.closure({q.data(), v.data(), nullptr, 0.0, Vec3::Zero()}));
    REQUIRE(e.closure({q.data(), v.data(), nullptr, 0.0, Vec3::Zero()}) > 0.01);
    checkJacobian(e, q, v);
    checkEnergyGradient(e, q, {0});
  }
  SECTION("a member's node within the smoothing band") {
    const GroundContactElement e(ground, 0.3, Vec3::Zero(), false, 0, {0, 1, 2}, {0, 1, 2});
    VecX q(3), v(3);
    q << 0.5, -0.2, -0.205;
    v << 0.03, -0.02, -0.4;
    checkJacobian(e, q, v);
    checkEnergyGradient(e, q, {0});
  }
  SECTION("a support of a turned body on a tilted bed: two points settled, one lifted off") {
    // The normal law only: the bed's shear springs are an AnchoredSupportElement's
    // (tests/crane/test_support_friction.cpp).
    VecX q(6), v(6);
    q << 1.0, 2.0, 0.0, 0.2 * uniform(random), 0.2 * uniform(random), 0.2 * uniform(random);
    for (int k = 0; k < 6; ++k) v(k) = 0.2 * uniform(random);
    SupportBed bed;
    bed.up = Vec3(0.1, -0.2, 1.0).normalized();
    bed.level = 0.3;
    bed.law = {4.0e7, 3.0e5, 0.002};
    SupportBed lifted = bed;
    lifted.level = -5.0;
    const SupportElement e({{Vec3(0.5, -0.4, -0.3), bed}, {Vec3(0.3, 0.5, -0.3), bed}, {Vec3(-0.6, 0.3, -0.3), lifted}}, 0,
                           {0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4, 5});
    const double settled = e.closure({q.data(), v.data(), nullptr, 0.0, Vec3::Zero()});
    CAPTURE(q.transpose(), settled);
    REQUIRE(settled > 0.002);
    checkJacobian(e, q, v);
    checkPowerBalance(e, q, v);
    q(2) += (settled - 0.001) / bed.up.z();  // raised into the smoothing band
    REQUIRE(e.closure({q.data(), v.data(), nullptr, 0.0, Vec3::Zero()}) == Approx(0.001));
    checkJacobian(e, q, v);
    checkPowerBalance(e, q, v);
  }
  SECTION("a backstop pressed in and turning") {
    // The boom's point B 5 m from the foot, turned 0.13 rad about the hinge's y axis from its drawn
    // direction x: closure 0.13 − 0.1; the whole turned by R about an oblique axis.
    BackstopElement::Hinge hinge;
    hinge.foot = Vec3(0.2, 0.0, -0.1);
    hinge.axis = Vec3::UnitY();
    hinge.drawn = Vec3::UnitX();
    hinge.point = Vec3(0.3, -0.4, 0.5);
    hinge.engaged = 0.1;
    std::vector<int> indices(12);
    for (int k = 0; k < 12; ++k) indices[k] = k;
    const BackstopElement e(hinge, {5.0e7, 1.0e6, 0.005}, 0, 1, indices, indices);
    const Mat3 R = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    const Mat3 Rb = Eigen::AngleAxisd(-0.7, Vec3(3, -1, 2).normalized()).toRotationMatrix();
    const Vec3 rs(1.0, 2.0, 3.0);
    const Vec3 B = rs + R * (hinge.foot + 5.0 * Vec3(std::cos(0.13), 0.0, -std::sin(0.13)));
    VecX q(12), v(12);
    q << rs, rotationVector(R), B - Rb * hinge.point, rotationVector(Rb);
    for (int k = 0; k < 12; ++k) v(k) = 0.3 * uniform(random);
    const VecX zero = VecX::Zero(12);
    CHECK(e.closure({q.data(), zero.data(), nullptr, 0.0, Vec3::Zero()}) == Approx(0.03).epsilon(1e-12));
    checkJacobian(e, q, v);
    checkEnergyGradient(e, q, {0, 6});
  }
}

TEST_CASE("A body resting on the ground presses it in by its weight over the stiffness", "[contact]") {
  // Drawn 0.01 m into the ground (the statics start where the contact carries): k (δ − ε/2) = m g.
  const double k = 1.0e6, eps = 0.005, weight = 1000 * 9.81;
  const Vec3 at = test::equilibriumJointPosition(ballOnRail(0.49, k, 0.0, 1.0), "ball.origin");
  const double depth = weight / k + eps / 2;
  CHECK(at.z() == Approx(0.5 - depth).epsilon(1e-12));
}

TEST_CASE("A ball dropped on a lossless ground bounces back to its height", "[contact]") {
  // 1 m of free fall onto k = 1e6 N/m: contact for about π √(m/k) = 0.1 s, back at 1.5 m after
  // about 1.0 s. The smoothed spring is conservative: the energy books close.
  const Scene scene = parseScene(ballOnRail(1.5, 1.0e6, 0.0, 1.2), "<test>");
  test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const std::vector<double>& p = run.jointPositions("ball.origin");
  double lowest = 1e9, highest_after = -1e9;
  for (std::size_t s = 0; s < run.recorder.samples(); ++s) {
    lowest = std::min(lowest, p[3 * s + 2]);
    if (run.recorder.time()[s] > 0.7) highest_after = std::max(highest_after, p[3 * s + 2]);
  }
  // Drop height to the contact (1 m) plus the penetration δ: ½ k δ² (smoothed) = m g (1 + δ).
  CHECK(lowest < 0.5 - 0.1);
  CHECK(highest_after == Approx(1.5).margin(2e-5));
  CHECK(run.recorder.relativeBalanceDrift() <= 1e-6);
  const auto events = run.recorder.envelope().events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].what == "on the ground");
  CHECK(events[0].first_time == Approx(std::sqrt(2.0 / 9.81)).margin(2e-3));
  CHECK(events[0].depth == Approx(0.5 - lowest).epsilon(1e-12));
}

TEST_CASE("A damped bounce books the energy the ground's damper takes", "[contact]") {
  const Scene scene = parseScene(ballOnRail(1.5, 1.0e6, 2.0e4, 1.2), "<test>");
  test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const auto& dissipated = run.recorder.dissipated();
  CHECK(dissipated.back() > 0.1 * 1000 * 9.81 * 1.0);  // ζ ≈ 0.32: most of a tenth of the drop's energy or more
  CHECK(run.recorder.relativeBalanceDrift() <= 1e-6);
}

TEST_CASE("A boom raised onto its backstop rests where the stop's moment holds it", "[contact]") {
  const double torque = 2.0e4, k = 1.0e6, eps = 0.2 * kDegree, gravity_moment = 1000 * 9.81 * 5.0;
  // T − m g l cos β = k (δ − ε/2), δ = β − 85°, solved by Newton.
  double beta = 86.0 * kDegree;
  for (int i = 0; i < 50; ++i) {
    const double f = torque - gravity_moment * std::cos(beta) - k * (beta - 85.0 * kDegree - eps / 2);
    beta -= f / (gravity_moment * std::sin(beta) - k);
  }
  for (const std::string joints : {"[turntable.foot, bar.foot]", "[bar.foot, turntable.foot]"}) {
    CAPTURE(joints);
    // The bar turns freely until the stop engages: statics by relaxation, which starts without
    // stiffness along the free hinge.
    const Scene scene = parseScene(barOnBackstop(torque, k, joints), "<test>");
    const Model model = compileModel(scene);
    const Assembler assembler(model);
    const StaticResult eq = sceneEquilibrium(scene, model, assembler, true);
    REQUIRE(eq.converged);
    const Vec3 bar = model.jointFrame(eq.q.data(), model.findJoint("bar.tip")).r - model.jointFrame(eq.q.data(), model.findJoint("bar.foot")).r;
    CHECK(std::atan2(bar.z(), bar.x()) / kDegree == Approx(beta / kDegree).margin(1e-8));
  }
}

TEST_CASE("A fast payout: the backstop holds the boom, without it the boom goes over, reported",
          "[contact][crane]") {
  // The shipped hard case, its first 4.5 s: the rope snatches the falling load at about 2 s with
  // more than its breaking force; the boom springs back onto its backstop. Without the backstop
  // it passes the vertical at about 2.8 s and is 14° past it at 4 s.
  Scene scene = test::loadScene("crane_hoist_payout.yaml");
  scene.solver.t_end = 4.5;
  struct Run {
    std::vector<EnvelopeEvent> events;
    double largest_boom_angle = 0.0, largest_compression = -1.0;
  };
  const auto run = [](const Scene& s) {
    const Model model = compileModel(s);
    const Assembler assembler(model);
    ResultsRecorder recorder(assembler);
    const SimulationOutcome outcome = simulate(assembler, runInitialState(s, model, assembler, true), recorder);
    REQUIRE(outcome.complete);
    const EnvelopeMonitor& e = recorder.envelope();
    Run r{e.events(), *std::max_element(e.boomAngle().begin(), e.boomAngle().end())};
    if (!e.backstopCompression().empty()) r.largest_compression = *std::max_element(e.backstopCompression().begin(), e.backstopCompression().end());
    return r;
  };
  const auto find = [](const std::vector<EnvelopeEvent>& events, const std::string& what) {
    const auto e = std::find_if(events.begin(), events.end(), [&](const EnvelopeEvent& x) { return x.what == what; });
    return e == events.end() ? std::optional<EnvelopeEvent>() : *e;
  };
  const Run with = run(scene);
  const auto backstop = find(with.events, "on its backstop"), snap = find(with.events, "rope overload");
  REQUIRE(backstop);
  CHECK(backstop->depth == Approx(with.largest_compression).epsilon(1e-12));
  CHECK(backstop->depth < 5.0);           // deg past 85.5°: the boom stays on its stops
  CHECK(with.largest_boom_angle < 93.0);  // its head whips at most a few degrees further
  CHECK(!find(with.events, "on the ground"));
  CHECK(!find(with.events, "below ground"));
  REQUIRE(snap);
  CHECK(snap->part == "hoist_rope");
  CHECK(snap->peak > 13.08e6);
  CHECK(snap->first_time == Approx(2.0).margin(0.2));

  scene.crane->backstop.reset();
  const Run without = run(scene);
  const auto over = find(without.events, "boom past its angle limit");
  REQUIRE(over);
  CHECK(over->first_time < 3.2);
  CHECK(over->limit == 90.0);
  CHECK(without.largest_boom_angle > 95.0);
}
