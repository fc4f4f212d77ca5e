// Sections given by their properties (EA, GA_y, GA_z, EI_y, EI_z, GJ, ρA, ρI_y, ρI_z, ρI_p)
// instead of a shape and a material: equal to the shape section where both describe the same
// beam (statics and modes, Timoshenko and spline beams); the two shear stiffnesses in their own
// bending planes (a short cantilever's tip deflection PL³/3EI + PL/κGA in y and in z); and a
// rotary inertia independent of the bending stiffness in the Timoshenko frequency equation.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "cantilever_theory.hpp"
#include "cranesim/elements/section.hpp"
#include "cranesim/solvers/modes.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kLength = 5.0;

/// A cantilever along x clamped at the origin, with SECTION (and MATERIAL) as given, no gravity,
/// a tip force `force`.
std::string cantilever(const std::string& type, double length, int segments, const std::string& section,
                       const Vec3& force) {
  return fmt::format(R"(name: cantilever
gravity: [0, 0, 0]
ground:
  joints: [{{name: wall}}]
members:
  - {{name: beam, type: {}, start: [0, 0, 0], end: [{:.17g}, 0, 0], segments: {}, {}}}
constraints:
  - {{name: clamp, type: fixed, joints: [ground.wall, beam.start]}}
loads:
  - {{name: tip, joint: beam.end, force: [{:.17g}, {:.17g}, {:.17g}]}}
solver: {{t_end: 1}}
)",
                     type, length, segments, section, force.x(), force.y(), force.z());
}

std::string propertiesSection(const SectionProperties& p, bool shear = true) {
  std::string s = fmt::format("section: {{EA: {:.17g}, EI_y: {:.17g}, EI_z: {:.17g}, GJ: {:.17g}, rhoA: {:.17g}, "
                              "rhoI_y: {:.17g}, rhoI_z: {:.17g}, rhoI_p: {:.17g}",
                              p.EA, p.EIy, p.EIz, p.GJ, p.rhoA, p.rhoIy, p.rhoIz, p.rhoIp);
  if (shear) s += fmt::format(", GA_y: {:.17g}, GA_z: {:.17g}", p.GAy, p.GAz);
  return s + "}";
}


VecX frequencies(const std::string& yaml, int count) {
  const Model model = test::loadYaml(yaml);
  return computeModes(model, model.q0, 0.0, count).frequencies;
}

}  // namespace

TEST_CASE("A section given by its properties equals the shape section it describes", "[section][statics][modes]") {
  Material steel;
  steel.density = 7850.0;
  steel.youngs_modulus = 2.1e11;
  steel.shear_modulus = 2.1e11 / 2.6;
  const Section tube = Section::circular(0.1, 0.08, 0.3);
  const SectionProperties p = tube.properties(steel);
  const std::string shape = "section: {outer_radius: 0.1, inner_radius: 0.08}, material: {density: 7850, youngs_modulus: 2.1e11, poisson_ratio: 0.3}";
  const Vec3 load(3e4, 2e4, -5e4);  // bends the 5 m tube by ~0.2 m: geometrically nonlinear
  for (const char* type : {"timoshenko", "spline_beam"}) {
    // The spline beam has no shear deformation: its properties section leaves GA out.
    const bool shear = std::string(type) == "timoshenko";
    const std::string given = propertiesSection(p, shear);
    INFO(type);
    const Vec3 by_shape = test::equilibriumJointPosition(cantilever(type, kLength, 8, shape, load), "beam.end");
    const Vec3 by_properties = test::equilibriumJointPosition(cantilever(type, kLength, 8, given, load), "beam.end");
    CHECK((by_shape - Vec3(kLength, 0, 0)).norm() > 0.05);
    CHECK((by_shape - by_properties).norm() < 1e-12 * kLength);
    const VecX f_shape = frequencies(cantilever(type, kLength, 8, shape, Vec3::Zero()), 8);
    const VecX f_properties = frequencies(cantilever(type, kLength, 8, given, Vec3::Zero()), 8);
    CHECK((f_shape - f_properties).cwiseAbs().maxCoeff() < 1e-9 * f_shape.maxCoeff());
  }
}

TEST_CASE("GA_y and GA_z act in their own bending planes", "[section][statics]") {
  // A short, shear-soft cantilever (L = 1 m) with different stiffnesses in the two planes. A small
  // tip force keeps it linear: δ_y = PL³/3EI_z + PL/GA_y, δ_z = PL³/3EI_y + PL/GA_z, exact for
  // Timoshenko elements with consistent shape functions.
  SectionProperties p;
  p.EA = 1e9, p.GJ = 1e6, p.EIy = 2e6, p.EIz = 5e6, p.GAy = 3e6, p.GAz = 8e6;
  p.rhoA = 50.0, p.rhoIy = 0.1, p.rhoIz = 0.2, p.rhoIp = 0.3;
  const double L = 1.0, P = 1.0;
  const std::string section = propertiesSection(p);
  const double along_y = test::equilibriumJointPosition(cantilever("timoshenko", L, 4, section, Vec3(0, P, 0)), "beam.end").y();
  const double along_z = test::equilibriumJointPosition(cantilever("timoshenko", L, 4, section, Vec3(0, 0, P)), "beam.end").z();
  const double bending_y = P * L * L * L / (3.0 * p.EIz), bending_z = P * L * L * L / (3.0 * p.EIy);
  CHECK(along_y == Approx(bending_y + P * L / p.GAy).epsilon(1e-6));
  CHECK(along_z == Approx(bending_z + P * L / p.GAz).epsilon(1e-6));
  // The shear parts are a third and a fifth of the deflections: swapping GA_y and GA_z would
  // miss by 10 % and 20 %.
  CHECK(P * L / p.GAy > 0.3 * along_y);
}

TEST_CASE("A rotary inertia of its own: the Timoshenko frequency equation", "[section][modes]") {
  // A steel tube's stiffness with five times its rotary inertia (heavy attachments off the axis):
  // the lowest bending frequency against the Timoshenko beam's frequency equation.
  Material steel;
  steel.density = 7850.0;
  steel.youngs_modulus = 2.1e11;
  steel.shear_modulus = 2.1e11 / 2.6;
  SectionProperties p = Section::circular(0.1, 0.08, 0.3).properties(steel);
  p.rhoIy *= 5.0, p.rhoIz *= 5.0, p.rhoIp *= 5.0;
  const double L = 2.0;  // short: rotary inertia and shear matter
  const VecX f = frequencies(cantilever("timoshenko", L, 24, propertiesSection(p), Vec3::Zero()), 2);
  const double exact = test::timoshenkoCantileverFrequencies(L, p.EIz, p.GAy, p.rhoA, p.rhoIz, 1).at(0);
  const double without_rotary = test::timoshenkoCantileverFrequencies(L, p.EIz, p.GAy, p.rhoA, p.rhoIz / 5.0, 1).at(0);
  INFO("f = " << f(0) << " Hz, Timoshenko " << exact << " Hz, with the tube's own rotary inertia " << without_rotary);
  CHECK(f(0) == Approx(exact).epsilon(1e-4));                      // 24 elements: 1.1e-5 measured
  CHECK(std::abs(exact - without_rotary) > 50.0 * 1e-4 * exact);  // the extra rotary inertia: −0.9 %
}
