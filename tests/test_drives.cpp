// Rheonomic drives: a rod turned about a fixed axis by each Appendix E profile follows the
// prescribed angle, including profiles whose motion starts at t = 0 or at a breakpoint, where
// the integrator restarts with the accelerations of the coming segment. Loads scaled by linear
// and step tables deliver exactly the tables' impulse.

#include <catch2/catch.hpp>

#include <numbers>

#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

const char* kDrivenRod = R"(
name: driven rod
ground:
  joints: [{name: pivot}]
bodies:
  - name: rod
    mass: 1.0
    inertia: [0.08333333333333333, 0.08333333333333333, 1.0e-4]
    position: [0, 0, -0.5]
    joints: [{name: top, position: [0, 0, 0.5]}, {name: tip, position: [0, 0, -0.5]}]
constraints:
  - {name: hinge, type: revolute, joints: [ground.pivot, rod.top], axis: y, drive: DRIVE}
solver: {t_end: 5, rtol: 1.0e-8, atol: 1.0e-10}  # tanh starts 2.5e-5 off 0: posed there
output: {interval: 0.01}
)";

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
    std::string yaml = kDrivenRod;
    yaml.replace(yaml.find("DRIVE"), 5, drive);
    const Scene scene = parseScene(yaml, "<test>");
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
