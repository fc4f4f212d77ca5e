// Members drawn along an arc (model/arc.hpp): the undeformed node frames follow the arc's
// tangent, and a quarter-circle cantilever of straight Timoshenko elements converges to the
// curved beam's closed-form flexibility (Castigliano with bending, torsion, axial and shear
// energy) as the segments shrink, in its plane and out of it.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

#include "cranesim/math/rotation.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadius = 2.0, kE = 2.1e11, kNu = 0.3, kOuter = 0.06, kInner = 0.05;

/// A quarter circle of radius 2 m in the x-y plane about the origin, from (2, 0, 0) clamped to
/// (0, 2, 0) free, a steel tube, loaded at its tip without gravity.
std::string quarterArc(int segments, const Vec3& force) {
  return fmt::format(R"(
name: quarter-circle cantilever
gravity: [0, 0, 0]
ground:
  joints: [{{name: wall, position: [2, 0, 0], rotation: {{axis: [0, 0, 1], angle_deg: 90}}}}]
members:
  - {{name: arc, type: timoshenko, start: [2, 0, 0], end: [0, 2, 0], arc: {{centre: [0, 0, 0]}}, segments: {},
     section: {{outer_radius: {}, inner_radius: {}}}, material: {{density: 7850, youngs_modulus: {}, poisson_ratio: {}}}}}
constraints:
  - {{name: clamp, type: fixed, joints: [ground.wall, arc.start]}}
loads:
  - {{name: tip, joint: arc.end, force: [{}, {}, {}]}}
solver: {{t_end: 1}}
)",
                     segments, kOuter, kInner, kE, kNu, force.x(), force.y(), force.z());
}

/// The curved beam's tip displacement under a tip force (x, y in the plane, z across it), by
/// Castigliano over θ ∈ [0, π/2] with ds = R dθ (the clamp at θ = 0): in the plane the moment
/// about z, the normal and the shear force; across it the bending moment, the torque and the
/// shear, with Cowper's shear factor of the tube (section.hpp).
Vec3 closedForm(const Vec3& F) {
  const double A = kPi * (kOuter * kOuter - kInner * kInner), I = kPi / 4 * (std::pow(kOuter, 4) - std::pow(kInner, 4));
  const double G = kE / (2 * (1 + kNu)), EI = kE * I, GJ = G * 2 * I, EA = kE * A;
  const double ratio = kInner / kOuter, m = ratio * ratio;  // κ of a hollow circle (Cowper), as section.hpp
  const double kappa = 6 * (1 + kNu) * (1 + m) * (1 + m) / ((7 + 6 * kNu) * (1 + m) * (1 + m) + (20 + 12 * kNu) * m);
  const double kGA = kappa * G * A, R = kRadius;
  // ∫ over the quarter: ∫(1 − sin)² = 3π/4 − 2, ∫cos² = ∫sin² = π/4, ∫cos (1 − sin) = 1/2.
  const double i11 = 3 * kPi / 4 - 2, i22 = kPi / 4, i12 = 0.5;
  // In the plane, with M = −R((1 − sin θ) Fx + cos θ Fy), N and V from the force's components
  // along the tangent (−sin θ, cos θ) and the inward normal (−cos θ, −sin θ).
  const double xx = R * R * R / EI * i11 + R / EA * kPi / 4 + R / kGA * kPi / 4;
  const double yy = R * R * R / EI * i22 + R / EA * kPi / 4 + R / kGA * kPi / 4;
  const double xy = R * R * R / EI * i12 + R / EA * (-0.5) + R / kGA * 0.5;
  // Across it: bending −R cos θ Fz, torque R (1 − sin θ) Fz, shear Fz.
  const double zz = R * R * R / EI * i22 + R * R * R / GJ * i11 + R / kGA * kPi / 2;
  return {xx * F.x() + xy * F.y(), xy * F.x() + yy * F.y(), zz * F.z()};
}

}  // namespace

TEST_CASE("An arc member's nodes lie on the arc with their x axes along its tangent", "[arc][scene]") {
  const Model model = test::loadYaml(quarterArc(6, Vec3::Zero()));
  for (int i = 0; i <= 6; ++i) {
    const Frame f = model.jointFrame(model.q0.data(), model.findJoint(fmt::format("arc.n{}", i)));
    const double theta = kPi / 2 * i / 6;
    CHECK((f.r - kRadius * Vec3(std::cos(theta), std::sin(theta), 0)).norm() < 1e-14);
    CHECK((f.R.col(0) - Vec3(-std::sin(theta), std::cos(theta), 0)).norm() < 1e-14);  // tangent
    CHECK((f.R.col(2) - Vec3::UnitZ()).norm() < 1e-14);                               // the arc's axis
    CHECK((f.R.col(1) + f.r / kRadius).norm() < 1e-14);                               // towards the centre
  }
}

TEST_CASE("A quarter-circle cantilever converges to the curved beam's closed form", "[arc][statics]") {
  // Small loads (tip displacements ~2e-5 R): the geometrically nonlinear statics is linear here to ~1e-5.
  for (const Vec3& force : {Vec3(10, 0, 0), Vec3(0, 10, 0), Vec3(0, 0, 10)}) {
    const Vec3 exact = closedForm(force);
    double previous = 0.0;
    for (int segments : {8, 16, 32}) {
      const Vec3 tip = test::equilibriumJointPosition(quarterArc(segments, force), "arc.end") - Vec3(0, kRadius, 0);
      const double error = (tip - exact).norm() / exact.norm();
      INFO("force " << force.transpose() << ", " << segments << " segments: tip " << tip.transpose() << " against "
                    << exact.transpose() << ", relative error " << error);
      CHECK(error < 8e-3 * 64.0 / (segments * segments));  // second order; measured 1.9e-3…6.8e-3 at 8, 1.2e-4…4.4e-4 at 32
      if (previous > 0.0) CHECK(previous / error > 3.5);  // measured 3.8…4.0
      previous = error;
    }
  }
}

TEST_CASE("Arcs the long way round, and drawings that are no arc", "[arc][scene]") {
  // 270° about −z from (2, 0, 0): through (0, −2, 0) and (−2, 0, 0) to (0, 2, 0).
  std::string yaml = quarterArc(12, Vec3::Zero());
  yaml.replace(yaml.find("arc: {centre: [0, 0, 0]}"), 24, "arc: {centre: [0, 0, 0], axis: [0, 0, -1]}");
  const Model model = test::loadYaml(yaml);
  const Frame third = model.jointFrame(model.q0.data(), model.findJoint("arc.n4"));  // 90° along
  CHECK((third.r - Vec3(0, -kRadius, 0)).norm() < 1e-14);
  CHECK((third.R.col(0) - Vec3(-1, 0, 0)).norm() < 1e-14);

  const auto rejects = [](std::string scene, const std::string& from, const std::string& to, const std::string& why) {
    scene.replace(scene.find(from), from.size(), to);
    try {
      test::loadYaml(scene);
      FAIL("accepted: " << to);
    } catch (const SceneError& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(why) != std::string::npos);
    }
  };
  const std::string base = quarterArc(4, Vec3::Zero());
  rejects(base, "end: [0, 2, 0]", "end: [0, 2.1, 0]", "an arc keeps one radius");
  rejects(base, "end: [0, 2, 0]", "end: [-2, 0, 0]", "lie in one line");
  rejects(base, "arc: {centre: [0, 0, 0]}", "arc: {centre: [0, 0, 0], axis: [1, 0, 1]}", "in the plane through its centre");
  // An arc in a tilted plane: its axis from the drawing.
  std::string tilted = base;
  tilted.replace(tilted.find("end: [0, 2, 0]"), 14, "end: [0, 1.4142135623730951, 1.4142135623730951]");
  const Model t = test::loadYaml(tilted);
  const Frame tip = t.jointFrame(t.q0.data(), t.findJoint("arc.end"));
  CHECK((tip.R.col(2) - Vec3(0, -1, 1).normalized()).norm() < 1e-14);
}
