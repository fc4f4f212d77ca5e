// Rheonomic drives: a rod turned about a fixed axis by each Appendix E profile follows the
// prescribed angle, including profiles whose motion starts at t = 0 or at a breakpoint, where
// the integrator restarts with the accelerations of the coming segment. Loads scaled by linear
// and step tables deliver exactly the tables' impulse.

#include <catch2/catch.hpp>

#include <numbers>

#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// A free 2 kg ball pushed along x by a 10 N force scaled by SCALE, no gravity.
const char* kPushedBall = R"(
name: pushed ball
gravity: [0, 0, 0]
bodies:
  - {name: ball, mass: 2.0, inertia: [1, 1, 1], joints: [{name: centre}]}
loads:
  - {name: push, joint: ball.centre, force: [10, 0, 0], scale: SCALE}
solver: {t_end: 5, rtol: 1.0e-10, atol: 1.0e-12}
output: {interval: 0.5}
)";

}  // namespace

TEST_CASE("A load scaled by a linear or a step table delivers the table's impulse exactly", "[dynamics][profiles]") {
  struct Case {
    const char* scale;
    double impulse;       // ∫ scale dt over the table, s
    double first_moment;  // ∫ (t_end − t) scale dt, s²: the displacement per unit force and mass
  };
  // Triangle 0 → 1 → 0 over [1, 3]: area 1, centroid at t = 2. Steps 0 on [0, 1), 1 on [1, 2),
  // 0.5 on [2, 4), 0 after: area 2, ∫(5 − t) s dt = 3.5 + 0.5·4. (The cubic table through the
  // triangle's points with natural end slopes has area 1.25.)
  const Case cases[] = {
      {"{type: table, t: [1, 2, 3], value: [0, 1, 0], interpolation: linear}", 1.0, 3.0},
      {"{type: table, t: [0, 1, 2, 4], value: [0, 1, 0.5, 0], interpolation: step}", 2.0, 5.5},
  };
  for (const Case& c : cases) {
    std::string yaml = kPushedBall;
    yaml.replace(yaml.find("SCALE"), 5, c.scale);
    const test::SimulationRun run(parseScene(yaml, "<test>"));
    INFO(c.scale << ": " << run.outcome.message);
    REQUIRE(run.outcome.complete);
    // x(5) = (F/m) ∫₀⁵ (5 − t) s(t) dt from rest at the origin; v(5) = (F/m) ∫ s dt.
    const auto& t = run.recorder.time();
    const auto& x = run.jointPositions("ball.centre");
    REQUIRE(t.size() >= 2);
    CHECK(t.back() == Approx(5.0));
    const std::size_t last = t.size() - 1;
    CHECK(x[3 * last] == Approx(5.0 * c.first_moment).epsilon(1e-8));
    // After the table ends the ball coasts at (F/m) ∫ s dt.
    CHECK((x[3 * last] - x[3 * (last - 1)]) / (t[last] - t[last - 1]) == Approx(5.0 * c.impulse).epsilon(1e-8));
  }
}

TEST_CASE("A driven revolute follows every profile, from t = 0 and across breakpoints", "[dynamics][drives]") {
  const std::vector<std::string> drives = {
      "{type: trapezoid, from: 0, distance: 1.5, t_start: 0, duration: 4, t_accel: 1, t_decel: 1}",
      "{type: cosine_step, from: 0, to: 45, t_start: 1, t_end: 3, unit: deg}",
      "{type: cosine_full, base: 0, peak: 0.5, t_start: 0.5, t_end: 4.5}",
      "{type: tanh, from: 0, to: 1, t_start: 1, t_end: 3, confidence: 0.99}",
      "{type: table, t: [0, 1, 2.5, 4], value: [0, 0.3, -0.2, 0.4]}",
      "{type: table, t: [0, 1, 2.5, 4], value: [0, 0.3, -0.2, 0.4], interpolation: linear}",
      "{type: ramp, value: 0, rate: 0.5, t_start: 2}",
  };
  for (const std::string& drive : drives) {
    const Scene scene = test::drivenRod(drive);
    const test::SimulationRun run(scene);
    INFO(drive << ": " << run.outcome.message);
    REQUIRE(run.outcome.complete);
    const Profile& profile = *scene.constraints[0].drive;
    const auto& t = run.recorder.time();
    const auto& tip = run.jointPositions("rod.tip");
    double worst = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      // Rotation about +y by ψ takes the tip (0, 0, −1) to (−sin ψ, 0, −cos ψ).
      const double angle = std::atan2(-tip[3 * k], -tip[3 * k + 2]);
      worst = std::max(worst, std::abs(angle - profile(t[k])));
    }
    INFO("max angle error " << worst);
    CHECK(worst < 1e-8);
  }
}

TEST_CASE("A drive's velocity jump moves the masses as an impulse through the constraints would", "[dynamics][drives]") {
  // A cart whose drive starts to ramp at 1 m/s at t = 0.5 s, carrying a double pendulum drawn at
  // angles (rods of 2 m and 1.5 m, bobs of 1 kg and 100 kg). In the jump the two bobs together
  // are pushed only through the upper rod: their momentum changes along that rod alone. (A
  // least-norm change of the velocities would ignore the masses and push the pair sideways.)
  const Scene scene = parseScene(R"(
name: cart with a double pendulum
gravity: [0, 0, -9.81]
ground:
  joints: [{name: rail}]
bodies:
  - {name: cart, mass: 10, inertia: [1, 1, 1]}
  - {name: upper, mass: 1, inertia: [1.0e-3, 1.0e-3, 1.0e-3], position: [1.2, 0, -1.6]}
  - {name: lower, mass: 100, inertia: [1, 1, 1], position: [2.4, 0, -2.5]}
constraints:
  - {name: track, type: prismatic, joints: [ground.rail, cart.origin], axis: x, drive: {type: ramp, value: 0, rate: 1, t_start: 0.5}}
  - {name: rod1, type: distance, joints: [cart.origin, upper.origin], length: 2}
  - {name: rod2, type: distance, joints: [upper.origin, lower.origin], length: 1.5}
solver: {t_end: 0.50001, rtol: 1.0e-10, atol: 1.0e-12}
output: {interval: 1.0e-5}
)",
                                 "<test>");
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const Model& model = run.model;
  const auto& t = run.recorder.time();
  const std::size_t before = std::find_if(t.begin(), t.end(), [](double x) { return x >= 0.5 - 1e-12; }) - t.begin();
  const std::size_t after = before + 1;
  REQUIRE(after < t.size());
  const auto velocity = [&](const std::string& body, std::size_t k) {
    const int v = model.nodes[model.joints[model.findJoint(body + ".origin")].node].v;
    return Vec3(run.recorder.stateColumn(model.nq + v)[k], run.recorder.stateColumn(model.nq + v + 1)[k],
                run.recorder.stateColumn(model.nq + v + 2)[k]);
  };
  const auto position = [&](const std::string& body, std::size_t k) {
    const auto& p = run.recorder.jointPositions(model.findJoint(body + ".origin"));
    return Vec3(p[3 * k], p[3 * k + 1], p[3 * k + 2]);
  };
  CHECK(velocity("cart", after).x() == Approx(1.0).epsilon(1e-9));
  const Vec3 rod1 = (position("upper", before) - position("cart", before)).normalized();
  const Vec3 change = 1.0 * (velocity("upper", after) - velocity("upper", before)) +
                      100.0 * (velocity("lower", after) - velocity("lower", before));
  // Gravity acts for the 1e-5 s between the samples: 101 kg · 9.81 m/s² · 1e-5 s ≈ 1e-2 N·s.
  INFO("momentum change of the bobs " << change.transpose() << " N·s; upper rod " << rod1.transpose());
  CHECK(change.norm() > 1.0);
  CHECK(change.cross(rod1).norm() < 2e-2);
  CHECK(run.recorder.relativeBalanceDrift() < 1e-6);
}
