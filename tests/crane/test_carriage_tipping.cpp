// The statics' acceptance of a crane on supports: a carriage whose load tips it is no equilibrium
// (the case fails, saying it tipped), one whose load barely lets it stand is (with the margin of
// a moment balance); a solution is accepted only with its force residual small beside the
// forces present; and a statics past the tipping point stops soon after its corrector ends tipped.
//
// The tests' carriage on pads (carriage_on_pads.hpp) straight ahead: the pads' front edge at
// x = 2.5 m, the upper carriage's 6 t 1 m behind the axis, the load 8 m out. Its resultant
// x_r = (8 L − 6 t · 1 m) / (26 t + L) reaches the edge at L = 12.909 t.

#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "carriage_on_pads.hpp"
#include "cranesim/crane/support_reading.hpp"
#include "cranesim/model/carriage_tipping.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "cranesim/solvers/equilibrium_system.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kTippingLoad = 71000.0 / 5.5;  // kg: 8 L − 6000 = 2.5 (26000 + L)

double resultantX(double load) { return (8.0 * load - 6000.0) / (26000.0 + load); }

Scene carriageScene(double load) {
  test::CarriageOnPads c;
  c.load_mass = load;
  return parseScene(test::carriageOnPadsYaml(c), "<test>");
}

/// Why the scene's equilibrium is no stand of the crane: sceneEquilibrium's exception (none
/// found) or equilibriumInstability's answer (found, but tipped or unstable); empty when it stands.
std::string rejection(const Scene& scene, const Model& model) {
  const Assembler assembler(model);
  try {
    return equilibriumInstability(model, sceneEquilibrium(scene, model, assembler, true), true);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
}

}  // namespace

TEST_CASE("A carriage that barely stands is an equilibrium with the moment balance's margin", "[supports][statics]") {
  const double load = 12500.0;  // the resultant 5.8 cm inside the front edge
  const Scene scene = carriageScene(load);
  const Model model = compileModel(scene);
  CHECK(rejection(scene, model).empty());
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  CHECK(carriageTipped(model, eq.q, 0.0).empty());
  const VecX zero = VecX::Zero(model.nv);
  const SupportReading r = readSupports(model, *model.envelope.supports, {eq.q.data(), zero.data(), zero.data(), 0.0, model.gravity});
  const double weight = (26000.0 + load) * 9.81;
  CHECK(r.carried == Approx(weight).epsilon(1e-9));
  // W (2.5 m − x_r) about the front edge: the ground settles by 1e-5 m, the geometry with it.
  CHECK(r.tipping.margin == Approx(weight * (2.5 - resultantX(load))).epsilon(1e-3));
  for (const PadReading& pad : r.pads) CHECK(pad.force > 0.0);  // two rows of pads: the rear ones carry up to the edge
}

TEST_CASE("A carriage whose load tips it has no equilibrium: the statics say it tipped", "[supports][statics]") {
  // 13.3 t puts the resultant 5.5 cm beyond the front edge: no load on the pads balances it.
  // The statics must not report a number for it; whatever they reach, they say it tipped.
  for (const double load : {13300.0, 20000.0}) {
    CAPTURE(load, resultantX(load));
    REQUIRE(resultantX(load) > 2.5);
    const Scene scene = carriageScene(load);
    const Model model = compileModel(scene);
    const std::string why = rejection(scene, model);
    CAPTURE(why);
    CHECK(why.find("tipped") != std::string::npos);
  }
  CHECK(resultantX(kTippingLoad) == Approx(2.5).epsilon(1e-12));
}

TEST_CASE("A carriage resting on two pads in one line counts as tipped, on three it stands", "[supports][statics]") {
  // The carriage drawn tilted about its front edge by 1 mrad: the rear pads 5 m behind it rise
  // 5 mm, off the bed; the front ones carry (their settlement is the drawing's own).
  const Scene scene = carriageScene(9000.0);
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  CHECK(carriageTipped(model, eq.q, 0.0).empty());
  const int carriage = model.nodes[static_cast<std::size_t>(model.envelope.supports->node)].q;
  VecX tilted = eq.q;
  tilted(carriage + 2) += 2.5e-3;  // centre up by 2.5 m × 1 mrad …
  tilted(carriage + 4) = 1e-3;     // … and turned about y: x = +2.5 m (front) stays, x = −2.5 m rises
  const std::string why = carriageTipped(model, tilted, 0.0);
  CAPTURE(why);
  CHECK(why.find("has tipped") != std::string::npos);
  CHECK(why.find("front_left") != std::string::npos);
  CHECK(why.find("front_right") != std::string::npos);
  CHECK(why.find("rear") == std::string::npos);
  VecX lifted = eq.q;
  lifted(carriage + 2) += 1.0;
  CHECK(carriageTipped(model, lifted, 0.0).find("lifted off") != std::string::npos);
}

TEST_CASE("A solution is accepted only with its force residual small beside the forces present", "[supports][statics]") {
  // The standing carriage's equilibrium, and the same with the carriage 1 mm deeper in the bed:
  // its four pads' springs of 5e9 N/m push 2e7 N more than the weight they balance.
  const Scene scene = carriageScene(9000.0);
  const Model model = compileModel(scene);
  StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  EquilibriumSystem system(model, 0.0);
  VecX x(system.size());
  x << eq.q, eq.lambda;
  StaticResult accepted;
  acceptEquilibrium(system, x, accepted);
  CHECK(accepted.converged);
  CHECK(accepted.force_residual <= 1e-6 * 9000.0 * 9.81);
  const int carriage = model.nodes[static_cast<std::size_t>(model.envelope.supports->node)].q;
  x(carriage + 2) -= 1e-3;
  StaticResult off;
  acceptEquilibrium(system, x, off);
  CHECK_FALSE(off.converged);
  CHECK(off.force_residual == Approx(4 * 5.0e9 * 1e-3).epsilon(0.05));
  CHECK(off.message.find("force residual") != std::string::npos);
}

TEST_CASE("The outrigger crane with a load past its tipping load fails as tipped", "[supports][statics][crane]") {
  // configs/crane_on_outriggers.yaml with its luffing rope at 34 m (the load 55 m out) and 80 t,
  // twice what tips it there: the statics used to end "converged" with the carriage tilted by
  // 3.5° onto its front pads, the resultant on their edge and 5.6e4 N left in the residual, a
  // case of the load chart counted as computed. The same crane with 20 t stands.
  for (const double load : {80000.0, 20000.0}) {
    CAPTURE(load);
    Scene scene = test::loadScene("crane_on_outriggers.yaml");
    for (MemberSpec& m : scene.members)
      if (m.name == "luffing_rope") m.length = Profile(ConstantProfile{34.0});
    for (RigidBodySpec& b : scene.bodies)
      if (b.name == "load") b.mass = load;
    const Model model = compileModel(scene);
    const std::string why = rejection(scene, model);
    CAPTURE(why);
    CHECK((why.find("has tipped") != std::string::npos) == (load == 80000.0));
    if (load == 20000.0) CHECK(why.empty());
  }
}

TEST_CASE("A statics past the tipping point stops once its corrector ends tipped", "[supports][statics][crane]") {
  // The outrigger crane luffed out to 34 m with 80 t tips at 47 % of the path from its drawing.
  // Past that point there is no equilibrium, only a tipping point to find more closely: the path
  // stops halving its step at 1/64 of the path (PathOptions::min_step_tipped) instead of 1/4096,
  // and reports where it stopped within that step.
  Scene scene = test::loadScene("crane_on_outriggers.yaml");
  for (MemberSpec& m : scene.members)
    if (m.name == "luffing_rope") m.length = Profile(ConstantProfile{34.0});
  for (RigidBodySpec& b : scene.bodies)
    if (b.name == "load") b.mass = 80000.0;
  const Model model = compileModel(scene);
  PathOptions options;
  const StaticResult coarse = solveEquilibrium(scene, model, 0.0, options);
  options.min_step_tipped = options.min_step;
  const StaticResult fine = solveEquilibrium(scene, model, 0.0, options);
  CAPTURE(coarse.message, coarse.iterations, fine.iterations, coarse.path_reached, fine.path_reached);
  for (const StaticResult* r : {&coarse, &fine}) {
    CHECK_FALSE(r->converged);
    CHECK(r->message.find("has tipped") != std::string::npos);
  }
  CHECK(std::abs(coarse.path_reached - fine.path_reached) <= 1.0 / 64);
  CHECK(3 * coarse.iterations < 2 * fine.iterations);  // 107 against 178 iterations
}
