// Statics of a body free to spin about its joint: a family of equilibria (the spin about the
// vertical through a spherical hinge), so the equilibrium Jacobian is singular along it at every
// solution and Newton's step there is rounding divided by a vanishing pivot. The equilibrium
// (solveEquilibrium, from the drawing with its multipliers released from rest) must converge
// whatever the rounding: the same bar drawn at angles 0.005° apart took 11…655 iterations, or
// failed, before the correction-growth rule of dampedNewton (statics.cpp).

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "cranesim/math/rotation.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// A 2 kg bar with its centroid off its axis, hanging from a spherical hinge at its top, drawn
/// turned by `degrees` about [1, 1, 0] (the scene of tests/python/test_view.py at 30°).
std::string offsetBar(double degrees) {
  const double a = degrees * std::numbers::pi / 180.0, s = std::sin(a) / std::sqrt(2.0);
  return fmt::format(R"(
name: tilted bar with an offset centroid
ground:
  joints: [{{name: pivot, position: [0, 0, 0]}}]
bodies:
  - name: bar
    mass: 2.0
    centroid: [0.3, 0.1, 0.5]
    inertia: [0.2, 0.15, 0.07]
    position: [{:.17g}, {:.17g}, {:.17g}]
    rotation: {{axis: [1, 1, 0], angle_deg: {:.17g}}}
    joints: [{{name: top, position: [0, 0, 1]}}]
constraints:
  - {{name: hinge, type: spherical, joints: [ground.pivot, bar.top]}}
solver: {{t_end: 1}}
)",
                     -s, s, -std::cos(a), degrees);
}

}  // namespace

TEST_CASE("The equilibrium of a bar free to spin about its hinge converges in one load step whatever the rounding",
          "[statics]") {
  // Drawn within 0.03° of 30° (the previous build: 14…1335 iterations, or none), and far from
  // hanging, where the previous build found none at 120° and 150°.
  struct Drawing {
    double degrees;
    int iterations;  // at most
  };
  for (const auto [degrees, most] : {Drawing{29.98, 12}, {29.99, 12}, {29.995, 12}, {30.0, 12}, {30.005, 12}, {30.01, 12},
                                     {30.02, 12}, {30.03, 12}, {5.0, 12}, {60.0, 25}, {120.0, 40}, {150.0, 25}}) {
    const Scene scene = parseScene(offsetBar(degrees), "<test>");
    const Model model = compileModel(scene);
    const StaticResult eq = solveEquilibrium(scene, model, 0.0);  // as crane-sim static and modes
    INFO("drawn at " << degrees << "°: " << eq.iterations << " Newton iterations in " << eq.load_steps
                     << " load steps; " << eq.message);
    REQUIRE(eq.converged);
    CHECK(eq.load_steps == 1);
    CHECK(eq.iterations <= most);
    // The centroid on the vertical through the hinge, the hinge carrying the weight; Newton
    // finds the equilibrium nearest the drawing: hanging, or balanced upright from 150°.
    const Mat3 R = rotationMatrix<double>(Vec3(eq.q.segment<3>(3)));
    const Vec3 centroid = eq.q.head<3>() + R * Vec3(0.3, 0.1, 0.5);
    CHECK(std::hypot(centroid.x(), centroid.y()) < 1e-12);
    CHECK((centroid.z() < 0.0) == (degrees < 150.0));
    CHECK(eq.lambda.norm() == Approx(2.0 * 9.81).epsilon(1e-12));
  }
}
