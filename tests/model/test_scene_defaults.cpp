// A scene's `defaults:`: a truss section that leaves out its fidelity takes
// defaults.truss_fidelity, and says so; without a default the fidelity is required.

#include <catch2/catch.hpp>

#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// The type 2 cantilever (configs/truss_type2_super.yaml) with its boom replaced by one that
/// gives no fidelity, and a second section that gives its own; `defaults` is added as written.
std::string cantilever(const std::string& defaults) {
  return defaults + R"(
base: truss_type2_super.yaml
remove: [constraints.clamp, members.boom]
add:
  members:
    - {name: boom, type: truss, truss: type2, start: [0, 0, 0], end: [15, 0, 0], z_axis: [0, 0, 1]}
    - {name: outer, type: truss, truss: type2, start: [15, 0, 0], end: [30, 0, 0], z_axis: [0, 0, 1], fidelity: beam}
  constraints:
    - {name: clamp, type: fixed, joints: [ground.wall, boom.start]}
    - {name: splice, type: fixed, joints: [boom.end, outer.start]}
)";
}

Scene composed(const std::string& yaml) { return parseScene(yaml, test::configPath("defaults_test.yaml")); }

}  // namespace

TEST_CASE("A truss section without a fidelity takes the scene's default", "[scene][truss][defaults]") {
  const Scene scene = composed(cantilever("defaults: {truss_fidelity: condensed}\n"));
  REQUIRE(scene.members.size() == 2);
  CHECK(scene.members[0].fidelity == TrussFidelity::Condensed);
  CHECK(scene.members[0].fidelity_by_default);
  CHECK(scene.members[1].fidelity == TrussFidelity::Beam);
  CHECK_FALSE(scene.members[1].fidelity_by_default);

  // The defaulted section is the condensed element of truss_type2_condensed.yaml: 12
  // coordinates per section, the same as that scene's one section.
  const Model condensed = compileModel(test::loadScene("truss_type2_condensed.yaml"));
  const Scene alone = composed(R"(
defaults: {truss_fidelity: condensed}
base: truss_type2_super.yaml
remove: [constraints.clamp, members.boom]
add:
  members: [{name: boom, type: truss, truss: type2, start: [0, 0, 0], end: [15, 0, 0], z_axis: [0, 0, 1]}]
  constraints: [{name: clamp, type: fixed, joints: [ground.wall, boom.start]}]
)");
  CHECK(compileModel(alone).nq == condensed.nq);
}

TEST_CASE("A truss section without a fidelity and no default is refused", "[scene][truss][defaults]") {
  try {
    composed(cantilever(""));
    FAIL("accepted");
  } catch (const SceneError& e) {
    CHECK(e.where().path == "members[0]");
    CHECK_THAT(e.what(), Catch::Contains("missing field 'fidelity'"));
    CHECK_THAT(e.what(), Catch::Contains("defaults.truss_fidelity"));
  }
}

TEST_CASE("An unknown default fidelity is refused at its line", "[scene][truss][defaults]") {
  try {
    composed(cantilever("defaults: {truss_fidelity: condenced}\n"));
    FAIL("accepted");
  } catch (const SceneError& e) {
    CHECK(e.where().path == "defaults.truss_fidelity");
    CHECK(e.where().line == 1);
  }
}
