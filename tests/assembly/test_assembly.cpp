// Assembly of drawn geometry (solvers/initial_conditions.hpp, io/member_ends.hpp): a luffing
// jib crane (a 20 m lattice jib, two ropes, a load) drawn exactly, rounded to millimetres, and
// with its rope ends naming the joints they hang from reaches the same equilibrium; a drawing
// 10 % off is refused naming the constraint; member ends naming joints in a cycle or an unknown
// joint are refused at the member's key.

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "cranesim/solvers/initial_conditions.hpp"

using namespace cranesim;

namespace {

// The jib at 60° from the horizontal: its tip at (−10, 0, 10√3). JIB_TIP, LOAD_Z and the rope
// ends are filled in per drawing.
constexpr const char* kJibCrane = R"(
name: luffing jib crane
ground:
  joints:
    - {name: foot, position: [0, 0, 0]}
    - {name: mast_top, position: [4, 0, 12]}
trusses:
  - name: jib
    length: 20
    order: 4
    sections:
      - {nodes: [[0.5, 0.5], [-0.5, 0.5], [-0.5, -0.5], [0.5, -0.5]], cross_beams: [[1, 2], [2, 3], [3, 4], [4, 1]]}
      - {nodes: [[0.5, 0.5], [-0.5, 0.5], [-0.5, -0.5], [0.5, -0.5]], cross_beams: [[1, 2], [2, 3], [3, 4], [4, 1]]}
    main_beams: [[1, 1], [2, 2], [3, 3], [4, 4]]
    lacing: type1
    tubes:
      main: {outer_radius: 0.05, inner_radius: 0.04}
      cross: {outer_radius: 0.04, inner_radius: 0.03}
      sub: {outer_radius: 0.03, inner_radius: 0.025}
    material: {density: 7800, youngs_modulus: 2.06e11, poisson_ratio: 0.3}
bodies:
  - name: load
    mass: 1000
    centroid: [0, 0, -0.5]
    inertia: [200, 200, 150]
    position: [-10, 0, LOAD_Z]
    joints: [{name: hook, position: [0, 0, 0]}]
members:
  - {name: jib, type: truss, truss: jib, fidelity: condensed, start: [0, 0, 0], end: JIB_TIP, z_axis: [0, 0, 1]}
  - &rope {name: luffing_rope, type: rope, start: LUFFING_START, end: LUFFING_END, length: 14.9769, segments: 2,
           section: {radius: 0.01}, material: {density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.25}}
  - {<<: *rope, name: hoist_rope, start: HOIST_START, end: HOIST_END, length: 10}
constraints:
  - {name: foot_pin, type: revolute, joints: [ground.foot, jib.start], axis: y}
  - {name: luffing_on_mast, type: spherical, joints: [ground.mast_top, luffing_rope.start]}
  - {name: luffing_on_jib, type: spherical, joints: [jib.end, luffing_rope.end]}
  - {name: hoist_on_jib, type: spherical, joints: [jib.end, hoist_rope.start]}
  - {name: hook, type: spherical, joints: [load.hook, hoist_rope.end]}
solver: {t_end: 1}
)";

struct Drawing {
  std::string jib_tip, load_z, luffing_start, luffing_end, hoist_start, hoist_end;
};

const Drawing kExact{"[-10, 0, 17.320508075688775]", "7.320508075688775", "[4, 0, 12]", "[-10, 0, 17.320508075688775]",
                     "[-10, 0, 17.320508075688775]", "[-10, 0, 7.320508075688775]"};
const Drawing kMillimetres{"[-10, 0, 17.321]", "7.321", "[4, 0, 12]", "[-10, 0, 17.321]", "[-10, 0, 17.321]", "[-10, 0, 7.321]"};
const Drawing kNamedJoints{"[-10, 0, 17.321]", "7.321", "ground.mast_top", "jib.end", "jib.end", "load.hook"};

std::string sceneText(const Drawing& d) {
  std::string text = kJibCrane;
  const auto put = [&](const std::string& key, const std::string& value) {
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
      text.replace(at, key.size(), value);
  };
  put("JIB_TIP", d.jib_tip);
  put("LOAD_Z", d.load_z);
  put("LUFFING_START", d.luffing_start);
  put("LUFFING_END", d.luffing_end);
  put("HOIST_START", d.hoist_start);
  put("HOIST_END", d.hoist_end);
  return text;
}

struct JibEquilibrium {
  Vec3 hook, jib_tip;
  AssemblyMove move;
};

JibEquilibrium solveJib(const Drawing& d) {
  const Scene scene = parseScene(sceneText(d), "<jib>");
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  JibEquilibrium out;
  assembledInitialState(assembler, 0.0, model.q0, model.v0, scene.solver.assembly_tolerance, &out.move);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  INFO(eq.message);
  REQUIRE(eq.converged);
  out.hook = model.jointFrame(eq.q.data(), model.findJoint("load.hook")).r;
  out.jib_tip = model.jointFrame(eq.q.data(), model.findJoint("jib.end")).r;
  return out;
}

}  // namespace

TEST_CASE("A jib crane drawn to millimetres, or with rope ends naming joints, assembles to the exact drawing's equilibrium",
          "[assembly]") {
  const JibEquilibrium exact = solveJib(kExact);
  const JibEquilibrium rounded = solveJib(kMillimetres);
  const JibEquilibrium named = solveJib(kNamedJoints);
  CHECK(exact.move.displacement < 1e-12);
  // The millimetre drawing is closed by sub-millimetre moves, and they are reported.
  CHECK(rounded.move.displacement > 1e-4);
  CHECK(rounded.move.displacement < 1e-3);
  CHECK(rounded.move.scene_size == Approx(23.0).margin(0.5));  // mast top to jib tip, foot to tip
  for (const JibEquilibrium* other : {&rounded, &named}) {
    CHECK((other->hook - exact.hook).norm() < 1e-9);
    CHECK((other->jib_tip - exact.jib_tip).norm() < 1e-9);
  }
  // The load hangs below the tip on its 10 m rope (slightly stretched), not where it was drawn.
  CHECK(exact.hook.x() == Approx(exact.jib_tip.x()).margin(1e-6));
  CHECK(exact.jib_tip.z() - exact.hook.z() == Approx(10.0).epsilon(1e-3));
}

TEST_CASE("A drawing 10 % off is refused naming the constraint that does not close", "[assembly]") {
  Drawing off = kExact;
  off.hoist_end = "[-12.4, 0, 7.320508075688775]";  // 2.4 m beside the hook: 10 % of the 23 m scene
  const Scene scene = parseScene(sceneText(off), "<jib>");
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  try {
    assembledInitialState(assembler, 0.0, model.q0, model.v0, scene.solver.assembly_tolerance);
    FAIL("a drawing 10 % off was assembled");
  } catch (const SceneError& e) {
    CHECK(e.where().path == "constraints[4]");
    CHECK_THAT(e.what(), Catch::Contains("the drawing is off: |Φ| = 2.4 in 'hook/x'") &&
                             Catch::Contains("more than solver.assembly_tolerance = 0.001"));
  }
}

TEST_CASE("A truss drawn to millimetres keeps its type's length, one drawn 1 % short is refused", "[assembly]") {
  Drawing short_jib = kExact;
  short_jib.jib_tip = "[-9.9, 0, 17.147]";  // 19.8 m
  try {
    parseScene(sceneText(short_jib), "<jib>");
    FAIL("a 19.8 m drawing of a 20 m truss was accepted");
  } catch (const SceneError& e) {
    CHECK(e.where().path == "members[0].end");
    CHECK_THAT(e.what(), Catch::Contains("differs from the length 20 of truss type 'jib'"));
  }
  const Scene rounded = parseScene(sceneText(kMillimetres), "<jib>");
  const Model model = compileModel(rounded);
  const Vec3 tip = model.jointFrame(model.q0.data(), model.findJoint("jib.end")).r;
  CHECK(tip.norm() == Approx(20.0).epsilon(1e-14));
}

TEST_CASE("Member ends naming joints: any order, node joints, and clear errors", "[assembly]") {
  SECTION("a member named before it is drawn, through its node") {
    Drawing d = kMillimetres;
    d.luffing_end = "hoist_rope.n0";  // the hoist rope's first node: its start at the jib tip
    const Scene scene = parseScene(sceneText(d), "<jib>");
    CHECK((scene.members[1].end - Vec3(-10, 0, 17.321)).norm() < 1e-12);
  }
  SECTION("a truss end-section node") {
    Drawing d = kMillimetres;
    d.luffing_end = "jib.s2n1";
    const Scene scene = parseScene(sceneText(d), "<jib>");
    const Model model = compileModel(scene);
    const Vec3 node = model.jointFrame(model.q0.data(), model.findJoint("jib.s2n1")).r;
    CHECK((scene.members[1].end - node).norm() < 1e-12);
  }
  SECTION("a cycle") {
    Drawing d = kMillimetres;
    d.luffing_end = "hoist_rope.start";
    d.hoist_start = "luffing_rope.end";
    CHECK_THROWS_WITH(parseScene(sceneText(d), "<jib>"),
                      Catch::Contains("in a cycle (luffing_rope → hoist_rope → luffing_rope)"));
  }
  SECTION("an unknown joint, a node out of range") {
    Drawing d = kMillimetres;
    d.hoist_end = "load.hock";
    CHECK_THROWS_WITH(parseScene(sceneText(d), "<jib>"), Catch::Contains("body 'load' has no joint 'hock'"));
    d.hoist_end = "luffing_rope.n3";
    CHECK_THROWS_WITH(parseScene(sceneText(d), "<jib>"), Catch::Contains("offers start, end and its nodes n0 … n2"));
  }
}
