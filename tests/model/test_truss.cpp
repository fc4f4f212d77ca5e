// Truss description → geometry → full-member model (docs/truss.md): node and member counts of
// the thesis' truss types (Tables D-3, D-6; 7.1), mass, degrees of freedom and constraints of
// the compiled model, and the static deflection of the type 2 cantilever (8.2.1) against an
// equivalent beam.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/truss_geometry.hpp"
#include "cranesim/solvers/statics.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// The thesis' truss types as YAML entries of `trusses:` (Table D-3: types 1–3; Table D-6:
/// types 4–6), radii and material as in configs/truss_type2_cantilever.yaml.
std::string trussType(const std::string& name, double length, int order, const std::string& section1,
                      const std::string& section2, const std::string& main_beams, const std::string& lacing) {
  return "  - name: " + name + "\n    length: " + std::to_string(length) + "\n    order: " + std::to_string(order) +
         "\n    sections:\n      - " + section1 + "\n      - " + section2 + "\n    main_beams: " + main_beams +
         "\n    lacing: " + lacing +
         "\n    tubes:\n      main: {outer_radius: 0.1, inner_radius: 0.08}\n      cross: {outer_radius: 0.1, inner_radius: 0.08}"
         "\n      sub: {outer_radius: 0.05, inner_radius: 0.04}"
         "\n    material: {density: 7800, youngs_modulus: 2.06e11, poisson_ratio: 0.25}\n";
}

const std::string kFour = "{nodes: [[1.5, 1.4], [-1.5, 1.4], [-1.5, -1.4], [1.5, -1.4]], cross_beams: [[1, 2], [2, 3], [3, 4], [4, 1]]}";
const std::string kTwo = "{nodes: [[1.5, 0], [-1.5, 0]], cross_beams: [[1, 2]]}";
const std::string kFourDerrick = "{nodes: [[1.3, 1.1], [-1.3, 1.1], [-1.3, -1.1], [1.3, -1.1]], cross_beams: [[1, 2], [2, 3], [3, 4], [4, 1]]}";
const std::string kTwoDerrick = "{nodes: [[1.3, 0], [-1.3, 0]], cross_beams: [[1, 2]]}";

std::string mainBoomTypes() {
  return trussType("type1", 5, 3, kTwo, kFour, "[[1, 1], [2, 2], [2, 3], [1, 4]]", "tp_type1") +
         trussType("type2", 15, 6, kFour, kFour, "[[1, 1], [2, 2], [3, 3], [4, 4]]", "type1") +
         trussType("type3", 5, 3, kFour, kFour, "[[1, 1], [2, 2], [3, 3], [4, 4]]", "type1");
}

std::string derrickTypes() {
  return trussType("type4", 8, 5, kTwoDerrick, kFourDerrick, "[[1, 1], [2, 2], [2, 3], [1, 4]]", "tp_type1") +
         trussType("type5", 13, 6, kFourDerrick, kFourDerrick, "[[1, 1], [2, 2], [3, 3], [4, 4]]", "type1") +
         trussType("type6", 5, 3, kFourDerrick, kTwoDerrick, "[[1, 1], [2, 2], [3, 2], [4, 1]]", "tp_anti_type1");
}

/// A scene with the given truss types and no members (the types are validated when read).
std::vector<TrussDescription> readTypes(const std::string& types) {
  return parseScene("trusses:\n" + types + "bodies:\n  - {name: b, mass: 1, inertia: [1, 1, 1]}\nsolver: {t_end: 1}\n", "<test>").trusses;
}

struct RoleCounts {
  int main = 0, cross = 0, sub = 0;
};

RoleCounts countRoles(const TrussGeometry& g) {
  RoleCounts c;
  for (const TrussMember& m : g.members) (m.role == TrussMemberRole::Main ? c.main : m.role == TrussMemberRole::Cross ? c.cross : c.sub)++;
  return c;
}

double tubeLength(const TrussGeometry& g, const TrussMember& m) { return (g.nodes[m.node2].position - g.nodes[m.node1].position).norm(); }

double tubeMass(const TrussGeometry& g) {
  double mass = 0.0;
  for (const TrussMember& m : g.members) mass += g.material.density * m.section.area * tubeLength(g, m);
  return mass;
}

/// Every diagonal joins two different chords, lies in its face (z hint ⟂ tube) and spans one bay.
void checkLacing(const TrussGeometry& g, int order) {
  for (const TrussMember& m : g.members) {
    const Vec3 d = g.nodes[m.node2].position - g.nodes[m.node1].position;
    CHECK(std::abs(m.z_axis.dot(d)) < 1e-12 * d.norm());
    CHECK(m.z_axis.norm() == Approx(1.0));
    if (m.role != TrussMemberRole::Sub) continue;
    const TrussNode &a = g.nodes[m.node1], &b = g.nodes[m.node2];
    CHECK(std::abs(std::abs(a.xi - b.xi) * order - 1.0) < 1e-12);
    CHECK(a.chord != b.chord);
  }
}

}  // namespace

TEST_CASE("Truss geometry of the thesis' type 2 section", "[truss]") {
  const TrussGeometry g = buildTrussGeometry(test::loadScene("truss_type2_cantilever.yaml").trusses.at(0));
  CHECK(g.nodes.size() == 8 + 4 * 5);
  CHECK(g.chords.size() == 4);
  const RoleCounts c = countRoles(g);
  CHECK(c.main == 4 * 6);
  CHECK(c.cross == 8);
  CHECK(c.sub == 4 * 6);  // one diagonal per bay and side face
  checkLacing(g, 6);
  // Σ ρ A L by hand: 4 chords of 15 m, per section 2 × 3 m + 2 × 2.8 m cross beams, per side face
  // 6 diagonals over bays of 2.5 m: 12 of √(3² + 2.5²) and 12 of √(2.8² + 2.5²).
  const double A_main = std::numbers::pi * (0.1 * 0.1 - 0.08 * 0.08), A_sub = std::numbers::pi * (0.05 * 0.05 - 0.04 * 0.04);
  const double expected = 7800.0 * (A_main * (60.0 + 2.0 * 11.6) + A_sub * 12.0 * (std::hypot(3.0, 2.5) + std::hypot(2.8, 2.5)));
  CHECK(tubeMass(g) == Approx(expected).epsilon(1e-12));
}

TEST_CASE("Truss geometry of the transition pieces (types 1 and 6)", "[truss]") {
  const auto main_boom = readTypes(mainBoomTypes());
  const TrussGeometry tp = buildTrussGeometry(main_boom.at(0));
  CHECK(tp.nodes.size() == 2 + 4 + 4 * 2);
  RoleCounts c = countRoles(tp);
  CHECK(c.main == 4 * 3);
  CHECK(c.cross == 1 + 4);
  CHECK(c.sub == 4 * 3 - 2);  // the first bay of each triangular side face has no diagonal
  checkLacing(tp, 3);
  const TrussGeometry anti = buildTrussGeometry(readTypes(derrickTypes()).at(2));
  c = countRoles(anti);
  CHECK(anti.nodes.size() == 4 + 2 + 4 * 2);
  CHECK(c.sub == 4 * 3 - 2);
  checkLacing(anti, 3);
  int first_bay = 0, last_bay = 0;  // the triangular faces meet at x = length: no diagonal in their last bay
  for (const TrussMember& m : anti.members) {
    if (m.role != TrussMemberRole::Sub) continue;
    const double x = std::min(anti.nodes[m.node1].xi, anti.nodes[m.node2].xi);
    first_bay += x < 1e-12, last_bay += x > 2.0 / 3.0 - 1e-12;
  }
  CHECK(first_bay == 4);
  CHECK(last_bay == 2);
}

TEST_CASE("Tube counts of the thesis' main and derrick booms (7.1)", "[truss]") {
  // 7.1: the main boom (types 1, 2, 2, 2, 3) has 227 beam elements, the derrick boom (types 4, 5, 6) 126.
  const auto m = readTypes(mainBoomTypes());
  const auto tubes = [](const TrussDescription& d) { return static_cast<int>(buildTrussGeometry(d).members.size()); };
  CHECK(tubes(m[0]) + 3 * tubes(m[1]) + tubes(m[2]) == 227);
  const auto d = readTypes(derrickTypes());
  CHECK(tubes(d[0]) + tubes(d[1]) + tubes(d[2]) == 126);
  // 7.2: 384 DOF = 64 nodes × 6 for the derrick when each section keeps its own end nodes.
  const auto nodes = [](const TrussDescription& t) { return static_cast<int>(buildTrussGeometry(t).nodes.size()); };
  CHECK(nodes(d[0]) + nodes(d[1]) + nodes(d[2]) == 64);
}

TEST_CASE("Full-member model of the type 2 cantilever: mass, coordinates, constraints", "[truss][scenes]") {
  const Scene scene = test::loadScene("truss_type2_cantilever.yaml");
  const Model model = compileModel(scene);
  const double mass = tubeMass(buildTrussGeometry(scene.trusses.at(0)));
  // 28 truss nodes + 2 end plates, each a frame node; 8 end-section nodes fixed to their plate + the clamp.
  CHECK(model.nodes.size() == 30);
  CHECK(model.nv == 6 * 30);
  CHECK(model.m == 6 * 8 + 6);
  CHECK(model.elements.size() == 24 + 24 + 2);  // chord segments, diagonals, two plates
  const Assembler assembler(model);
  VecX v = VecX::Zero(model.nv);
  for (const Node& n : model.nodes) v(n.v) = 1.0;  // uniform translation along x, no rotation
  CHECK(2.0 * assembler.kineticEnergy(0.0, model.q0.data(), v.data()) == Approx(mass).epsilon(1e-12));
  const Eigen::SparseMatrix<double> M = assembler.massMatrix(0.0, model.q0.data());
  for (int axis = 0; axis < 3; ++axis) {
    VecX u = VecX::Zero(model.nv);
    for (const Node& n : model.nodes) u(n.v + axis) = 1.0;
    CHECK(u.dot(M * u) == Approx(mass).epsilon(1e-12));
  }
}

TEST_CASE("Type 2 cantilever: static tip deflection against an equivalent beam", "[truss][scenes][statics]") {
  const Scene scene = test::loadScene("truss_type2_cantilever.yaml");
  const Model model = compileModel(scene);
  const StaticResult eq = solveStatics(model, model.q0, 0.0);
  REQUIRE(eq.converged);
  const Frame tip = model.jointFrame(eq.q.data(), model.findJoint("boom.end"));
  const double deflection = -tip.r.z();

  // Equivalent beam: chords at z = ±1.4 (parallel axes) plus their own I; weight of chords and
  // lacing spread along the span, the cross-section beams of section 2 a tip load.
  const TrussGeometry g = buildTrussGeometry(scene.trusses.at(0));
  const double E = 2.06e11, L = 15.0, gravity = 9.81;
  double EI = 0.0, spread = 0.0, tip_mass = 0.0;
  for (const TrussMember& m : g.members) {
    const double mm = g.material.density * m.section.area * tubeLength(g, m);
    if (m.role == TrussMemberRole::Cross) tip_mass += g.nodes[m.node1].end_section == 1 ? mm : 0.0;
    else spread += mm;
  }
  const Section& tube = g.members.front().section;  // the members start with the main beams
  for (const auto& chord : g.chords) {
    const double z = g.nodes[chord[0]].position.z();
    EI += E * (tube.area * z * z + tube.Iy);
  }
  const double q = spread * gravity / L, P = tip_mass * gravity;
  const double bending = q * std::pow(L, 4) / (8.0 * EI) + P * std::pow(L, 3) / (3.0 * EI);
  // Lacing shear stiffness of the two side faces (height h = 2.8 m, bays a = 2.5 m, one diagonal
  // of length d per bay): S = 2 E A_d a h² / d³.
  const double a = 2.5, h = 2.8, d = std::hypot(a, h), A_d = std::numbers::pi * (0.05 * 0.05 - 0.04 * 0.04);
  const double S = 2.0 * E * A_d * a * h * h / std::pow(d, 3);
  const double shear = q * L * L / (2.0 * S) + P * L / S;
  INFO("tip deflection " << deflection << " m; equivalent beam: bending " << bending << " m, + lacing shear " << bending + shear
                         << " m; ratios " << deflection / bending << ", " << deflection / (bending + shear));
  CHECK(deflection > bending);
  CHECK(deflection < 2.0 * bending);
  CHECK(deflection == Approx(bending + shear).epsilon(0.05));

  // The same truss placed along y: the tubes' section frames turn differently against their
  // nodes (rotated_ends.hpp), the deflection must not change.
  Scene turned = scene;
  turned.members[0].end = Vec3(0.0, 15.0, 0.0);
  turned.ground_joints[0].rotation = axisAngle(Vec3::UnitZ(), std::numbers::pi / 2.0);  // the clamp turns along
  const Model turned_model = compileModel(turned);
  const StaticResult turned_eq = solveStatics(turned_model, turned_model.q0, 0.0);
  REQUIRE(turned_eq.converged);
  const Frame turned_tip = turned_model.jointFrame(turned_eq.q.data(), turned_model.findJoint("boom.end"));
  CHECK(-turned_tip.r.z() == Approx(deflection).epsilon(1e-8));
}

TEST_CASE("DOF bookkeeping of the thesis' main boom as full-member model (7.1)", "[truss][scenes]") {
  std::string yaml = "gravity: [0, 0, -9.81]\nground: {joints: [{name: foot}]}\ntrusses:\n" + mainBoomTypes() + "members:\n";
  const char* types[] = {"type1", "type2", "type2", "type2", "type3"};
  const double stations[] = {0.0, 5.0, 20.0, 35.0, 50.0, 55.0};
  for (int i = 0; i < 5; ++i)
    yaml += "  - {name: b" + std::to_string(i + 1) + ", type: truss, truss: " + types[i] + ", start: [" + std::to_string(stations[i]) +
            ", 0, 0], end: [" + std::to_string(stations[i + 1]) + ", 0, 0], fidelity: members}\n";
  yaml += "constraints:\n  - {name: foot, type: fixed, joints: [ground.foot, b1.start]}\n";
  for (int i = 1; i < 5; ++i)
    yaml += "  - {name: j" + std::to_string(i) + ", type: fixed, joints: [b" + std::to_string(i) + ".end, b" + std::to_string(i + 1) + ".start]}\n";
  yaml += "solver: {t_end: 1}\n";
  const Model model = test::loadYaml(yaml);
  // 114 truss nodes (each section keeps its own end nodes) + 10 plates; inside the trusses
  // 38 end-section nodes fixed to plates, 4 joints between sections, the foot.
  CHECK(model.nodes.size() == 114 + 10);
  CHECK(model.nv == 6 * 124);
  CHECK(model.m == 6 * (38 + 4 + 1));
  // Free boom (without the foot): 76 internal nodes + 6 independent end sections.
  CHECK(model.nv - (model.m - 6) == 6 * (76 + 6));
  CHECK(model.elements.size() == 227 - 37 + 10);  // tubes without the 37 cross-section beams, plates
}

TEST_CASE("The same truss as one super truss element: 12 coordinates, the same mass", "[truss][scenes]") {
  Scene scene = test::loadScene("truss_type2_cantilever.yaml");
  scene.members[0].fidelity = TrussFidelity::SuperTruss;
  const Model model = compileModel(scene);
  CHECK(model.nodes.size() == 2);
  CHECK(model.elements.size() == 1);
  CHECK(model.nv == 12);
  CHECK(model.m == 6);  // the clamp only
  const Assembler assembler(model);
  VecX v = VecX::Zero(model.nv);
  for (const Node& n : model.nodes) v(n.v) = 1.0;
  CHECK(2.0 * assembler.kineticEnergy(0.0, model.q0.data(), v.data()) ==
        Approx(tubeMass(buildTrussGeometry(scene.trusses.at(0)))).epsilon(1e-12));
}
