// The equivalent Timoshenko beam of a lattice section (model/equivalent_beam.hpp): the beam
// element built with the fitted section must carry the loadings the fit is made from exactly as
// the condensed full-member stiffness does (the Timoshenko element's own clamped flexibility,
// not the fit's formulas), its mass must be the tubes', and its stiffnesses must agree with the
// closed-form estimate of a four-chord box (chords by the parallel-axis theorem).

#include <catch2/catch.hpp>

#include <cstdio>

#include "cranesim/elements/condensed_truss.hpp"
#include "cranesim/elements/timoshenko_beam.hpp"
#include "cranesim/model/equivalent_beam.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;

/// Flexibility of end section `end` with the other one clamped, from a 12 × 12 stiffness on
/// [u¹, θ¹, u², θ²].
Mat6 flexibility(const Eigen::Matrix<double, 12, 12>& K, int end) { return Mat6(K.block<6, 6>(6 * end, 6 * end)).inverse(); }

/// Clamped–guided flexibility: deflection w with the end rotation θ held.
double guided(const Mat6& C, int w, int theta) { return C(w, w) - C(w, theta) * C(w, theta) / C(theta, theta); }

TrussGeometry trussOf(const char* scene_file, const char* truss) {
  const Scene scene = test::loadScene(scene_file);
  for (const TrussDescription& d : scene.trusses)
    if (d.name == truss) return buildTrussGeometry(d);
  FAIL("no truss " << truss);
  return {};
}

}  // namespace

TEST_CASE("Equivalent beam: the Timoshenko element reproduces the lattice section's stiffness", "[equivalent_beam]") {
  for (const char* type : {"type2", "type3", "type5", "type1", "type4", "type6"}) {
    const TrussGeometry g = trussOf("crane.yaml", type);
    const EquivalentBeam eq = equivalentBeam(g);
    TimoshenkoBeamKernel beam;
    beam.length = g.length;
    beam.section = eq.section;
    beam.material = eq.material;
    std::printf("%s: EA %.4e N, GJ %.4e N·m², EI_y %.4e, EI_z %.4e N·m², κ %.4f, guided mismatch %.3f, shear planes ±%.3f\n", type,
                eq.material.youngs_modulus * eq.section.area, eq.material.shear_modulus * eq.section.J,
                eq.material.youngs_modulus * eq.section.Iy, eq.material.youngs_modulus * eq.section.Iz, eq.section.shear_factor,
                eq.guided_mismatch, eq.shear_plane_mismatch);
    INFO(type);
    // Both ends: the fitted loadings are the same seen from either end.
    for (int end = 0; end < 2; ++end) {
      const Mat6 truss = flexibility(CondensedTrussKernel(g).stiffness, end), fitted = flexibility(beam.localStiffness(), end);
      CHECK(fitted(0, 0) == Approx(truss(0, 0)).epsilon(1e-9));  // axial
      CHECK(fitted(3, 3) == Approx(truss(3, 3)).epsilon(1e-9));  // torsion
      CHECK(fitted(4, 4) == Approx(truss(4, 4)).epsilon(1e-9));  // constant moment about y
      CHECK(fitted(5, 5) == Approx(truss(5, 5)).epsilon(1e-9));  // constant moment about z
      // Clamped–guided: one κGA for both planes, so their sum is met (where the taper allows).
      const double shear_truss = guided(truss, 2, 4) + guided(truss, 1, 5), shear_beam = guided(fitted, 2, 4) + guided(fitted, 1, 5);
      if (eq.guided_mismatch <= 0.0) {
        CHECK(shear_beam == Approx(shear_truss).epsilon(1e-9));
        CHECK(eq.shear_plane_mismatch < 0.05);
      } else {
        CHECK(shear_beam > shear_truss);
        CHECK(eq.shear_plane_mismatch == 0.0);
        // The plane without taper (bending about z: the chords keep their y at both ends) keeps its
        // guided deflection: it alone sets κGA.
        CHECK(guided(fitted, 1, 5) == Approx(guided(truss, 1, 5)).epsilon(1e-9));
      }
    }
  }
}

TEST_CASE("Equivalent beam: mass and the closed-form stiffness of the type 2 box", "[equivalent_beam]") {
  const TrussGeometry g = trussOf("crane.yaml", "type2");
  const EquivalentBeam eq = equivalentBeam(g);
  double mass = 0.0;
  for (const TrussMember& t : g.members)
    mass += g.material.density * t.section.area * (g.nodes[t.node2].position - g.nodes[t.node1].position).norm();
  CHECK(eq.mass == Approx(mass).epsilon(1e-12));
  CHECK(eq.material.density * eq.section.area * g.length == Approx(mass).epsilon(1e-12));
  // Four chords at (±1.5, ±1.4): A = 4 A_c, I_y = 4 A_c 1.4² + 4 I_c, I_z = 4 A_c 1.5² + 4 I_c.
  // The lacing adds a little axial and bending stiffness; the box prismatic, so no taper.
  const Section chord = g.members.front().section;
  CHECK(eq.section.area == Approx(4.0 * chord.area).epsilon(0.03));
  CHECK(eq.section.Iy == Approx(4.0 * (chord.area * 1.4 * 1.4 + chord.Iy)).epsilon(0.03));
  CHECK(eq.section.Iz == Approx(4.0 * (chord.area * 1.5 * 1.5 + chord.Iz)).epsilon(0.03));
  CHECK(eq.guided_mismatch <= 0.0);
}
