// The supports' horizontal forces: friction with memory (model/anchored_support_element.hpp). A pad
// off the ground carries nothing; a carriage pushed sideways at its pads' level stands while the
// push stays below μ W, displaced by the held law's hand statics, has no equilibrium beyond it,
// sticks on its pads' shear springs in a run, slides under a larger push with the acceleration
// (P − μ W)/m less the slip law's band, and, released, stays where it slid, at rest, with the
// push's work dissipated; a carriage on two tracks turned past their friction turns as the
// anchors' ellipse says and, released, stays turned with the work dissipated; a carriage
// whose load tips it falls over its front edge in a run instead of hanging on its lifted pads,
// and the run's envelope says it tipped when its rear pads lift; a track's anchor slides and
// turns within the ellipse of its friction; the element's Jacobian is its residual's derivative.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "carriage_on_pads.hpp"
#include "cranesim/model/anchored_support_element.hpp"
#include "cranesim/model/support_elements.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "element_differences.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kMass = 20000.0, kGravity = 9.81, kFriction = 0.4;  // kg, m/s², μ
constexpr double kSubgradeModulus = 1.0e9, kPadArea = 0.5;          // N/m³, m²
constexpr double kShearStiffness = 0.8 * kSubgradeModulus * kPadArea;  // N/m per pad (shear_ratio 0.8)

/// The tests' 20 t carriage on a bed of the constants above: `supports` under ground.supports,
/// `joints` its joints (all at the supports' level z = 0, its centroid 0.6 m above), `load` its
/// one load at its origin.
std::string testCarriage(const std::string& supports, const std::string& joints, const std::string& load, double t_end) {
  return fmt::format(R"(
name: test carriage
gravity: [0, 0, -{g}]
ground:
  supports:
    body: carriage
    soil: {{subgrade_modulus: {k_s}, allowable_pressure: 1.0e6}}
    friction: {mu}
{supports}
bodies:
  - name: carriage
    mass: {mass}
    centroid: [0, 0, 0.6]
    inertia: [30000, 40000, 60000]
    joints:
{joints}
loads:
  - {load}
solver: {{t_end: {t_end}, rtol: 1.0e-7, atol: 1.0e-9}}
output: {{interval: 0.25}}
)",
                     fmt::arg("g", kGravity), fmt::arg("k_s", kSubgradeModulus), fmt::arg("mu", kFriction), fmt::arg("supports", supports),
                     fmt::arg("mass", kMass), fmt::arg("joints", joints), fmt::arg("load", load), fmt::arg("t_end", t_end));
}

/// A 20 t carriage on four pads at (±2.5, ±2) m pushed along x by `push` N at its origin, the
/// pads' level: the push puts no moment on it, each pad carries W/4 and a quarter of the push.
/// `scale` is the push's profile.
std::string pushedCarriage(double push, double t_end, const std::string& scale = "1") {
  std::string pads = "    pads:\n";
  for (const char* pad : {"front_left", "rear_left", "rear_right", "front_right"})
    pads += fmt::format("      - {{name: {0}, joint: carriage.{0}, area: {1}}}\n", pad, kPadArea);
  return testCarriage(pads, R"(      - {name: front_left, position: [2.5, 2, 0]}
      - {name: rear_left, position: [-2.5, 2, 0]}
      - {name: rear_right, position: [-2.5, -2, 0]}
      - {name: front_right, position: [2.5, -2, 0]})",
                      fmt::format("{{name: push, joint: carriage.origin, force: [{}, 0, 0], scale: {}}}", push, scale), t_end);
}

/// The test carriage on two tracks 6 m long (6 stretches of 0.5 m² each, the pads' area) at
/// y = ±2 m, turned about z by `torque` N·m at its origin, the tracks' level: by symmetry it turns
/// about z without sliding, each stretch carrying W/12. `scale` is the torque's profile.
std::string turnedCarriage(double torque, double t_end, const std::string& scale) {
  std::string tracks = "    tracks:\n";
  for (const char* track : {"left", "right"})
    tracks += fmt::format("      - {{name: {0}, from: carriage.{0}_rear, to: carriage.{0}_front, width: {1}, segments: 6}}\n", track, kPadArea);
  return testCarriage(tracks, R"(      - {name: left_rear, position: [-3, 2, 0]}
      - {name: left_front, position: [3, 2, 0]}
      - {name: right_rear, position: [-3, -2, 0]}
      - {name: right_front, position: [3, -2, 0]})",
                      fmt::format("{{name: turn, joint: carriage.origin, torque: [0, 0, {}], scale: {}}}", torque, scale), t_end);
}

/// A load's profile that holds it for the first second only.
constexpr const char* kFirstSecond = "{type: table, t: [0, 1], value: [1, 0], interpolation: step}";

/// The scene of `yaml` at rtol 1e-9, for books that close to 1e-6.
Scene booksScene(const std::string& yaml) {
  Scene scene = parseScene(yaml, "<test>");
  scene.solver.rtol = 1e-9;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-11);
  return scene;
}

/// The lever ρ of a test track's friction: the mean √(x_i² + r₀²) of its stretches, r₀ = ⅔ √(A/π).
double trackLever() {
  const double r0 = 2.0 / 3.0 * std::sqrt(kPadArea / std::numbers::pi);
  double lever = 0.0;
  for (const double x : {0.5, 1.5, 2.5}) lever += std::sqrt(x * x + r0 * r0) / 3.0;
  return lever;
}

/// The friction torque of one track turning about the carriage's centre, 2 m off its own, with
/// the angular acceleration α: at full slip its pull g lies along its scaled motion
/// (2 ω, 0, ρ ω), |g| = μN + b + o, so T = (μN + b + o) √(2² + ρ²); o is the over-pull whose
/// catch-up rate o²/(2 w Σk τ) (w = 0.05 μN + b) matches the anchor lag ε times the anchor's
/// scaled acceleration α √(2² + ρ²) (the pads' slidingAcceleration, on Σk of six stretches).
double trackTurningTorque(double acceleration) {
  const double bound = kFriction * kMass * kGravity / 2.0, arm = std::sqrt(4.0 + std::pow(trackLever(), 2));
  const double width = AnchoredSupportElement::kCatchUpFraction * bound + AnchoredSupportElement::kSlipBandFloor;
  const double over = std::sqrt(2.0 * width * 6.0 * kShearStiffness * AnchoredSupportElement::kCatchUpTime *
                                AnchoredSupportElement::kAnchorLag * std::max(acceleration, 0.0) * arm);
  return (bound + AnchoredSupportElement::kSlipBandFloor + over) * arm;
}

/// The carriage's turn about z from its joint at (3, 2, 0) m, sample by sample.
std::vector<double> turnAngles(const test::SimulationRun& run) {
  const std::vector<double>& p = run.jointPositions("carriage.left_front");
  std::vector<double> out;
  for (std::size_t i = 0; i < p.size() / 3; ++i) out.push_back(std::atan2(p[3 * i + 1], p[3 * i]) - std::atan2(2.0, 3.0));
  return out;
}

/// The bed under the test carriage's front-left pad, its level at z = 0.
SupportBed frontLeftBed() {
  SupportBed bed;
  bed.level = 0.0;
  bed.anchor = Vec3(2.5, 2.0, 0.0);
  bed.law = {5.0e8, 4.0e5, 1e-5};
  bed.shear_stiffness = 4.0e8;
  bed.shear_damping = 3.6e5;
  bed.friction = kFriction;
  return bed;
}

/// The carriage's acceleration sliding under `push` > μ W, by the fixed point of the test below.
double slidingAcceleration(double push) {
  const double weight = kMass * kGravity, floor = AnchoredSupportElement::kSlipBandFloor;
  const double width = AnchoredSupportElement::kCatchUpFraction * kFriction * weight / 4.0 + floor;
  double acceleration = (push - kFriction * weight) / kMass;
  for (int k = 0; k < 20; ++k) {
    const double over = std::sqrt(2.0 * width * kShearStiffness * AnchoredSupportElement::kCatchUpTime * AnchoredSupportElement::kAnchorLag * acceleration);
    acceleration = (push - kFriction * weight - 4.0 * (floor + over)) / kMass;
  }
  return acceleration;
}

/// The carriage's move along x from where it was drawn at the equilibrium.
double equilibriumShift(const Model& model, const StaticResult& eq) {
  const int origin = model.findJoint("carriage.origin");
  return model.jointFrame(eq.q.data(), origin).r.x() - model.jointFrame(model.q0.data(), origin).r.x();
}

}  // namespace

TEST_CASE("A pad off the ground carries nothing, however far it has moved across the bed", "[supports][friction]") {
  const SupportBed bed = frontLeftBed();
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
    // Nor across the bed: statics bounds its shear spring by μ N = 0.
    const auto& anchored = dynamic_cast<const AnchoredSupportElement&>(*model.elements[static_cast<std::size_t>(support.element) + 1]);
    ElementInput held = at;
    held.rates = ParameterRates::Held;
    Eigen::Matrix<double, 9, 1> rows;
    anchored.residual(held, rows.data());
    CHECK(rows.head<6>().norm() <= 1e-12 * weight);
  }
  CHECK(lifted == 1);
}

TEST_CASE("A carriage pushed sideways stands below μ W, displaced as hand statics say, and not beyond", "[supports][friction][statics]") {
  const double weight = kMass * kGravity, limit = kFriction * weight;
  // Each pad carries N = W/4 and T = P/4 across. Statics holds the anchors where they were drawn:
  // T = k u up to the stick's onset ς μN, then ς μN + w y/√(1 + y²) with y = (k u − ς μN)/w,
  // w = (1 − ς) μN: k u = μN (ς + (1 − ς) y), y = z/√(1 − z²), z = (s − ς)/(1 − ς), s = P/(μ W).
  const double stick = AnchoredSupportElement::kStickFraction;
  for (const double share : {0.1, 0.5, 0.9, 0.98}) {
    CAPTURE(share);
    const Scene scene = parseScene(pushedCarriage(share * limit, 1.0), "<test>");
    const Model model = compileModel(scene);
    const StaticResult eq = solveEquilibrium(scene, model, 0.0);
    REQUIRE(eq.converged);
    const double z = std::max(share - stick, 0.0) / (1.0 - stick), y = z / std::sqrt(1.0 - z * z);
    const double hand = share <= stick ? share * limit / 4.0 / kShearStiffness : limit / 4.0 * (stick + (1.0 - stick) * y) / kShearStiffness;
    CHECK(equilibriumShift(model, eq) == Approx(hand).epsilon(1e-6));
  }
  for (const double share : {1.02, 1.2}) {
    CAPTURE(share);
    const Scene scene = parseScene(pushedCarriage(share * limit, 1.0), "<test>");
    const Model model = compileModel(scene);
    CHECK_FALSE(solveEquilibrium(scene, model, 0.0).converged);
  }
}

TEST_CASE("A carriage pushed below μ W sticks: the shear springs' k law holds, the anchors stay", "[supports][friction][dynamics]") {
  // 0.3 μ W switched on at t = 0 on the drawn carriage: it overshoots to at most 0.6 μ W, below
  // the stick's onset (0.9 μ N per pad), rings down on its dampers and rests at P/(4k); the
  // anchors do not move at all (the slip law is exactly zero below the onset).
  const double push = 0.3 * kFriction * kMass * kGravity;
  const test::SimulationRun run(parseScene(pushedCarriage(push, 1.0), "<test>"));
  REQUIRE(run.outcome.complete);
  const std::vector<double>& x = run.jointPositions("carriage.origin");
  const std::size_t last = run.recorder.time().size() - 1;
  CHECK(x[3 * last] - x[0] == Approx(push / (4.0 * kShearStiffness)).epsilon(1e-6));
  int anchors = 0;
  for (const Node& n : run.model.nodes) {
    if (n.name.find(".anchor") == std::string::npos) continue;
    ++anchors;
    for (int k = 0; k < 2; ++k)
      for (const double slid : run.recorder.stateColumn(n.q + k)) CHECK(slid == 0.0);
  }
  CHECK(anchors == 4);
}

TEST_CASE("A carriage pushed past μ W slides with the acceleration (P − μ W)/m less the slip band", "[supports][friction][dynamics]") {
  // From rest under P = 1.5 μ W: its pads stick on their shear springs for a few milliseconds,
  // then slide, and the carriage's x gains a·h² in each second difference over h = 0.25 s. At
  // full slip each pad pulls its anchor along with k|e| = μN + b (b = kSlipBandFloor) plus the
  // over-pull o that makes the anchor's catch-up rate o²/(2 w k τ) (w = 0.05 μN + b, τ = 0.01 s)
  // match its lag ε a: m a = P − μ W − 4 (b + o).
  const double weight = kMass * kGravity, push = 1.5 * kFriction * weight;
  const double acceleration = slidingAcceleration(push);
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
  CHECK(run.recorder.relativeBalanceDrift() <= 1e-5);
}

TEST_CASE("A carriage pushed past μ W for 1 s and released stays where it slid, at rest, its push dissipated", "[supports][friction][dynamics]") {
  // 1.5 μ W for 1 s: the carriage slides with a₁ (the test above) and, released, brakes with
  // (μ W + 4 b)/m to rest after x = v₁²/2 (1/a₁ + 1/a₂), v₁ = a₁ · 1 s less the few milliseconds
  // it sticks. It stays there: its last two samples agree, its speed is gone, and the push's
  // work is dissipated, the books closing at rtol 1e-9.
  const double weight = kMass * kGravity, push = 1.5 * kFriction * weight;
  const test::SimulationRun run(booksScene(pushedCarriage(push, 3.0, kFirstSecond)));
  REQUIRE(run.outcome.complete);
  const std::vector<double>& times = run.recorder.time();
  const std::vector<double>& x = run.jointPositions("carriage.origin");
  const std::size_t last = times.size() - 1;
  REQUIRE(times[last] == Approx(3.0));
  const double slide = x[3 * last] - x[0];
  const double a1 = slidingAcceleration(push);
  const double a2 = (kFriction * weight + 4.0 * AnchoredSupportElement::kSlipBandFloor) / kMass;
  CAPTURE(slide);
  CHECK(slide == Approx(0.5 * a1 * a1 * (1.0 / a1 + 1.0 / a2)).epsilon(5e-3));
  CHECK(std::abs(x[3 * last] - x[3 * (last - 1)]) <= 1e-9);
  const int origin = run.model.findJoint("carriage.origin");
  const int carriage = run.model.joints[static_cast<std::size_t>(origin)].node;
  const double speed = run.recorder.stateColumn(run.assembler.vOffset() + run.model.nodes[static_cast<std::size_t>(carriage)].v).back();
  CHECK(std::abs(speed) <= 1e-6);
  const double work = push * (x[3 * 4] - x[0]);  // the push's work up to its release at 1 s (sample 4)
  REQUIRE(times[4] == Approx(1.0));
  CHECK(run.recorder.dissipated().back() == Approx(work).epsilon(1e-6));
  CHECK(run.recorder.relativeBalanceDrift() <= 1e-6);
}

TEST_CASE("A carriage on tracks turned past friction and released stays where it turned, its work dissipated", "[supports][friction][dynamics]") {
  // 1.5 times the tracks' friction torque at rest 2 T(0) for 1 s: the carriage turns with
  // α₁ = (1.5 · 2 T(0) − 2 T(α₁)) / I_z in each second difference over h = 0.25 s (after it
  // sticks for a few milliseconds; T(α) grows by the anchor lag's over-pull, 1.6 % here), then
  // brakes with 2 T(0) / I_z to rest and stays. Coulomb's law at each stretch,
  // Σ μN_i √(x_i² + 2²), would turn 5 % slower. The torque's work is dissipated.
  const double inertia = 60000.0, torque = 1.5 * 2.0 * trackTurningTorque(0.0);
  double accelerating = (torque - 2.0 * trackTurningTorque(0.0)) / inertia;
  for (int k = 0; k < 20; ++k) accelerating = (torque - 2.0 * trackTurningTorque(accelerating)) / inertia;
  const double braking = -2.0 * trackTurningTorque(0.0) / inertia;
  const test::SimulationRun run(booksScene(turnedCarriage(torque, 3.0, kFirstSecond)));
  REQUIRE(run.outcome.complete);
  const std::vector<double>& times = run.recorder.time();
  const std::vector<double> turn = turnAngles(run);
  REQUIRE(times[4] == Approx(1.0));
  for (std::size_t i = 2; i <= 4; ++i) {
    CAPTURE(times[i]);
    CHECK((turn[i] - 2 * turn[i - 1] + turn[i - 2]) / (0.25 * 0.25) == Approx(accelerating).epsilon(2e-3));
  }
  CAPTURE(turn[4], turn[5], turn[6]);
  CHECK((turn[6] - 2 * turn[5] + turn[4]) / (0.25 * 0.25) == Approx(braking).epsilon(2e-3));
  const std::size_t last = times.size() - 1;
  REQUIRE(times[last] == Approx(3.0));
  CHECK(std::abs(turn[last] - turn[last - 1]) <= 1e-9);
  const double stop = turn[4] + 0.5 * std::pow(accelerating * 1.0, 2) / -braking;
  CHECK(turn[last] == Approx(stop).epsilon(1e-2));
  // Neither slid: the carriage's origin stays on the turn's axis.
  const std::vector<double>& origin = run.jointPositions("carriage.origin");
  CHECK(std::hypot(origin[3 * last], origin[3 * last + 1]) <= 1e-9);
  CHECK(run.recorder.dissipated().back() == Approx(torque * turn[4]).epsilon(1e-6));
  CHECK(run.recorder.relativeBalanceDrift() <= 1e-6);
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
  // The envelope says it tipped from the first sample on which only the front pads carry, the
  // rear pads' lift-off, and names the edge it stands on.
  const std::vector<EnvelopeEvent> events = run.recorder.envelope().events();
  const auto event = [&](const std::string& what, const std::string& part) {
    return std::find_if(events.begin(), events.end(), [&](const EnvelopeEvent& e) { return e.what == what && e.part == part; });
  };
  const auto tipped = event("tipped", "carriage"), lifted = event("lifted off", "rear_left");
  REQUIRE(tipped != events.end());
  REQUIRE(lifted != events.end());
  CHECK(tipped->leaves_envelope);
  CHECK(tipped->first_time == lifted->first_time);
  CHECK(tipped->why.find("front_left, front_right") != std::string::npos);
  CHECK(tipped->why.find("an edge") != std::string::npos);
}

TEST_CASE("A track's anchor slides and turns within the ellipse of its friction, sticks inside it", "[supports][friction]") {
  // A rigid strip of 12 points 1 m apart along x on a level bed, each settled to carry N, its
  // anchor at rest where it was drawn. The body is moved by u across the strip (y) and turned
  // by β about its centre (z), so that point x_i pulls its anchor with k (u + β x_i) along y:
  // F = 12 k u, M = k β Σ x_i². With uniform N the centre of friction is the strip's centre and
  // the lever ρ = mean √(x_i² + r₀²), r₀ = ⅔ √(A/π); the anchor stays put while
  // √(F² + (M/ρ)²) < 0.9 μN (12 points) and slides beyond μN + b, along the pull's direction
  // in (F, M/ρ) (associated flow), following the body's motion projected on it.
  SupportBed bed = frontLeftBed();
  const double k = bed.shear_stiffness, area = 0.5, n = 12.0;
  std::vector<SupportPoint> points;
  double lever = 0.0, arm2 = 0.0;
  for (int i = 0; i < 12; ++i) {
    const double x = i - 5.5;
    bed.anchor = Vec3(x, 0.0, 0.0);
    points.push_back({Vec3(x, 0.0, 0.0), bed});
    lever += std::sqrt(x * x + std::pow(2.0 / 3.0 * std::sqrt(area / std::numbers::pi), 2)) / n;
    arm2 += x * x;
  }
  const AnchoredSupportElement strip(points, std::vector<double>(12, area), 0, 1, {0, 1, 2, 3, 4, 5, 6, 7, 8}, {0, 1, 2, 3, 4, 5, 6, 7, 8});
  const double settle = 2e-4;
  const double normal = penaltyForce<double>(settle, 0.0, bed.law), bound = kFriction * normal * n;
  for (const double share : {0.5, 0.89, 1.2}) {
    for (const double turn_part : {0.0, 0.6, 1.0}) {
      CAPTURE(share, turn_part);
      // |g| = share μN split between the slide (F) and the turn (M/ρ).
      const double F = share * bound * std::sqrt(1.0 - turn_part * turn_part), M = share * bound * turn_part * lever;
      const double u = F / (n * k), beta = M / (k * arm2);
      Eigen::Matrix<double, 9, 1> q = Eigen::Matrix<double, 9, 1>::Zero(), v = q, a = q, r;
      q << 0.0, u, -settle, 0.0, 0.0, beta, 0.0, 0.0, 0.0;
      v << 0.0, 0.3, 0.0, 0.0, 0.0, 0.05, 0.0, 0.0, 0.0;  // the body slides on and turns (rad/s)
      const ElementInput in{q.data(), v.data(), a.data(), 0.0, Vec3(0, 0, -kGravity)};
      strip.residual(in, r.data());
      // The anchor's rows are ṡ − w with ṡ = 0: −w.
      const Eigen::Vector3d w = -r.tail<3>();
      if (share < AnchoredSupportElement::kStickFraction) {
        CHECK(w.norm() == 0.0);
        continue;
      }
      // Beyond μN + b: full slip, w = ĝ (ĝ · Ẇ) + catch-up along ĝ, Ẇ = (0, 0.3, ρ · 0.05).
      const Eigen::Vector3d direction(0.0, std::sqrt(1.0 - turn_part * turn_part), turn_part);
      const Eigen::Vector3d scaled(w(0), w(1), w(2) * lever);  // (ν, ρ θ̇)
      const double along = 0.3 * direction(1) + lever * 0.05 * direction(2);
      const double over = share * bound - bound - AnchoredSupportElement::kSlipBandFloor;
      const double width = AnchoredSupportElement::kCatchUpFraction * bound + AnchoredSupportElement::kSlipBandFloor;
      const double catching = (over - 0.5 * width) / (n * k * AnchoredSupportElement::kCatchUpTime);
      CHECK(direction.dot(scaled) == Approx(0.5 * (along + std::sqrt(along * along + 1e-8)) + catching).epsilon(1e-9));
      CHECK((scaled - direction * direction.dot(scaled)).norm() <= 1e-9 * scaled.norm());
    }
  }
}

namespace {

/// The element's Jacobians against central differences of its residual at q, v, a.
void checkAnchoredJacobian(const AnchoredSupportElement& element, Eigen::Matrix<double, 9, 1> q, Eigen::Matrix<double, 9, 1> v,
                           Eigen::Matrix<double, 9, 1> a, bool held) {
  ElementInput in{q.data(), v.data(), a.data(), 0.0, Vec3(0, 0, -kGravity)};
  if (held) in.rates = ParameterRates::Held, v.setZero(), a.setZero();
  const double cj = 1e3;
  Eigen::Matrix<double, 9, 18> J;
  element.jacobian(in, cj, J.data());
  MatX fd = test::residualDifferences(element, in, 1e-9);
  Eigen::Matrix<double, 9, 9> M;
  element.mass(in, M.data());
  if (!held) fd.rightCols(9) += cj * M;
  const double q_error = (J.leftCols(9) - fd.leftCols(9)).norm() / std::max(fd.leftCols(9).norm(), 1.0);
  const double v_error = (J.rightCols(9) - fd.rightCols(9)).norm() / std::max(fd.rightCols(9).norm(), 1.0);
  CAPTURE(q_error, v_error, fd.leftCols(9).norm(), fd.rightCols(9).norm());
  CHECK(q_error <= 1e-6);
  CHECK(v_error <= 1e-6);
  Eigen::Matrix<double, 9, 9> Jq;
  element.coordinateJacobian(in, Jq.data());
  CHECK((Jq - J.leftCols(9)).norm() <= 1e-14 * std::max(J.leftCols(9).norm(), 1.0));
}

}  // namespace

TEST_CASE("An anchored support's Jacobian is its residual's derivative: sticking, slipping, sliding, lifted, held", "[supports][friction]") {
  const std::vector<int> local{0, 1, 2, 3, 4, 5, 6, 7, 8};
  SECTION("a pad") {
    const SupportBed bed = frontLeftBed();
    const AnchoredSupportElement pad({{Vec3(2.5, 2.0, 0.0), bed}}, {4.0}, 0, 1, local, local);
    // Settled 0.2 mm (N ≈ 1e5 N, μN ≈ 4e4 N), the anchor slid 0.2 m along x and 1 cm along y, the
    // pad k|e| = 2e4 N (sticking), 3.8e4 N (in the slip band), 4.1e4 N (full slip) ahead of it, or
    // 1 mm above the bed; moving along its offset and turning a little.
    for (const double pull : {2.0e4, 3.8e4, 4.1e4})
      for (const double lift : {-2e-4, 1e-3})
        for (const bool held : {false, true}) {
          CAPTURE(pull, lift, held);
          Eigen::Matrix<double, 9, 1> q, v, a;
          q << 0.2 + 0.8 * pull / bed.shear_stiffness, 0.01 + 0.6 * pull / bed.shear_stiffness, lift, 1e-8, -2e-8, 3e-8, 0.2, 0.01, 0.0;
          v << 0.3, 0.2, 0.001, 0.02, -0.01, 0.03, 0.28, 0.19, 0.0;
          a << 1.0, 0.5, 0.0, 0.1, 0.0, 0.2, 0.9, 0.4, 0.1;
          checkAnchoredJacobian(pad, q, v, a, held);
        }
  }
  SECTION("a track of five stretches, its anchor slid and turned") {
    // Points 1 m apart along x, each settled about 0.2 mm (the body tilted a little: N varies by
    // 2 % along the track; μN ≈ 2e5 N), the anchor slid (0.2, 0.01) m and turned 0.02 rad, the
    // body off it by δ (|g| ≈ 5 k |δ|: 1e5 N sticking, 1.9e5 N in the band, 2.1e5 N sliding)
    // and turned 2e-7 rad further (a moment), or 1 mm above the bed.
    SupportBed bed = frontLeftBed();
    std::vector<SupportPoint> points;
    for (int i = 0; i < 5; ++i) {
      bed.anchor = Vec3(i - 2.0, 0.0, 0.0);
      points.push_back({bed.anchor, bed});
    }
    const AnchoredSupportElement track(points, std::vector<double>(5, 1.0), 0, 1, local, local);
    for (const double pull : {1.0e5, 1.9e5, 2.1e5})
      for (const double lift : {-2e-4, 1e-3})
        for (const bool held : {false, true}) {
          CAPTURE(pull, lift, held);
          const double shift = pull / (5.0 * bed.shear_stiffness);
          Eigen::Matrix<double, 9, 1> q, v, a;
          q << 0.2 + 0.8 * shift, 0.01 + 0.6 * shift, lift, 2e-8, 1e-6, 0.02 + 2e-7, 0.2, 0.01, 0.02;
          v << 0.3, 0.2, 0.001, 0.02, -0.01, 0.03, 0.28, 0.19, 0.025;
          a << 1.0, 0.5, 0.0, 0.1, 0.0, 0.2, 0.9, 0.4, 0.1;
          checkAnchoredJacobian(track, q, v, a, held);
        }
  }
}
