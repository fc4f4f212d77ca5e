// List edits of a scene built on another (`base:` with add, insert_before, insert_after,
// remove): the composed scene is read like a plain one, and bad edits are reported at the edit.

#include <catch2/catch.hpp>

#include <numbers>

#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// The scene `yaml` read as if it stood in configs/, so `base: pendulum.yaml` finds the pendulum
/// (a 1 kg, 1 m rod hinged at ground.pivot, drawn horizontal with its tip at x = −1).
Scene composed(const std::string& yaml) { return parseScene(yaml, test::configPath("edited_pendulum.yaml")); }

/// The error of composing `yaml`; fails the test when it composes.
SceneError composeError(const std::string& yaml) {
  try {
    composed(yaml);
  } catch (const SceneError& e) {
    return e;
  }
  FAIL("the scene was accepted");
  return SceneError({}, "");
}

}  // namespace

TEST_CASE("A member added to a base scene holds the pendulum up", "[scene][list_edits]") {
  // A vertical rope of 1 m from a hanger above the tip: the rod (1 kg, centroid at 0.5 m) stays
  // horizontal, the rope carries T = m g / 2 by moments about the hinge and stretches by
  // δ = T L / EA; the tip sinks by δ (to first order in δ, the rod's turn moves it 5e-7 m sideways).
  const std::string yaml = R"(
base: pendulum.yaml
insert_before:
  ground.joints.pivot:
    - {name: hanger, position: [-1, 0, 1]}
add:
  members:
    - name: stay
      type: rope
      start: ground.hanger
      end: rod.tip
      length: 1.0
      section: {radius: 1.0e-3}
      material: {density: 1.0, youngs_modulus: 1.5e9}
  constraints:
    - {name: stay_top, type: spherical, joints: [ground.hanger, stay.start]}
    - {name: stay_bottom, type: spherical, joints: [rod.tip, stay.end]}
)";
  const Scene scene = composed(yaml);
  REQUIRE(scene.ground_joints.size() == 2);
  CHECK(scene.ground_joints[0].name == "hanger");  // before the pivot
  REQUIRE(scene.members.size() == 1);
  CHECK(scene.members[0].name == "stay");
  REQUIRE(scene.constraints.size() == 3);
  CHECK(scene.constraints[0].name == "hinge");  // the base's first, the added ones after it

  const double T = 9.81 / 2.0, EA = 1.5e9 * std::numbers::pi * 1e-6, stretch = T * 1.0 / EA;  // 1.04 mm
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const Vec3 tip = model.jointFrame(eq.q.data(), model.findJoint("rod.tip")).r;
  CHECK(tip.z() == Approx(-stretch).epsilon(1e-3));
  CHECK(tip.x() == Approx(-1.0).margin(1e-5));

  // Without the rope the same rod hangs down.
  const Scene base = test::loadScene("pendulum.yaml");
  const Model base_model = compileModel(base);
  const StaticResult hanging = solveEquilibrium(base, base_model, 0.0);
  REQUIRE(hanging.converged);
  CHECK(base_model.jointFrame(hanging.q.data(), base_model.findJoint("rod.tip")).r.z() == Approx(-1.0).epsilon(1e-9));
}

TEST_CASE("Items inserted next to a named item keep the list's order", "[scene][list_edits]") {
  const Scene scene = composed(R"(
base: pendulum.yaml
insert_after:
  bodies.rod.joints.top:
    - {name: middle, position: [0, 0, 0]}
insert_before:
  bodies.rod.joints.top:
    - {name: above, position: [0, 0, 0.6]}
)");
  REQUIRE(scene.bodies.size() == 1);
  std::vector<std::string> names;
  for (const JointSpec& j : scene.bodies[0].joints) names.push_back(j.name);
  CHECK(names == std::vector<std::string>{"above", "top", "middle", "tip"});
}

TEST_CASE("Adding to a list the base lacks creates it", "[scene][list_edits]") {
  const Scene scene = composed(R"(
base: pendulum.yaml
add:
  loads:
    - {name: push, joint: rod.tip, force: [0, 0, -1]}
)");
  REQUIRE(scene.loads.size() == 1);
  CHECK(scene.loads[0].joint == "rod.tip");
  const SceneError e = composeError("base: pendulum.yaml\nadd:\n  lods: [{name: push, joint: rod.tip}]\n");
  CHECK(e.where().path == "add.lods");
  CHECK_THAT(e.what(), Catch::Contains("the base scene has no list 'lods' here (did you mean 'loads'?)"));
}

TEST_CASE("An item removed and added again replaces the base's", "[scene][list_edits]") {
  const Scene scene = composed(R"(
base: pendulum.yaml
remove: [constraints.hinge]
add:
  constraints:
    - {name: hinge, type: spherical, joints: [ground.pivot, rod.top]}
)");
  REQUIRE(scene.constraints.size() == 1);
  CHECK(scene.constraints[0].type == ConstraintType::Spherical);
}

TEST_CASE("Bad list edits are reported at the edit", "[scene][list_edits]") {
  SECTION("removing an item that others refer to names the referrer") {
    const SceneError e = composeError("base: pendulum.yaml\nremove: [bodies.rod]\n");
    CHECK(e.where().path == "remove[0]");
    CHECK(e.where().line == 2);
    CHECK_THAT(e.what(), Catch::Contains("cannot remove 'rod' from the bodies: constraints[0].joints[1] ('rod.top') refers to it"));
  }
  SECTION("removing a joint that a constraint uses") {
    const SceneError e = composeError("base: pendulum.yaml\nremove: [bodies.rod.joints.top]\n");
    CHECK_THAT(e.what(), Catch::Contains("constraints[0].joints[1] ('rod.top') refers to it"));
  }
  SECTION("removing the referrer too is fine") {
    const Scene s = composed("base: pendulum.yaml\nremove: [constraints.hinge, bodies.rod.joints.top]\n");
    CHECK(s.constraints.empty());
    CHECK(s.bodies[0].joints.size() == 1);
  }
  SECTION("an added item whose name the list has") {
    const SceneError e = composeError(R"(base: pendulum.yaml
add:
  bodies:
    - {name: rod, mass: 1, inertia: [1, 1, 1]}
)");
    CHECK(e.where().path == "add.bodies[0].name");
    CHECK(e.where().line == 4);
    CHECK_THAT(e.what(), Catch::Contains("already have an item named 'rod'"));
  }
  SECTION("inserting next to a name the list lacks suggests the close one") {
    const SceneError e = composeError(R"(base: pendulum.yaml
insert_after:
  bodies.rdo:
    - {name: bob, mass: 1, inertia: [1, 1, 1]}
)");
    CHECK(e.where().path == "insert_after.bodies.rdo");
    CHECK_THAT(e.what(), Catch::Contains("the base scene's bodies have no item named 'rdo' (did you mean 'rod'?"));
  }
  SECTION("adding to a list the base cannot have") {
    const SceneError e = composeError("base: pendulum.yaml\nadd:\n  solver: [{name: x}]\n");
    CHECK_THAT(e.what(), Catch::Contains("'solver' is not a list in the base scene"));
  }
  SECTION("an added item is validated like any other, at its line in this scene") {
    const SceneError e = composeError(R"(base: pendulum.yaml
add:
  bodies:
    - {name: bob, mass: -1, inertia: [1, 1, 1]}
)");
    CHECK(e.where().path == "bodies[1].mass");
    CHECK(e.where().line == 4);
  }
  SECTION("list edits need a base") {
    const SceneError e = composeError("name: x\nadd: {bodies: []}\n");
    CHECK_THAT(e.what(), Catch::Contains("'add' needs a 'base' scene"));
  }
}
