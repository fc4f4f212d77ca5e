// Booms assembled from their sections (`booms:`, src/io/boom_assembly.cpp) on the thesis crane:
// configs/crane_configured.yaml against configs/crane.yaml, which draws every coordinate by
// hand, and the same configuration with one 15 m insert more and one fewer; booms drawn where
// their equilibrium meets stated figures.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "cranesim/crane/crane_figures.hpp"
#include "cranesim/crane/stated_equilibrium_search.hpp"
#include "cranesim/planning/target.hpp"
#include "cranesim/session/session.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

const MemberSpec& member(const Scene& scene, const std::string& name) {
  for (const MemberSpec& m : scene.members)
    if (m.name == name) return m;
  FAIL("no member " << name);
  return scene.members.front();
}

const RigidBodySpec& body(const Scene& scene, const std::string& name) {
  for (const RigidBodySpec& b : scene.bodies)
    if (b.name == name) return b;
  FAIL("no body " << name);
  return scene.bodies.front();
}

/// The thesis crane's drawing by hand from its tables (Appendix D), in the x–z plane: the foot
/// pin at the origin, the main boom of `boom_length` at `angle_deg` (85°) towards −x, its head
/// frame x along the boom and z = x × y; the derrick's 26 m at 65° towards +x.
struct ThesisGeometry {
  explicit ThesisGeometry(double boom_length, double angle_deg = 85.0) {
    x = Vec3(-std::cos(angle_deg * kDeg), 0.0, std::sin(angle_deg * kDeg));
    z = x.cross(Vec3::UnitY());
    head = boom_length * x;
    tie_joint = head + 1.75 * x - 1.4 * z;   // head joint 3 (Table D-5)
    sheave = head + 2.2 * x + 1.7 * z;       // head joint 4
    derrick_top = 26.0 * Vec3(std::cos(65.0 * kDeg), 0.0, std::sin(65.0 * kDeg));
  }
  Vec3 x, z, head, tie_joint, sheave, derrick_top;
};

/// Positions of the joints that show the crane's shape in its static equilibrium at t = 0.
std::map<std::string, Vec3> equilibriumJoints(const Scene& scene) {
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  std::map<std::string, Vec3> at;
  for (const char* joint : {"pedestal.origin", "boom1.end", "boom2.end", "boom3.end", "boom4.end", "head.origin", "head.tie",
                            "head.sheave", "derrick1.end", "derrick3.end", "tie1.end", "tie2.end", "load.origin", "load.bottom"})
    at[joint] = model.jointFrame(eq.q.data(), model.findJoint(joint)).r;
  return at;
}

std::string point(const Vec3& p) { return fmt::format("[{:.17g}, {:.17g}, {:.17g}]", p.x(), p.y(), p.z()); }

}  // namespace

TEST_CASE("The configured thesis crane is drawn where crane.yaml draws it", "[scene][boom_assembly]") {
  const Scene configured = test::loadScene("crane_configured.yaml"), drawn = test::loadScene("crane.yaml");
  const ThesisGeometry hand(55.0);
  // crane.yaml rounds each coordinate to 1e-6 m and each direction component to 1e-7: a point
  // lies within √3 · 5e-7 m of the exact one. Its ties' joints lie off the straight line from
  // the head's tie joint to the derrick's top, by 0.1 and 0.2 mm (their direction is 6 µrad off).
  for (const char* name : {"boom1", "boom2", "boom3", "boom4", "boom5", "derrick1", "derrick2", "derrick3", "tie1", "tie2",
                           "luffing_rope", "sub_cable", "hoist_rope"}) {
    INFO(name);
    const MemberSpec &c = member(configured, name), &d = member(drawn, name);
    const bool on_luffing_line = std::string(name).rfind("tie", 0) == 0 || std::string(name) == "luffing_rope";
    CHECK(c.type == d.type);
    CHECK((c.start - d.start).norm() < (on_luffing_line && std::string(name) != "tie1" ? 1e-4 : 9e-7));
    CHECK((c.end - d.end).norm() < (on_luffing_line ? 2e-4 : 9e-7));
    CHECK((c.end - c.start).norm() == Approx((d.end - d.start).norm()).margin(on_luffing_line ? 2e-5 : 2e-6));
    CHECK(c.damping == d.damping);
    if (c.type == MemberType::Truss) {
      CHECK(c.truss == d.truss);
      CHECK(c.fidelity == d.fidelity);
      CHECK((c.z_axis - d.z_axis).norm() < 1e-7);
    }
  }
  CHECK(configured.members.size() == drawn.members.size());
  CHECK((body(configured, "head").position - hand.head).norm() < 1e-12);
  CHECK((body(configured, "head").position - body(drawn, "head").position).norm() < 9e-7);
  CHECK((body(configured, "head").rotation - body(drawn, "head").rotation).norm() < 1e-12);
  CHECK((body(configured, "load").position - (hand.sheave - 54.8342 * Vec3::UnitZ())).norm() < 1e-12);
  CHECK((body(configured, "load").position - body(drawn, "load").position).norm() < 9e-7);

  // The luffing line runs straight from the head's tie joint to the derrick's top: two 15 m
  // ties, then the rope over the rest, 6.145284 m (crane.yaml states it to 0.1 mm: 6.1453).
  const double rope = (hand.derrick_top - hand.tie_joint).norm() - 30.0;
  CHECK((*member(configured, "luffing_rope").length)(0.0) == Approx(rope).margin(1e-12));
  CHECK((*member(configured, "luffing_rope").length)(0.0) == Approx(6.1453).margin(5e-5));
  CHECK((member(configured, "tie1").start - hand.tie_joint).norm() < 1e-12);
  CHECK((member(configured, "tie2").end - member(configured, "luffing_rope").end).norm() < 1e-12);
  CHECK((member(configured, "tie2").end - member(configured, "tie2").start).norm() == Approx(15.0).margin(1e-12));
  CHECK((*member(configured, "hoist_rope").length)(0.0) == 54.8342);

  // The same parts joined by as many constraints of the same kinds: the models have the same size.
  CHECK(configured.constraints.size() == drawn.constraints.size());
  const Model c = compileModel(configured), d = compileModel(drawn);
  CHECK(c.nq == d.nq);
  CHECK(c.m == d.m);
}

TEST_CASE("The configured thesis crane stands as crane.yaml drawn exactly, to 1e-9 m", "[scene][boom_assembly][crane]") {
  // crane.yaml with its rounding taken out: the ties drawn at their exact points along the
  // luffing line (a strut tie is unstressed at its drawn length) and the luffing rope at its
  // exact length. The booms, the head and the load as crane.yaml draws them: a truss section
  // takes its type's length, the fixed joints their frames, the ropes their stated lengths, so
  // the booms' drawn coordinates only start the solver.
  const ThesisGeometry hand(55.0);
  const Vec3 along = (hand.derrick_top - hand.tie_joint).normalized();
  const std::string exact = fmt::format(R"(
base: crane.yaml
modify:
  members.tie1.start: {}
  members.tie1.end: {}
  members.tie2.start: {}
  members.tie2.end: {}
  members.luffing_rope.end: {}
  members.luffing_rope.length: {:.17g}
)", point(hand.tie_joint), point(hand.tie_joint + 15.0 * along), point(hand.tie_joint + 15.0 * along),
                                        point(hand.tie_joint + 30.0 * along), point(hand.tie_joint + 30.0 * along),
                                        (hand.derrick_top - hand.tie_joint).norm() - 30.0);
  const auto drawn_exactly = equilibriumJoints(parseScene(exact, test::configPath("crane_exact.yaml")));
  const auto configured = equilibriumJoints(test::loadScene("crane_configured.yaml"));
  const auto drawn = equilibriumJoints(test::loadScene("crane.yaml"));
  double rounding = 0.0;
  for (const auto& [joint, r] : configured) {
    INFO(joint);
    CHECK((r - drawn_exactly.at(joint)).norm() < 1e-9);
    rounding = std::max(rounding, (r - drawn.at(joint)).norm());
  }
  // crane.yaml as written: its 16 µm longer luffing rope and its ties' rounded lengths move the
  // joints by up to 53 µm.
  CHECK(rounding > 1e-6);
  CHECK(rounding < 1e-4);
}

namespace {

const RopeTension& tensionOf(const CraneFigures& figures, const std::string& rope) {
  for (const RopeTension& r : figures.ropes)
    if (r.rope == rope) return r;
  FAIL("no rope " << rope);
  return figures.ropes.front();
}

/// The root of the increasing or decreasing `f` in [lo, hi], by bisection.
template <class F> double root(const F& f, double lo, double hi) {
  const bool rising = f(hi) > f(lo);
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) > 0.0) == rising ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

/// `p` (x, z) turned by `angle` about the y axis through the origin, in the x–z plane.
Eigen::Vector2d turned(const Eigen::Vector2d& p, double angle) { return Eigen::Rotation2Dd(angle) * p; }
Eigen::Vector2d xz(const Vec3& p) { return {p.x(), p.z()}; }

/// The configured crane's equilibrium by hand from its drawing `hand` (ties reaching `reach` m
/// down the luffing line) and the forces of the equilibrium `eq`: the luffing line and the
/// sub-cable stretch by T L / EA and the booms' four chords shorten by N L / EA; the derrick
/// turns until its top hangs on the stretched sub-cable, then the boom until its tie joint
/// reaches the stretched line (as the hand calculation of tests/crane/test_crane_figures.cpp for
/// crane.yaml). Left out: the booms' bending and the lacing's share of the axial force, the
/// ropes' sag and the ties' weight.
struct HandStretch {
  HandStretch(const ThesisGeometry& hand, double reach, const Model& model, const StaticResult& eq, const CraneFigures& f) {
    const auto force = [&](const char* constraint) {
      return constraintLoad(model.constraints[static_cast<std::size_t>(model.findConstraint(constraint))], eq.lambda.data()).force;
    };
    const auto meanTension = [&](const char* r) { return 0.5 * (tensionOf(f, r).at_start + tensionOf(f, r).at_end); };
    const double rope_EA = 1.0e11 * std::numbers::pi * 0.05 * 0.05, tie_EA = 2.06e11 * std::numbers::pi * 0.05 * 0.05;
    const double chords_EA = 4.0 * 2.06e11 * std::numbers::pi * (0.1 * 0.1 - 0.08 * 0.08);
    const double rope = (hand.derrick_top - hand.tie_joint).norm() - reach;  // as the tool sizes it
    const double sub_cable = 23.5640 * (1.0 + meanTension("sub_cable") / rope_EA);
    const double line = reach * (1.0 + force("tie1_start") / tie_EA) + rope * (1.0 + meanTension("luffing_rope") / rope_EA);
    const double derrick_scale = 1.0 - force("derrick_foot") / chords_EA;
    boom_scale = 1.0 - force("boom_foot") / chords_EA;
    const Eigen::Vector2d A(11.0, 0.0), D0 = derrick_scale * xz(hand.derrick_top), H0 = boom_scale * xz(hand.tie_joint);
    const double derrick_turn = root([&](double a) { return (turned(D0, a) - A).norm() - sub_cable; }, -0.1, 0.1);
    const Eigen::Vector2d D = turned(D0, derrick_turn);
    boom_turn = root([&](double b) { return (turned(H0, b) - D).norm() - line; }, -0.1, 0.1);
  }
  /// Where a point of the boom drawn at `drawn` stands in equilibrium (x, z).
  Eigen::Vector2d placed(const Vec3& drawn) const { return turned(boom_scale * xz(drawn), boom_turn); }

  double boom_scale = 1.0, boom_turn = 0.0;  // rad about y: negative lowers the boom
};

}  // namespace

TEST_CASE("One 15 m insert more or fewer: drawn by the tool, standing as the hand calculation says",
          "[scene][boom_assembly][crane]") {
  struct Configuration {
    const char* scene;
    double boom_length;     // m: 5 + 15 n + 5
    int ties;
    double hanging_length;  // m: the hoist rope's unstretched length
  };
  const auto [file, boom_length, ties, hanging_length] =
      GENERATE(Configuration{"crane_configured_long.yaml", 70.0, 2, 69.8342},
               Configuration{"crane_configured_short.yaml", 40.0, 1, 39.8342});
  INFO(file);
  const Scene scene = test::loadScene(file);
  const Model model = compileModel(scene);
  const ThesisGeometry hand(boom_length);
  const double reach = 15.0 * ties;

  // As drawn, rigid: the head at the boom's length along 85°, the luffing rope over what the
  // ties leave of the line from the head's tie joint to the derrick's top, the hook the hanging
  // length under the sheave.
  const CraneFigures drawn = craneFigures(scene, model, model.q0.data(), 0.0);
  REQUIRE(drawn.boom);
  CHECK(drawn.boom->boom_angle_deg == Approx(85.0).margin(1e-9));
  CHECK(drawn.boom->head_height == Approx(boom_length * std::sin(85.0 * kDeg)).margin(1e-9));
  CHECK(drawn.boom->hook_radius == Approx(-hand.sheave.x()).margin(1e-9));
  CHECK(drawn.boom->hook_height == Approx(hand.sheave.z() - hanging_length).margin(1e-9));
  const double rope = (hand.derrick_top - hand.tie_joint).norm() - reach;
  CHECK((*member(scene, "luffing_rope").length)(0.0) == Approx(rope).margin(1e-12));

  // In equilibrium: stretched and shortened as the hand calculation HandStretch says.
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const CraneFigures f = craneFigures(scene, model, eq.q.data(), eq.t);
  const Eigen::Vector2d head = HandStretch(hand, reach, model, eq, f).placed(hand.head);
  const double hand_angle = std::atan2(head.y(), -head.x()) / kDeg;
  CHECK(f.boom->boom_angle_deg == Approx(hand_angle).margin(0.05));
  CHECK(f.boom->head_height == Approx(head.y()).margin(0.01));
  CHECK(85.0 - f.boom->boom_angle_deg > 0.2);  // the stretch counts
}

TEST_CASE("A truss type at another length in whole bays", "[scene][boom_assembly]") {
  // Two 15 m type 2 inserts as one 30 m section of 12 bays: the boom's head where the three
  // inserts put it, one section (and one splice) fewer.
  const Scene three = test::loadScene("crane_configured.yaml");
  const Scene joined = parseScene(R"(
base: crane_configured.yaml
remove: [booms.boom.sections.boom4]
modify:
  booms.boom.sections.boom3.length: 30
)", test::configPath("joined.yaml"));
  CHECK((body(joined, "head").position - body(three, "head").position).norm() < 1e-12);
  CHECK(member(joined, "boom3").truss == "type2_12bays");
  const auto type = std::find_if(joined.trusses.begin(), joined.trusses.end(),
                                 [](const TrussDescription& d) { return d.name == "type2_12bays"; });
  REQUIRE(type != joined.trusses.end());
  CHECK(type->length == 30.0);
  CHECK(type->order == 12);
  CHECK(joined.members.size() + 1 == three.members.size());
  const Model model = compileModel(joined);
  CHECK(solveEquilibrium(joined, model, 0.0).converged);
}

TEST_CASE("The boom angle the luffing rope gives", "[scene][boom_assembly]") {
  const auto withRope = [](double rope) {
    return parseScene(fmt::format(R"(
base: crane_configured.yaml
modify:
  booms.boom.angle_deg: from_luffing_rope
  booms.boom.luffing.rope_length: {:.17g}
)", rope), test::configPath("from_rope.yaml"));
  };
  const ThesisGeometry at85(55.0);
  // The rope the tool sizes for 85° gives 85° back.
  const Scene same = withRope((at85.derrick_top - at85.tie_joint).norm() - 30.0);
  CHECK((body(same, "head").position - at85.head).norm() < 1e-9);

  // crane.yaml's 6.1453 m rope, by the law of cosines in the triangle of the foot pin O, the
  // derrick's top D (26 m at 65°) and the head's tie joint H, which lies ρ_H from O at the fixed
  // angle ε below the boom axis: |D − H| = 36.1453 m fixes the angle at O between D and H.
  const double rho_D = 26.0, rho_H = at85.tie_joint.norm(), line = 30.0 + 6.1453;
  const double epsilon = 95.0 - std::atan2(at85.tie_joint.z(), at85.tie_joint.x()) / kDeg;  // H below the axis
  const double at_O = std::acos((rho_D * rho_D + rho_H * rho_H - line * line) / (2.0 * rho_D * rho_H)) / kDeg;
  const double hand_angle = 180.0 - (65.0 + at_O) - epsilon;
  const Scene scene = withRope(6.1453);
  const Model model = compileModel(scene);
  const CraneFigures drawn = craneFigures(scene, model, model.q0.data(), 0.0);
  CHECK(hand_angle == Approx(85.0).margin(1e-3));  // 16 µm more rope: a little lower
  CHECK(hand_angle < 85.0);
  CHECK(drawn.boom->boom_angle_deg == Approx(hand_angle).margin(1e-9));
  CHECK((*member(scene, "luffing_rope").length)(0.0) == Approx(6.1453).margin(1e-12));
}

TEST_CASE("A hook at a stated height, and a jib standing on the boom's head", "[scene][boom_assembly]") {
  // The hoist by hook height: the rope's unstretched length is the sheave's height less it. A
  // 5 m jib (truss type 3) pinned at the head's joint j5 (0, 0, 1.2 in the boom's frame), its own
  // pin the head's y axis, at 30° towards −x: its end 5 m along (−cos 30°, 0, sin 30°) from j5
  // (held by nothing: it is drawn, not stood).
  const Scene scene = parseScene(R"(
base: crane_configured.yaml
modify:
  booms.boom.hoist: {sheave: sheave, hook_height: 2.5, hook: load.origin,
                     rope: {name: hoist_rope, section: {radius: 0.05}, material: {density: 7800, youngs_modulus: 1.0e11}}}
add:
  booms:
    - {name: jib, foot: head.j5, towards: [-1, 0, 0], angle_deg: 30, sections: [{name: jib1, truss: type3}]}
)", test::configPath("jib.yaml"));
  const ThesisGeometry hand(55.0);
  CHECK((*member(scene, "hoist_rope").length)(0.0) == Approx(hand.sheave.z() - 2.5).margin(1e-12));
  CHECK(body(scene, "load").position.z() == Approx(2.5).margin(1e-12));
  const Vec3 j5 = hand.head + 1.2 * hand.z;
  const Vec3 along(-std::cos(30.0 * kDeg), 0.0, std::sin(30.0 * kDeg));
  CHECK((member(scene, "jib1").start - j5).norm() < 1e-12);
  CHECK((member(scene, "jib1").end - (j5 + 5.0 * along)).norm() < 1e-12);
  CHECK(std::any_of(scene.constraints.begin(), scene.constraints.end(), [](const ConstraintSpec& c) {
    return c.name == "jib_foot" && c.type == ConstraintType::Revolute && c.joint1 == "head.j5" && c.joint2 == "jib1.start";
  }));
  CHECK_NOTHROW(compileModel(scene));  // its pin lines up with the head's: the drawing closes (the jib hangs free)
}

TEST_CASE("A boom drawn where its equilibrium holds the hook at a stated radius", "[scene][boom_assembly][crane]") {
  // crane_configured.yaml (55 m boom, two ties) with the hook stated 30 m from the slewing axis,
  // for a light and a heavy load. Rigid, the hook hangs under the sheave, 57.2 m up the boom and
  // 1.7 m off its axis: radius 57.2 cos a + 1.7 sin a. Loaded, the ropes and ties stretch and the
  // chords shorten (HandStretch), so the boom is drawn steeper than that rigid angle.
  const double stated = 30.0;
  const double mass = GENERATE(50000.0, 200000.0);
  INFO(mass << " kg");
  const Scene scene = parseScene(fmt::format(R"(
base: crane_configured.yaml
modify:
  booms.boom.angle_deg: from_equilibrium
  booms.boom.equilibrium: {{hook_radius: {}}}
  bodies.load.mass: {}
)", stated, mass), test::configPath("at_radius.yaml"));
  REQUIRE(scene.stated_equilibrium);
  const StatedEquilibriumSearch search = searchStatedEquilibrium(scene);
  CHECK(search.equilibria <= 6);
  const Scene drawn = sceneAtStatedEquilibrium(scene, true);
  CHECK_FALSE(drawn.stated_equilibrium);
  const Model model = compileModel(drawn);
  const StaticResult eq = solveEquilibrium(drawn, model, 0.0);
  REQUIRE(eq.converged);
  const CraneFigures f = craneFigures(drawn, model, eq.q.data(), eq.t);
  CHECK(f.boom->hook_radius == Approx(stated).margin(kStatedRadiusTolerance));
  CHECK(model.jointFrame(model.q0.data(), model.findJoint("boom5.end")).r.normalized().dot(ThesisGeometry(1.0, search.drawing.angle_deg).x) ==
        Approx(1.0).margin(1e-12));  // drawn at the angle found

  const auto rigidRadius = [](double a) { return 57.2 * std::cos(a * kDeg) + 1.7 * std::sin(a * kDeg); };
  const double rigid_angle = root([&](double a) { return rigidRadius(a) - stated; }, 10.0, 89.0);
  const ThesisGeometry at_found(55.0, search.drawing.angle_deg);
  const HandStretch stretch(at_found, 30.0, model, eq, f);
  const auto handRadius = [&](double a) { return -stretch.placed(ThesisGeometry(55.0, a).sheave).x(); };
  const double hand_angle = root([&](double a) { return handRadius(a) - stated; }, 10.0, 89.0);
  CHECK(search.drawing.angle_deg == Approx(hand_angle).margin(0.05));
  CHECK(search.drawing.angle_deg - rigid_angle > (mass > 1e5 ? 0.4 : 0.1));  // the stretch counts
  UNSCOPED_INFO("rigid " << rigid_angle << "°, hand with stretch " << hand_angle << "°, found " << search.drawing.angle_deg << "°");
}

TEST_CASE("A boom drawn where its equilibrium stands at a stated boom angle", "[scene][boom_assembly][crane]") {
  const Scene scene = parseScene(R"(
base: crane_configured.yaml
modify:
  booms.boom.angle_deg: from_equilibrium
  booms.boom.equilibrium: {boom_angle_deg: 60}
)", test::configPath("at_angle.yaml"));
  const StatedEquilibriumSearch search = searchStatedEquilibrium(scene);
  CHECK(search.figure == Approx(60.0).margin(kStatedBoomAngleTolerance));
  const Scene drawn = sceneAtStatedEquilibrium(scene, true);
  const Model model = compileModel(drawn);
  const StaticResult eq = solveEquilibrium(drawn, model, 0.0);
  REQUIRE(eq.converged);
  const CraneFigures f = craneFigures(drawn, model, eq.q.data(), eq.t);
  CHECK(f.boom->boom_angle_deg == Approx(60.0).margin(kStatedBoomAngleTolerance));
  // Drawn steeper by the stretch, as the hand calculation at the angle found says.
  const HandStretch stretch(ThesisGeometry(55.0, search.drawing.angle_deg), 30.0, model, eq, f);
  const Eigen::Vector2d head = stretch.placed(ThesisGeometry(55.0, search.drawing.angle_deg).head);
  CHECK(std::atan2(head.y(), -head.x()) / kDeg == Approx(60.0).margin(0.05));
  CHECK(search.drawing.angle_deg - 60.0 > 0.2);
}

TEST_CASE("A hoist rope sized where its equilibrium holds the hook at a stated height", "[scene][boom_assembly][crane]") {
  // crane_configured.yaml at its 85° with the hook stated 5 m above the ground: the rope the
  // tool finds is the one that, hanging from the sheave where the equilibrium puts it and
  // stretched under the 390 t load and its own weight, reaches down to 5 m — the stretch
  // δ = (W L + ρ g A L² / 2) / EA, about 0.24 m, is what it leaves out of the drawn length.
  const double stated = 5.0;
  const Scene scene = parseScene(fmt::format(R"(
base: crane_configured.yaml
modify:
  booms.boom.hoist.hanging_length: from_equilibrium
  booms.boom.equilibrium: {{hook_height: {}}}
)", stated), test::configPath("at_height.yaml"));
  REQUIRE(scene.stated_equilibrium);
  const StatedEquilibriumSearch search = searchStatedEquilibrium(scene);
  CHECK(search.equilibria <= 3);  // the hook moves by the rope's change, stretched: by 0.5 % more
  const Scene drawn = sceneAtStatedEquilibrium(scene, true);
  const Model model = compileModel(drawn);
  const StaticResult eq = solveEquilibrium(drawn, model, 0.0);
  REQUIRE(eq.converged);
  const CraneFigures f = craneFigures(drawn, model, eq.q.data(), eq.t);
  CHECK(f.boom->hook_height == Approx(stated).margin(kStatedHookHeightTolerance));
  CHECK(f.boom->boom_angle_deg < 85.0);  // the angle is not searched: drawn at 85°, lowered by the stretch
  CHECK(f.boom->boom_angle_deg > 84.0);
  const double L = (*member(drawn, "hoist_rope").length)(0.0);
  CHECK(L == search.drawing.hanging_length);

  const double g = 9.8, W = 390000.6 * g, A = std::numbers::pi * 0.05 * 0.05, EA = 1.0e11 * A;
  const double sheave = model.jointFrame(eq.q.data(), model.findJoint("head.sheave")).r.z();
  const double hand = root([&](double l) { return l + (W * l + 7800.0 * g * A * l * l / 2.0) / EA - (sheave - stated); },
                           1.0, sheave);
  // The rope's Green–Lagrange strain ε(1 + ε/2) leaves ε²/2 L ≈ 0.7 mm of the stretch to the
  // linear formula; the search's tolerance 1 mm.
  CHECK(L == Approx(hand).margin(2.0e-3));
  CHECK(sheave - stated - L > 0.2);  // the stretch counts
}

TEST_CASE("A boom drawn where its equilibrium holds the hook at a stated radius and height", "[scene][boom_assembly][crane]") {
  // The boom angle and the hoist rope found together: 100 t at 30 m, 10 m above the ground.
  const Scene scene = parseScene(R"(
base: crane_configured.yaml
modify:
  booms.boom.angle_deg: from_equilibrium
  booms.boom.hoist.hanging_length: from_equilibrium
  booms.boom.equilibrium: {hook_radius: 30, hook_height: 10}
  bodies.load.mass: 100000
)", test::configPath("at_radius_and_height.yaml"));
  const StatedEquilibriumSearch search = searchStatedEquilibrium(scene);
  CHECK(search.equilibria <= 7);
  const Scene drawn = sceneAtStatedEquilibrium(scene, true);
  const Model model = compileModel(drawn);
  const StaticResult eq = solveEquilibrium(drawn, model, 0.0);
  REQUIRE(eq.converged);
  const CraneFigures f = craneFigures(drawn, model, eq.q.data(), eq.t);
  CHECK(f.boom->hook_radius == Approx(30.0).margin(kStatedRadiusTolerance));
  CHECK(f.boom->hook_height == Approx(10.0).margin(kStatedHookHeightTolerance));
  CHECK(search.figure == Approx(f.boom->hook_radius).margin(1e-9));
  CHECK(search.hook_height == Approx(f.boom->hook_height).margin(1e-9));
}

TEST_CASE("crane-opt's target and a session draw a stated equilibrium as run and static do", "[scene][boom_assembly][crane]") {
  // A scene stating the hook's radius, read by crane-opt's target and by a step-by-step session:
  // each draws the boom where `sceneAtStatedEquilibrium` does, none at the search's first angle.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "cranesim_stated_readers";
  std::filesystem::create_directories(dir);
  const std::filesystem::path scene_path = dir / "at_radius.yaml", target_path = dir / "target.yaml";
  std::ofstream(scene_path) << fmt::format(R"(
base: {}
modify:
  booms.boom.angle_deg: from_equilibrium
  booms.boom.equilibrium: {{hook_radius: 25}}
  bodies.load.mass: 100000
)", test::configPath("crane_configured.yaml"));
  std::ofstream(target_path) << fmt::format(R"(
scene: {}
method: flatness
crane: {{luffing_rope: luffing_rope, hoist_rope: hoist_rope, boom_angle: [pedestal.boom_foot, head.origin], end_point: load.origin}}
map: {{boom_angle: {{from: 60, to: 80, step: 5}}, hoist_change: {{from: 0, to: 4, step: 2}}, hoist_length: 54.8342}}
fit: {{type: polynomial, order: [2, 2]}}
trajectory:
  origin: [0, 2.041]
  start: [-25, 0, 0, 0]
  target: [-20, 2, 0, 0]
  state_min: [-50, 0, -1, -1]
  state_max: [-5, 30, 1, 1]
  control_min: [-0.2, -0.2]
  control_max: [0.2, 0.2]
  Q: [100, 100, 100, 100]
  R: [1, 1]
  P_end: [100, 100, 100, 100]
  steps: 300
  sample_time: 0.1
)", scene_path.string());
  const Scene read = readScene(scene_path.string());
  REQUIRE(read.stated_equilibrium);
  const Scene drawn = sceneAtStatedEquilibrium(read, true);
  const auto boomTop = [](const Scene& s) { return member(s, "boom5").end; };
  const double first = read.stated_equilibrium->drawn.angle_deg;
  CHECK((boomTop(drawn) - boomTop(read)).norm() > 0.1);  // the search moves the boom off its first angle
  INFO("first angle " << first << "°");

  const TargetSpec target = readTarget(target_path.string());
  CHECK_FALSE(target.scene.stated_equilibrium);
  CHECK((boomTop(target.scene) - boomTop(drawn)).norm() < 1e-12);
  CHECK((*member(target.scene, "luffing_rope").length)(0.0) == (*member(drawn, "luffing_rope").length)(0.0));

  const Session session(scene_path.string());
  CHECK_FALSE(session.scene().stated_equilibrium);
  CHECK((boomTop(session.scene()) - boomTop(drawn)).norm() < 1e-12);
  std::filesystem::remove_all(dir);
}

namespace {

/// crane_configured.yaml with its luffing rope reeved on `falls` parts between the derrick's top
/// and the ties' end, from a winch on the pedestal at (2, 0, 1); the rope's `length` line is
/// added to the luffing line as `extra` (empty: the tool sizes the rope).
std::string reevedLuffing(int falls, const std::string& extra = "") {
  return fmt::format(R"(
base: crane_configured.yaml
add:
  bodies.pedestal.joints: [{{name: luffing_winch, position: [2, 0, 1]}}]
modify:
  booms.boom.luffing.rope: {{name: luffing_rope, element: reeved, falls: {}, winch: pedestal.luffing_winch,
                            head: {{radius: 0.35}}, hook: {{radius: 0.35}}, section: {{radius: 0.05}},
                            material: {{density: 7800, youngs_modulus: 1.0e11}}, damping: 1.0e-3}}
{})", falls, extra);
}

}  // namespace

TEST_CASE("A luffing rope reeved between the derrick's top and the ties' end", "[scene][boom_assembly][reeving]") {
  // Drawn: the rope runs from its winch to the derrick's top, then 12 falls over the 6.145 m the
  // ties leave of the line: its length the lead line and the falls.
  const ThesisGeometry hand(55.0);
  const Vec3 winch(2.0, 0.0, 1.0);
  const double span = (hand.derrick_top - hand.tie_joint).norm() - 30.0, lead = (hand.derrick_top - winch).norm();
  const Scene reeved = parseScene(reevedLuffing(12), test::configPath("reeved_luffing.yaml"));
  const MemberSpec& rope = member(reeved, "luffing_rope");
  REQUIRE(rope.reeving);
  CHECK((*rope.length)(0.0) == Approx(lead + 12.0 * span).margin(1e-9));
  CHECK((member(reeved, "tie2").end - (hand.tie_joint + 30.0 * (hand.derrick_top - hand.tie_joint).normalized())).norm() < 1e-12);
  CHECK(std::none_of(reeved.constraints.begin(), reeved.constraints.end(),
                     [](const ConstraintSpec& c) { return c.name.rfind("luffing_rope", 0) == 0; }));

  // At rest every fall carries the same tension, and the twelve together hold the boom as the
  // one straight rope of crane_configured.yaml does: its moment about the foot is the same, but
  // for the stiffer line's smaller stretch (the boom stands a little higher).
  const Scene single = test::loadScene("crane_configured.yaml");
  const auto lineTension = [](const Scene& scene) {
    const Model model = compileModel(scene);
    const StaticResult eq = solveEquilibrium(scene, model, 0.0);
    REQUIRE(eq.converged);
    const CraneFigures f = craneFigures(scene, model, eq.q.data(), eq.t);
    return std::pair{tensionOf(f, "luffing_rope").at_start, f.boom->boom_angle_deg};
  };
  const auto [part, reeved_angle] = lineTension(reeved);
  const auto [line, single_angle] = lineTension(single);
  CHECK(12.0 * part == Approx(line).epsilon(0.005));
  CHECK(reeved_angle > single_angle);
  CHECK(reeved_angle - single_angle < 0.2);

  // The boom angle a reeved rope's length gives: the one its falls close the line at, as the
  // single rope of the same span.
  const auto angleOf = [](const Scene& scene) {
    const Model model = compileModel(scene);
    return craneFigures(scene, model, model.q0.data(), 0.0).boom->boom_angle_deg;
  };
  const Scene by_rope = parseScene(reevedLuffing(12, fmt::format("  booms.boom.angle_deg: from_luffing_rope\n"
                                                                 "  booms.boom.luffing.rope_length: {:.17g}\n",
                                                                 lead + 12.0 * 7.0608)),
                                   test::configPath("reeved_by_rope.yaml"));
  const Scene single_by_rope = parseScene(R"(
base: crane_configured.yaml
modify:
  booms.boom.angle_deg: from_luffing_rope
  booms.boom.luffing.rope_length: 7.0608
)", test::configPath("by_rope.yaml"));
  CHECK(angleOf(by_rope) == Approx(angleOf(single_by_rope)).margin(1e-9));
  CHECK(angleOf(by_rope) < 85.0);  // 0.9 m more rope than at 85°: lower
}
