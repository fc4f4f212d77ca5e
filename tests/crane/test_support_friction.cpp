// The supports' horizontal forces held within friction (elements/friction_bound.hpp): a pad off
// the ground carries nothing; a carriage pushed sideways at its pads' level stands while the
// push stays below μ W, displaced by the bounded springs' hand statics, has no equilibrium
// beyond it, and slides under a larger push with the acceleration (P − μ W)/m; a carriage whose
// load tips it falls over its front edge in a run instead of hanging on its lifted pads.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "carriage_on_pads.hpp"
#include "cranesim/model/support_elements.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kMass = 20000.0, kGravity = 9.81, kFriction = 0.4;  // kg, m/s², μ
constexpr double kSubgradeModulus = 1.0e9, kPadArea = 0.5;          // N/m³, m²
constexpr double kShearStiffness = 0.8 * kSubgradeModulus * kPadArea;  // N/m per pad (shear_ratio 0.8)

/// A 20 t carriage on four pads at (±2.5, ±2) m pushed along x by `push` N at its origin, the
/// pads' level: the push puts no moment on it, each pad carries W/4 and a quarter of the push.
std::string pushedCarriage(double push, double t_end) {
  return fmt::format(R"(
name: carriage pushed sideways
gravity: [0, 0, -{g}]
ground:
  supports:
    body: carriage
    soil: {{subgrade_modulus: {k_s}, allowable_pressure: 1.0e6}}
    friction: {mu}
    pads:
      - {{name: front_left, joint: carriage.front_left, area: {area}}}
      - {{name: rear_left, joint: carriage.rear_left, area: {area}}}
      - {{name: rear_right, joint: carriage.rear_right, area: {area}}}
      - {{name: front_right, joint: carriage.front_right, area: {area}}}
bodies:
  - name: carriage
    mass: {mass}
    centroid: [0, 0, 0.6]
    inertia: [30000, 40000, 60000]
    joints:
      - {{name: front_left, position: [2.5, 2, 0]}}
      - {{name: rear_left, position: [-2.5, 2, 0]}}
      - {{name: rear_right, position: [-2.5, -2, 0]}}
      - {{name: front_right, position: [2.5, -2, 0]}}
loads:
  - {{name: push, joint: carriage.origin, force: [{push}, 0, 0]}}
solver: {{t_end: {t_end}, rtol: 1.0e-7, atol: 1.0e-9}}
output: {{interval: 0.25}}
)",
                     fmt::arg("g", kGravity), fmt::arg("k_s", kSubgradeModulus), fmt::arg("mu", kFriction), fmt::arg("area", kPadArea),
                     fmt::arg("mass", kMass), fmt::arg("push", push), fmt::arg("t_end", t_end));
}

/// The carriage's move along x from where it was drawn at the equilibrium.
double equilibriumShift(const Model& model, const StaticResult& eq) {
  const int origin = model.findJoint("carriage.origin");
  return model.jointFrame(eq.q.data(), origin).r.x() - model.jointFrame(model.q0.data(), origin).r.x();
}

}  // namespace

TEST_CASE("A pad off the ground carries nothing, however far it has moved across the bed", "[supports][friction]") {
  SupportBed bed;
  bed.level = 0.0;
  bed.anchor = Vec3(2.5, 2.0, 0.0);
  bed.law = {5.0e8, 4.0e5, 1e-5};
  bed.shear_stiffness = 4.0e8;
  bed.shear_damping = 3.6e5;
  const SupportElement pad({{Vec3(2.5, 2.0, 0.0), bed}}, 0, {0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4, 5});
  // 1 mm above the bed, 5 cm and a few degrees off its drawn place, moving and turning.
  VecX q(6), v(6), a = VecX::Zero(6), r(6);
  q << 0.05, -0.03, 0.001, 0.0, 0.0, 0.05;
  v << 0.4, -0.3, 0.2, 0.1, -0.2, 0.3;
  const ElementInput in{q.data(), v.data(), a.data(), 0.0, Vec3(0, 0, -kGravity)};
  REQUIRE(pad.closure(in) < 0.0);
  pad.residual(in, r.data());
  CHECK(r.norm() <= 1e-12 * kMass * kGravity);
  CHECK(pad.contactForce(in) == 0.0);

  // The same on the tests' carriage slewed to 40°: its rear-right pad lifts off at the equilibrium.
  test::CarriageOnPads c;
  c.slewed_deg = 40.0;
  const Scene scene = parseScene(test::carriageOnPadsYaml(c), "<test>");
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const VecX zero = VecX::Zero(model.nv);
  const ElementInput at{eq.q.data(), zero.data(), zero.data(), 0.0, model.gravity};
  const double weight = (c.carriage_mass + c.upper_mass + c.load_mass) * c.gravity;
  int lifted = 0;
  for (const EnvelopeSupport& support : model.envelope.supports->pads) {
    const auto& element = dynamic_cast<const SupportElement&>(*model.elements[support.element]);
    if (element.closure(at) >= 0.0) continue;
    ++lifted;
    CAPTURE(support.name);
    VecX force(element.size());
    element.residual(at, force.data());
    CHECK(force.norm() <= 1e-12 * weight);
  }
  CHECK(lifted == 1);
}

TEST_CASE("A carriage pushed sideways stands below μ W, displaced as hand statics say, and not beyond", "[supports][friction][statics]") {
  const double weight = kMass * kGravity, limit = kFriction * weight;
  // Each pad carries N = W/4 and P/4 across: P/4 = k u μN / √((μN)² + (k u)²), so
  // k u = (P/4) / √(1 − (P/(μ W))²): the elastic shift P/(4k) grown as the push nears μ W.
  for (const double share : {0.1, 0.5, 0.9, 0.98}) {
    CAPTURE(share);
    const Scene scene = parseScene(pushedCarriage(share * limit, 1.0), "<test>");
    const Model model = compileModel(scene);
    const StaticResult eq = solveEquilibrium(scene, model, 0.0);
    REQUIRE(eq.converged);
    const double hand = share * limit / 4.0 / (kShearStiffness * std::sqrt(1.0 - share * share));
    CHECK(equilibriumShift(model, eq) == Approx(hand).epsilon(1e-6));
  }
  for (const double share : {1.02, 1.2}) {
    CAPTURE(share);
    const Scene scene = parseScene(pushedCarriage(share * limit, 1.0), "<test>");
    const Model model = compileModel(scene);
    CHECK_FALSE(solveEquilibrium(scene, model, 0.0).converged);
  }
}

TEST_CASE("A carriage pushed past μ W slides with the acceleration (P − μ W)/m", "[supports][friction][dynamics]") {
  // From rest under P = 1.5 μ W: its pads stick on their shear springs for a few milliseconds,
  // then slide, and the carriage's x gains a·h² in each second difference over h = 0.25 s.
  const double weight = kMass * kGravity, push = 1.5 * kFriction * weight;
  const double acceleration = (push - kFriction * weight) / kMass;
  const test::SimulationRun run(parseScene(pushedCarriage(push, 1.0), "<test>"));
  REQUIRE(run.outcome.complete);
  const std::vector<double>& times = run.recorder.time();
  const std::vector<double>& x = run.jointPositions("carriage.origin");
  REQUIRE(times.size() == 5);
  CHECK(times.back() == Approx(1.0));
  for (std::size_t i = 3; i < times.size(); ++i) {  // from 0.25 s: past the sticking
    CAPTURE(times[i]);
    CHECK((x[3 * i] - 2 * x[3 * (i - 1)] + x[3 * (i - 2)]) / (0.25 * 0.25) == Approx(acceleration).epsilon(1e-4));
  }
  // The books close: the push's work is the carriage's kinetic energy and the pads' bounded
  // springs' (their slide μ N |u| is held in Φ, elements/friction_bound.hpp).
  CHECK(run.recorder.relativeBalanceDrift() <= 1e-5);
}

TEST_CASE("A carriage whose load tips it falls over its front edge in a run", "[supports][friction][dynamics]") {
  // 16 t on the tests' carriage straight ahead puts the resultant 0.4 m beyond the front pads'
  // edge (x = (8 L − 6 t · 1 m)/(26 t + L) = 2.905 m). Its rear pads lift off and, carrying
  // nothing, let it turn about the front edge ever faster: their rise gains more in each half
  // second than in the one before, and passes 0.5 m (a turn of 6°) within 2 s.
  test::CarriageOnPads c;
  c.load_mass = 16000.0;
  Scene scene = parseScene(test::carriageOnPadsYaml(c), "<test>");
  scene.solver.t_end = 2.0;
  scene.solver.rtol = 1e-6;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-8);
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const std::vector<double>& times = run.recorder.time();
  const std::vector<double>& rear = run.jointPositions("carriage.rear_left");
  std::vector<double> rise_at;  // the rear pad's rise at 0.5 s, 1 s, 1.5 s and 2 s
  for (const double target : {0.5, 1.0, 1.5, 2.0}) {
    const auto at = std::min_element(times.begin(), times.end(), [&](double a, double b) { return std::abs(a - target) < std::abs(b - target); });
    REQUIRE(*at == Approx(target));
    rise_at.push_back(rear[3 * static_cast<std::size_t>(at - times.begin()) + 2] - rear[2]);
  }
  REQUIRE(rise_at.size() == 4);
  CAPTURE(rise_at[0], rise_at[1], rise_at[2], rise_at[3]);
  for (std::size_t k = 1; k + 1 < rise_at.size(); ++k) CHECK(rise_at[k + 1] - rise_at[k] > rise_at[k] - rise_at[k - 1]);
  CHECK(rise_at.back() > 0.5);
}
