// Members meeting at an angle: a fixed constraint with `pose: drawn` keeps the relative pose the
// drawing gives its two joints, so an L-shaped or a kinked frame needs no corner body. Checked
// against the same frames built the old way, with a rigid corner body whose two joints carry
// the two members' axes: the same equilibrium to round-off. And the messages when a plain
// fixed constraint joins frames the drawing turns.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// A horizontal cantilever along x, clamped at the origin, and a second member from its end at
/// `angle_deg` in the x-y plane, loaded at its tip down and sideways (bending about both axes
/// and torsion in the first member). CORNER is replaced by the corner's constraints (and body).
const char* kFrame = R"(
name: frame with a corner
gravity: [0, 0, 0]
ground:
  joints: [{name: wall}]
BODIES
members:
  - {name: leg, type: timoshenko, start: [0, 0, 0], end: [4, 0, 0], segments: 4,
     section: {outer_radius: 0.1, inner_radius: 0.09}, material: {density: 7850, youngs_modulus: 2.1e11, poisson_ratio: 0.3}}
  - {name: arm, type: timoshenko, start: [4, 0, 0], end: END, segments: 3,
     section: {outer_radius: 0.1, inner_radius: 0.09}, material: {density: 7850, youngs_modulus: 2.1e11, poisson_ratio: 0.3}}
constraints:
  - {name: clamp, type: fixed, joints: [ground.wall, leg.start]}
CORNER
loads:
  - {name: tip, joint: arm.end, force: [2000, 3000, -5000]}
solver: {t_end: 1}
)";

std::string frame(double angle_deg, bool corner_body) {
  const double a = angle_deg * std::numbers::pi / 180.0;
  const std::string end = fmt::format("[{:.17g}, {:.17g}, 0]", 4.0 + 3.0 * std::cos(a), 3.0 * std::sin(a));
  std::string yaml = kFrame;
  yaml.replace(yaml.find("END"), 3, end);
  const std::string body =
      "bodies:\n  - {name: corner, mass: 1.0, inertia: [1, 1, 1], position: [4, 0, 0],\n" +
      fmt::format("     joints: [{{name: a}}, {{name: b, rotation: {{axis: [0, 0, 1], angle_deg: {:.17g}}}}}]}}\n", angle_deg);
  yaml.replace(yaml.find("BODIES"), 6, corner_body ? body : "");
  yaml.replace(yaml.find("CORNER"), 6,
               corner_body ? "  - {name: leg_corner, type: fixed, joints: [leg.end, corner.a]}\n"
                             "  - {name: corner_arm, type: fixed, joints: [corner.b, arm.start]}"
                           : "  - {name: corner, type: fixed, joints: [leg.end, arm.start], pose: drawn}");
  return yaml;
}


}  // namespace

TEST_CASE("Members meeting at 90° and at 45°: pose: drawn equals a corner body", "[assembly][statics]") {
  for (double angle : {90.0, 45.0, 5.6}) {
    const Vec3 drawn = test::equilibriumJointPosition(frame(angle, false), "arm.end");
    const Vec3 body = test::equilibriumJointPosition(frame(angle, true), "arm.end");
    INFO("angle " << angle << "°: pose: drawn " << drawn.transpose() << ", corner body " << body.transpose());
    CHECK((drawn - body).norm() < 1e-9);
    // The load bends the frame visibly (centimetres), so agreement is not that of two rigid frames.
    const double a = angle * std::numbers::pi / 180.0;
    CHECK((drawn - Vec3(4.0 + 3.0 * std::cos(a), 3.0 * std::sin(a), 0.0)).norm() > 1e-3);
  }
}

TEST_CASE("A plain fixed constraint between members at 90° names the pose, not a loop", "[assembly]") {
  std::string yaml = frame(90.0, false);
  yaml.replace(yaml.find(", pose: drawn"), 13, "");
  try {
    test::equilibriumJointPosition(yaml, "arm.end");
    FAIL("a fixed constraint between frames turned by 90° was accepted");
  } catch (const SceneError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("closes no loop") != std::string::npos);
    CHECK(message.find("pose: drawn") != std::string::npos);
    CHECK(message.find("closed loop") == std::string::npos);
  }
}
