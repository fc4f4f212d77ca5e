// Section forces of beams (output.section_forces; Element::sectionForces): the resultants at the
// two ends of every beam, from the forces its nodes exert on it (its residual M a + F), in its
// co-rotated frame. Checked by statics on configs/jib_fidelities.yaml — a 15 m lattice jib with
// 10 t on an 8 m rope from its tip, at rest:
// - as one equivalent beam, the jib is a free body loaded by its own weight and the rope at its
//   tip: the root carries the whole weight and its moment, the tip the rope's pull, exactly;
// - tube by tube, the tubes cut at the root (chords and the first diagonals) carry the same
//   root moment, M_y = Σ N z + the chords' own M_y, to 1 % (the diagonals' shear and bending
//   left out), and no net force along the jib.

#include <catch2/catch.hpp>

#include <cmath>

#include "cranesim/model/equivalent_beam.hpp"
#include "cranesim/solvers/statics.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kG = 9.81;

struct Equilibrium {
  Model model;
  VecX q;
};

Equilibrium jibAtRest(TrussFidelity fidelity) {
  Scene scene = test::loadScene("jib_fidelities.yaml");
  scene.members.at(0).fidelity = fidelity;
  scene.output.section_forces = {"jib"};
  Equilibrium eq{compileModel(scene), {}};
  const StaticResult st = solveStatics(eq.model, eq.model.q0, 0.0);
  REQUIRE(st.converged);
  eq.q = st.q;
  return eq;
}

/// Section forces of every recorded beam of the jib, 12 per element, at rest.
std::vector<Eigen::Matrix<double, 12, 1>> sectionForces(const Equilibrium& eq) {
  const VecX zero = VecX::Zero(eq.model.nv);
  const ElementInput in{eq.q.data(), zero.data(), zero.data(), 0.0, eq.model.gravity};
  std::vector<Eigen::Matrix<double, 12, 1>> out;
  for (const int e : eq.model.section_force_groups.at(0).elements) {
    Eigen::Matrix<double, 12, 1> f;
    REQUIRE(eq.model.elements[e]->sectionForces(in, f.data()));
    out.push_back(f);
  }
  return out;
}

Vec3 jointAt(const Equilibrium& eq, const std::string& joint) { return eq.model.jointFrame(eq.q.data(), eq.model.findJoint(joint)).r; }

/// Mass of the rope and the load hanging from the jib's tip.
double hangingMass() {
  const Scene scene = test::loadScene("jib_fidelities.yaml");
  const MemberSpec& rope = scene.members.at(1);
  return scene.bodies.at(1).mass + rope.material.density * rope.section.area * 8.0;
}

}  // namespace

TEST_CASE("Section forces: the equivalent-beam jib is a free body in equilibrium", "[section_forces][statics]") {
  const Equilibrium eq = jibAtRest(TrussFidelity::Beam);
  const auto forces = sectionForces(eq);
  REQUIRE(forces.size() == 1);
  const Eigen::Matrix<double, 12, 1>& s = forces[0];
  const Scene scene = test::loadScene("jib_fidelities.yaml");
  const double jib = equivalentBeam(buildTrussGeometry(scene.trusses.at(0))).mass, hanging = hangingMass();
  const Vec3 root = jointAt(eq, "jib.start"), tip = jointAt(eq, "jib.end"), hook = jointAt(eq, "load.hook");
  const double arm = tip.x() - root.x();
  // Section axes: x along the jib, z up (the scene's z_axis). The rope pulls the tip down.
  CHECK(s(8) == Approx(-hanging * kG).epsilon(1e-6));                        // V_z at the tip
  CHECK(std::abs(s(10)) < 1e-6 * hanging * kG * arm);                        // M_y at the tip
  CHECK(s(2) == Approx(-(hanging + jib) * kG).epsilon(1e-6));                // V_z at the root
  CHECK(s(4) == Approx((hanging * arm + jib * arm / 2) * kG).epsilon(1e-4));  // M_y at the root
  CHECK(std::abs(s(0)) < 2e-3 * (hanging + jib) * kG);  // axial: the weight along the root's slope (~1e-3)
  CHECK(std::abs(hook.x() - tip.x()) < 1e-6);
}

TEST_CASE("Section forces: the tubes cut at the root of the full-member jib carry its root moment", "[section_forces][statics]") {
  const Equilibrium eq = jibAtRest(TrussFidelity::Members);
  const auto forces = sectionForces(eq);
  const Model& model = eq.model;
  const std::vector<int>& elements = model.section_force_groups.at(0).elements;
  REQUIRE(elements.size() == 48);  // 4 chords × 6 bays, 4 faces × 6 diagonals
  const Vec3 root = jointAt(eq, "jib.start");
  double moment = 0.0, along = 0.0, largest = 0.0;
  int cut = 0;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const auto& nodes = model.elements[elements[k]]->nodes();
    const Vec3 a = model.nodeFrame(eq.q.data(), nodes[0]).r, b = model.nodeFrame(eq.q.data(), nodes[1]).r;
    largest = std::max(largest, std::abs(forces[k](0)));
    if (std::min(a.x(), b.x()) > root.x() + 1e-3) continue;  // not at the root section
    ++cut;
    const bool root_first = a.x() < b.x();
    const Vec3 axis = (b - a).normalized() * (root_first ? 1.0 : -1.0);  // from the root into the jib
    const double N = forces[k](root_first ? 0 : 6);
    const double z = (root_first ? a : b).z() - root.z();
    along += N * axis.x();
    moment += N * axis.x() * z;
    // A chord's section axes are the jib's (docs/truss.md), so its own bending moment adds.
    if (axis.x() > 0.999) moment += forces[k](4);
  }
  CHECK(cut == 8);
  const Scene scene = test::loadScene("jib_fidelities.yaml");
  const double jib = equivalentBeam(buildTrussGeometry(scene.trusses.at(0))).mass, hanging = hangingMass();
  const double arm = jointAt(eq, "jib.end").x() - root.x();
  const double expected = (hanging * arm + jib * arm / 2) * kG;  // M_y at the root: the top chords in tension
  INFO("root moment of the cut tubes " << moment << " N·m, of the loads " << expected << " N·m");
  CHECK(moment == Approx(expected).epsilon(0.01));
  CHECK(std::abs(along) < 1e-3 * largest);
}
