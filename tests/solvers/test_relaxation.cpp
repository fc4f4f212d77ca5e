// Static equilibrium by damped dynamics (relaxation.hpp) against Newton and closed forms: it
// finds the stable equilibrium where Newton converges to the nearest one, and a slack rope's
// catenary from a straight start.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "cranesim/io/scene_reader.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/solvers/relaxation.hpp"
#include "elastic_catenary.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

TEST_CASE("Relaxation finds the hanging pendulum where Newton finds the inverted one", "[statics][relaxation]") {
  // The pendulum rod of configs/pendulum.yaml, released 170° from hanging: the nearest
  // equilibrium is the inverted one.
  Scene scene = test::loadScene("pendulum.yaml");
  const double angle = 170.0 * std::numbers::pi / 180.0;
  RigidBodySpec& rod = scene.bodies.front();
  rod.rotation = Eigen::AngleAxisd(angle, Vec3::UnitY()).toRotationMatrix();
  rod.position = -rod.rotation * Vec3(0.0, 0.0, 0.5);
  const Model model = compileModel(scene);
  const int tip = model.findJoint("rod.tip");
  const auto tipHeight = [&](const VecX& q) {
    const Node& n = model.nodes[model.joints[tip].node];
    return (q.segment<3>(n.q) + rotationMatrix<double>(Vec3(q.segment<3>(n.q + 3))) * model.joints[tip].offset).z();
  };

  const StaticResult newton = solveStatics(model, model.q0, 0.0);
  INFO(newton.message);
  REQUIRE(newton.converged);
  CHECK(tipHeight(newton.q) == Approx(1.0).margin(1e-9));  // inverted: unstable, but an equilibrium

  RelaxationOptions options;
  options.damping = 3.0;  // ≈ 2ω, ω = √(3g/2l) = 3.8 rad/s for the rod
  const RelaxationResult relaxed = relaxToEquilibrium(scene, options);
  INFO(relaxed.equilibrium.message);
  REQUIRE(relaxed.equilibrium.converged);
  CHECK(tipHeight(relaxed.equilibrium.q) == Approx(-1.0).margin(1e-9));
  CHECK(relaxed.final_kinetic_ratio <= options.kinetic_energy_ratio);
  CHECK(relaxed.equilibrium.iterations <= 8);  // the relaxed state is close: Newton only polishes
}

TEST_CASE("Relaxation hangs a straight slack rope into the elastic catenary", "[statics][relaxation][rope]") {
  // The catenary of test_strut_rope.cpp, started from the straight line between the supports
  // and reeled out from the chord to 22 m (slack over a 20 m span: no transverse stiffness).
  const double span = 20.0, L0 = 22.0, radius = 0.01, E = 1e9, rho = 7800.0, g = 9.81;
  const Scene scene = parseScene(R"(
name: catenary
gravity: [0, 0, -9.81]
ground:
  joints: [{name: left, position: [0, 0, 0]}, {name: right, position: [20, 0, 0]}]
members:
  - {name: rope, type: rope, start: [0, 0, 0], end: [20, 0, 0], segments: 16, length: 22,
     section: {radius: 0.01}, material: {density: 7800, youngs_modulus: 1.0e9}, damping: 0.01}
constraints:
  - {name: a, type: spherical, joints: [ground.left, rope.start]}
  - {name: b, type: spherical, joints: [ground.right, rope.end]}
solver: {t_end: 1}
)", "<test>");
  const Model model = compileModel(scene);
  RelaxationOptions options;
  options.damping = 2.0;
  options.duration = 60.0;
  const RelaxationResult relaxed = relaxToEquilibrium(scene, options);
  INFO(relaxed.equilibrium.message);
  REQUIRE(relaxed.equilibrium.converged);
  const double A = std::numbers::pi * radius * radius;
  const double sag = test::elasticCatenary(span, L0, rho * A * g, E * A).sag;
  const Node& middle = model.nodes[model.joints[model.findJoint("rope.n8")].node];
  CHECK(-relaxed.equilibrium.q(middle.q + 2) == Approx(sag).epsilon(1e-4));
}
