// Absolute tolerances by kind of coordinate (solver.atol as a mapping): Model::absoluteTolerances
// lays them out over [q, dq] by each node's kind — positions and velocities first, then the
// dimensionless coordinates (rotation vectors, stretches, rope slopes) and their rates.

#include <catch2/catch.hpp>

#include <string>

#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// A load on a two-element rope, with the given `atol`.
std::string ropeScene(const std::string& atol) {
  return R"(
gravity: [0, 0, -9.81]
ground: {joints: [{name: top, position: [0, 0, 0]}]}
bodies:
  - {name: load, mass: 10, inertia: [1, 1, 1], position: [0, 0, -5], joints: [{name: hook, position: [0, 0, 0]}]}
members:
  - {name: rope, type: rope, start: ground.top, end: load.hook, segments: 2, section: {radius: 0.01},
     material: {density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.3}}
constraints:
  - {name: top, type: spherical, joints: [ground.top, rope.start]}
  - {name: hook, type: spherical, joints: [load.hook, rope.end]}
solver:
  t_end: 1
  atol: )" + atol + "\n";
}

}  // namespace

TEST_CASE("Absolute tolerances by kind of coordinate", "[tolerances][scenes]") {
  const Model model = test::loadYaml(ropeScene("{position: 1.0e-3, rotation: 2.0e-4, velocity: 3.0e-5, angular_velocity: 4.0e-6}"));
  const VecX atol = model.absoluteTolerances();
  REQUIRE(atol.size() == model.nq + model.nv);
  int frames = 0, slopes = 0;
  for (const Node& node : model.nodes) {
    INFO(node.name);
    CHECK(atol.segment(node.q, 3).isApproxToConstant(1e-3));
    CHECK(atol.segment(node.q + 3, 3).isApproxToConstant(2e-4));  // φ of the body, r' of the rope nodes
    CHECK(atol.segment(model.nq + node.v, 3).isApproxToConstant(3e-5));
    CHECK(atol.segment(model.nq + node.v + 3, 3).isApproxToConstant(4e-6));
    frames += node.kind == NodeKind::Frame, slopes += node.kind == NodeKind::PointSlope;
  }
  CHECK(frames == 1);
  CHECK(slopes == 3);
  const SolverSpec uniform = parseScene(ropeScene("1.0e-7"), "<test>").solver;
  CHECK(uniform.atol.isUniform());
  CHECK(uniform.atol.angular_velocity == 1e-7);
}
