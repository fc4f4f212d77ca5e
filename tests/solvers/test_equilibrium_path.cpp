// Statics for every control and load (solvers/equilibrium_path.hpp, solvers/drive_posing.hpp):
// the thesis crane solved from its drawn geometry with one set of solver settings over its
// working range, checked against crane-opt's static map (whose points are reached by
// continuation along the boom angle from the scene's own equilibrium); the slewing drive at any
// angle; loads from 10 t to 500 t, each equilibrium stable; relaxation reaching the same
// equilibrium from the drawing; a drive in a closed loop, which
// cannot be posed rigidly, moved along the path; the revolute drive's equation with one root
// per turn; a hook load too light for the derrick's sub-cable, which the statics name.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "cranesim/crane/crane_figures.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/planning/static_map.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "cranesim/solvers/modes.hpp"
#include "cranesim/solvers/relaxation.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kThesisLuffing = 7.0608, kThesisHoist = 53.9937, kLoadMass = 390000.6, kGravity = 9.8;
const CraneControls kCrane{"luffing_rope", "hoist_rope", "pedestal.boom_foot", "head.origin", "load.origin"};

struct CraneCase {
  double luffing = kThesisLuffing, hoist = kThesisHoist, slewing_deg = 0.0, load_mass = kLoadMass;
};

Scene craneScene(const std::string& config, const CraneCase& c) {
  Scene scene = withControls(test::loadScene(config), kCrane, Profile(ConstantProfile{c.luffing}),
                             Profile(ConstantProfile{c.hoist}));
  for (ConstraintSpec& k : scene.constraints)
    if (k.name == "slewing") k.drive = Profile(ConstantProfile{c.slewing_deg * kDegree});
  for (RigidBodySpec& b : scene.bodies)
    if (b.name == "load") b.mass = c.load_mass;
  return scene;
}

struct CraneEquilibrium {
  StaticResult result;
  Vec3 load = Vec3::Zero();
  Vec3 hook_force = Vec3::Zero();
};

CraneEquilibrium solveCrane(const std::string& config, const CraneCase& c) {
  const Scene scene = craneScene(config, c);
  const Model model = compileModel(scene);
  CraneEquilibrium out{solveEquilibrium(scene, model, 0.0)};
  INFO("luffing " << c.luffing << " m, hoist " << c.hoist << " m, slewing " << c.slewing_deg << "°, load "
                  << c.load_mass << " kg: " << out.result.message);
  REQUIRE(out.result.converged);
  out.load = model.jointFrame(out.result.q.data(), model.findJoint("load.origin")).r;
  for (const Constraint& k : model.constraints)
    if (k.name == "hook") out.hook_force = out.result.lambda.segment<3>(k.row);
  return out;
}

/// Every point of a coarse map (boom angles 45…85°, hoist rope 56…30 m) solved from the drawing
/// under the map's controls: the same end point.
void checkAgainstMap(const std::string& config, const std::vector<double>& angles, const std::vector<double>& changes) {
  StaticMapSpec spec;
  spec.boom_angles_deg = angles;
  spec.hoist_changes = changes;
  spec.hoist_length = kThesisHoist;
  const StaticMap map = computeStaticMap(craneScene(config, {}), kCrane, spec);
  for (const std::string& failure : map.failures) UNSCOPED_INFO(failure);
  REQUIRE(map.failures.empty());
  int iterations = 0, worst = 0;
  for (int i = 0; i < map.rows(); ++i)
    for (int j = 0; j < map.columns(); ++j) {
      const CraneCase c{map.luffing_length(i, j), map.hoist_rope_length(i, j), 0.0, kLoadMass};
      const CraneEquilibrium eq = solveCrane(config, c);
      INFO("boom angle " << angles[i] << "°, hoist change " << changes[j] << " m");
      CHECK((eq.load - Vec3(map.end_x(i, j), map.end_y(i, j), map.end_z(i, j))).norm() < 1e-3);
      CHECK(-eq.hook_force.z() == Approx(kLoadMass * kGravity).epsilon(1e-9));
      iterations += eq.result.iterations;
      worst = std::max(worst, eq.result.iterations);
    }
  WARN(config << ": " << map.rows() * map.columns() << " equilibria, Newton iterations mean "
              << double(iterations) / (map.rows() * map.columns()) << ", max " << worst);
}

/// The slewing drive at any angle turns the whole crane: at the thesis' controls, and with the
/// boom luffed far out (the path turns it by ~0.5 rad).
void checkSlewing(const std::string& config) {
  for (double luffing : {kThesisLuffing, 16.0}) {
    const CraneEquilibrium unturned = solveCrane(config, {luffing, kThesisHoist, 0.0, kLoadMass});
    for (double angle : {10.0, 45.0, 90.0, 180.0, -135.0}) {
      const CraneEquilibrium turned = solveCrane(config, {luffing, kThesisHoist, angle, kLoadMass});
      INFO(config << ": luffing rope " << luffing << " m, slewing " << angle << "°");
      // The slewing ring turns about the vertical through the origin, parallel to gravity: the
      // turned equilibrium is the unturned one turned.
      CHECK((turned.load - axisAngle(Vec3::UnitZ(), angle * kDegree) * unturned.load).norm() < 1e-6);
      // The predictor turns rotations about their body axes, so the path does not depend on
      // how far the crane is slewed (with summed rotation vectors the condensed crane's 16 m
      // case took 16 iterations at 180° and 18–20 at the other angles).
      CHECK(turned.result.iterations == unturned.result.iterations);
    }
  }
}

/// Loads from 10 t to 500 t at the thesis' controls, each equilibrium stable.
void checkLoads(const std::string& config) {
  for (double mass : {10e3, 100e3, 500e3}) {
    const CraneEquilibrium eq = solveCrane(config, {kThesisLuffing, kThesisHoist, 0.0, mass});
    INFO(config << ": load " << mass << " kg");
    CHECK(-eq.hook_force.z() == Approx(mass * kGravity).epsilon(1e-9));
    const Model model = compileModel(craneScene(config, {kThesisLuffing, kThesisHoist, 0.0, mass}));
    const ModalResult modes = computeModes(model, eq.result.q, 0.0, 3);
    CHECK(modes.omega_squared.minCoeff() > -modes.zero_threshold);
  }
}

}  // namespace

TEST_CASE("Equilibrium path: the condensed crane over its working range, against the static map", "[statics][crane]") {
  checkAgainstMap("crane_condensed.yaml", {45, 55, 65, 75, 85}, {-2, 11, 24});
}

TEST_CASE("Equilibrium path: the super truss crane over its working range, against the static map", "[statics][crane]") {
  checkAgainstMap("crane.yaml", {47, 60, 72, 84}, {-2, 11, 24});
}

TEST_CASE("Equilibrium path: the slewing drive turns the whole crane", "[statics][crane]") {
  checkSlewing("crane_condensed.yaml");
  checkSlewing("crane.yaml");
}

TEST_CASE("Equilibrium path: loads from 10 t to 500 t, each equilibrium stable", "[statics][crane]") {
  checkLoads("crane_condensed.yaml");
  checkLoads("crane.yaml");
}

TEST_CASE("Relaxation, the independent second method: the condensed crane reeled from its drawing to far controls",
          "[statics][relaxation][crane]") {
  // Luffing rope 12 m (drawn 6.145 m: the boom turns from 84° to ~60°), hoist rope 40 m (drawn
  // 54.8 m). Released at those lengths the ropes would start 6 m slack and 37 % stretched.
  const CraneCase far{12.0, 40.0};
  const Scene scene = craneScene("crane_condensed.yaml", far);
  RelaxationOptions options;
  options.damping = scene.solver.relaxation_damping;
  const RelaxationResult relaxed = relaxToEquilibrium(scene, options);
  INFO(relaxed.equilibrium.message);
  REQUIRE(relaxed.equilibrium.converged);
  CHECK(relaxed.equilibrium.iterations <= 3);  // the relaxed state is close: Newton only polishes
  const Model model = compileModel(scene);
  const Vec3 load = model.jointFrame(relaxed.equilibrium.q.data(), model.findJoint("load.origin")).r;
  const CraneEquilibrium path = solveCrane("crane_condensed.yaml", far);
  CHECK((load - path.load).norm() < 1e-6);
}

TEST_CASE("Equilibrium path: a hook too light for the derrick's sub-cable, named as the cause", "[statics][crane]") {
  // With the boom steep (luffing rope 6 m) the derrick leans back on its sub-cable only while the
  // luffing rope's pull outweighs its own weight's moment, which the hook load sets. The moment
  // balance is linear in the hook load on this nearly fixed geometry: the sub-cable's tension at
  // its anchor falls linearly with the load, through 0 between 2 t and 3 t. Below that the rope
  // hangs slack from the derrick, and at 1 t nothing holds the derrick back: no equilibrium
  // exists, and the statics say which rope went slack rather than only that Newton stalled.
  const auto anchorTension = [](double load) {
    const Scene scene = craneScene("crane_condensed.yaml", {6.0, kThesisHoist, 0.0, load});
    const Model model = compileModel(scene);
    const StaticResult eq = solveEquilibrium(scene, model, 0.0);
    INFO(load << " kg: " << eq.message);
    REQUIRE(eq.converged);
    for (const RopeTension& r : craneFigures(scene, model, eq.q.data(), 0.0).ropes)
      if (r.rope == "sub_cable") return r.at_start;
    FAIL("no sub_cable");
    return 0.0;
  };
  const double t3 = anchorTension(3000.0), t4 = anchorTension(4000.0), t5 = anchorTension(5000.0);
  CAPTURE(t3, t4, t5);
  CHECK(t4 == Approx(0.5 * (t3 + t5)).epsilon(0.01));
  const double slack_below = 3000.0 - t3 * 2000.0 / (t5 - t3);
  CAPTURE(slack_below);
  CHECK(slack_below > 2000.0);
  CHECK(slack_below < 3000.0);

  const Scene scene = craneScene("crane_condensed.yaml", {6.0, kThesisHoist, 0.0, 1000.0});
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  CAPTURE(eq.message);
  CHECK_FALSE(eq.converged);
  CHECK(eq.message.find("'sub_cable' at its start") != std::string::npos);
}

TEST_CASE("Equilibrium path: a drive in a closed loop moves along the path", "[statics][drives]") {
  // The slider-crank's crank cannot be turned rigidly (its rod holds the slider on the rail):
  // the drive's value moves from the drawn 0° to θ, and the slider follows the closed form.
  Scene scene = test::loadScene("slider_crank.yaml");
  for (double theta : {60.0, 135.0, -100.0}) {
    for (ConstraintSpec& c : scene.constraints)
      if (c.name == "crank_drive") c.drive = Profile(ConstantProfile{theta * kDegree});
    const Model model = compileModel(scene);
    const StaticResult eq = solveEquilibrium(scene, model, 0.0);
    INFO("crank at " << theta << "°: " << eq.message);
    REQUIRE(eq.converged);
    CHECK(eq.path_steps >= 1);
    const double r = 0.2, L = 0.6, s = std::sin(theta * kDegree);
    const double x = model.jointFrame(eq.q.data(), model.findJoint("slider.origin")).r.x();
    CHECK(x == Approx(r * std::cos(theta * kDegree) + std::sqrt(L * L - r * r * s * s)).epsilon(1e-10));
  }
}

TEST_CASE("Revolute drive: one root per turn, slope 1", "[constraints][drives]") {
  // Φ₆ as a function of the angle error e = ψ − ψ_d: zero only at e = 0 within (−π, π), with
  // unit slope there, monotone (the old sin e had a root at π and no slope at ±π/2).
  const Profile drive(ConstantProfile{0.3});
  const ConstraintLaw law{ConstraintType::Revolute, 2, &drive};
  const auto phi = [&](double e) {
    const Frame j1{Vec3::Zero(), Mat3::Identity()};
    const Frame j2{Vec3::Zero(), axisAngle(Vec3::UnitZ(), 0.3 + e)};
    double out[6];
    constraintEquations<double>(law, j1, j2, 0.0, out);
    return out[5];
  };
  CHECK(std::abs(phi(0.0)) < 1e-15);
  CHECK((phi(1e-6) - phi(-1e-6)) / 2e-6 == Approx(1.0).epsilon(1e-8));
  double previous = phi(-3.1);
  for (double e = -3.0; e < 3.1; e += 0.1) {
    const double now = phi(e);
    CHECK(now > previous);
    CHECK((std::abs(e) < 1e-9 || std::abs(now) > 0.09));
    previous = now;
  }
}
