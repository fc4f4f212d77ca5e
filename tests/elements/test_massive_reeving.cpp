// Massive reeved ropes (elements/massive_reeving.hpp): parts that carry the rope's weight, the
// material running over the sheaves, against hand formulas — a hook block's falls at rest (W/n
// at the hook, each fall's weight between its ends), a long lead part's sag against the elastic
// catenary, the hook's speed while hoisting, the energy books, the massless rope as the density
// goes to zero, the wind on the parts — and the Jacobians against central differences.

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "cranesim/model/massive_reeved_rope_element.hpp"
#include "cranesim/model/wind_elements.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "elastic_catenary.hpp"
#include "guided_hook.hpp"
#include "random_states.hpp"
#include "scene_fixtures.hpp"
#include "spread_blocks.hpp"

using namespace cranesim;

namespace {

constexpr double kGravity = 9.81, kWeight = test::kHookWeight, kRopeArea = test::kHookRopeArea;
constexpr double kEA = 1.0e11 * kRopeArea, kLineWeight = 7800.0 * kRopeArea * kGravity;  // w, N per m of rope

/// The guided hook (guided_hook.hpp) on `falls` massive falls of `elements` cables each, every
/// sheave of efficiency `efficiency`; the rope's length `length` (YAML; empty: 1e-3 shorter than
/// the drawn path, so that the parts start taut).
Scene massiveHook(int falls, int elements, double efficiency = 1.0, const std::string& length = "", double density = 7800.0,
                  const std::string& fidelity = "massive") {
  const std::string parts = fidelity == "massive" ? fmt::format("\n    elements_per_part: {}", elements) : "";
  const std::string taut = fmt::format("{}", (8.0 + 10.0 * falls) * (1.0 - 1e-3));
  return test::guidedHook(fmt::format("    falls: {}\n    winch: ground.winch\n    head: {{joint: ground.head, radius: 0.3}}\n"
                                      "    hook: {{joint: hook.sheaves, radius: 0.3}}\n    efficiency: {}\n    fidelity: {}{}\n"
                                      "    length: {}",
                                      falls, efficiency, fidelity, parts, length.empty() ? taut : length),
                          0.05, 8.0, density);
}

const MassiveReevedRopeElement& massiveRope(const Model& model) {
  const int index = findReevedRope(model, "hoist");
  REQUIRE(index >= 0);
  return dynamic_cast<const MassiveReevedRopeElement&>(reevedRope(model, index));
}

/// A fall's tensions at its top and bottom ends: its elements' tensions at the ends (the first
/// and last, `down`: from the head to the hook) and half an element's weight beyond them.
struct FallEnds {
  double top, bottom, weight;
};
FallEnds fallEnds(const MassiveReevedRopeElement& rope, const ElementInput& in, int part) {
  const std::vector<double> T = rope.elementTensions(in), sigma = rope.materialCoordinates(in);
  const int n = rope.kernel().elements_per_part;
  const double weight = kLineWeight * (sigma[part] - sigma[part + 1]), half = weight / (2.0 * n);
  const double first = T[part * n], last = T[part * n + n - 1];
  const bool down = part % 2 == 1;
  return {(down ? first : last) + half, (down ? last : first) - half, weight};
}

}  // namespace

TEST_CASE("A hook block on n massive falls at rest: W/n at the hook, each fall's weight between its ends",
          "[reeving][massive][statics]") {
  const int falls = GENERATE(1, 2, 4);
  const Scene scene = massiveHook(falls, 8);
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const MassiveReevedRopeElement& rope = massiveRope(model);
  const VecX v = VecX::Zero(model.nv);
  const ElementInput in{eq.q.data(), v.data(), nullptr, 0.0, model.gravity};
  for (int k = 1; k <= falls; ++k) {
    const FallEnds ends = fallEnds(rope, in, k);
    INFO(falls << " falls, fall " << k << ": top " << ends.top << " N, bottom " << ends.bottom << " N, weight " << ends.weight << " N");
    CHECK(std::abs((ends.top - ends.bottom) / ends.weight - 1.0) < 1e-6);
    CHECK(std::abs(ends.bottom / (kWeight / falls) - 1.0) < 1e-9);
  }
  // The lead part reaches the head sheave at the first fall's top tension (the sheave turns
  // freely): its last element's tension along the chord, half an element's weight beyond.
  const int n = rope.kernel().elements_per_part;
  const std::vector<Vec3> x = rope.chainPositions(in);
  const std::vector<double> sigma = rope.materialCoordinates(in);
  const double rise = (x[n] - x[n - 1]).normalized().z();  // dz/ds of the last element
  const double lead_at_head = rope.elementTensions(in)[n - 1] + 0.5 * kLineWeight * (sigma[0] - sigma[1]) / n * rise;
  const FallEnds first = fallEnds(rope, in, 1);
  INFO("lead part at the head " << lead_at_head << " N, first fall's top " << first.top << " N");
  CHECK(std::abs(lead_at_head / first.top - 1.0) < 1e-6);
}

TEST_CASE("A long massive lead part sags as Irvine's elastic catenary", "[reeving][massive][statics]") {
  // A 500 kg hook on one fall, the winch 40 m beside the head sheave at its height: the lead
  // part hangs ~0.9 m, far enough from a parabola (8/3 (d/l)² ≈ 1.4e-3) to tell the two apart.
  const int elements = 32;
  const Scene scene = parseScene(fmt::format(R"(
name: long lead
ground:
  joints:
    - {{name: winch, position: [-40, 0, 20]}}
    - {{name: head, position: [0, 0, 20]}}
    - {{name: guide, position: [0, 0, 10]}}
bodies:
  - name: hook
    mass: 500
    inertia: [10, 10, 10]
    position: [0, 0, 10]
    joints: [{{name: sheave, position: [0, 0, 0]}}]
members:
  - name: hoist
    type: rope
    element: reeved
    path: [ground.winch, {{joint: ground.head, radius: 0.3}}, hook.sheave]
    fidelity: massive
    elements_per_part: {}
    section: {{radius: 0.01}}
    material: {{density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.3}}
    length: 49.9
constraints:
  - {{name: guide, type: prismatic, joints: [ground.guide, hook.origin], axis: z}}
solver: {{t_end: 1, initial_state: equilibrium}}
)",
                                             elements),
                                 "<test>");
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const MassiveReevedRopeElement& rope = massiveRope(model);
  const VecX v = VecX::Zero(model.nv);
  const ElementInput in{eq.q.data(), v.data(), nullptr, 0.0, model.gravity};
  const std::vector<double> sigma = rope.materialCoordinates(in), T = rope.elementTensions(in);
  const std::vector<Vec3> x = rope.chainPositions(in);
  const test::ElasticCatenary catenary = test::elasticCatenary(40.0, sigma[0] - sigma[1], kLineWeight, kEA);
  const double sag = 20.0 - x[elements / 2].z(), H = T[0] * (x[1] - x[0]).normalized().x();
  const double parabola = kLineWeight * (sigma[0] - sigma[1]) * 40.0 / (8.0 * H);
  INFO("sag " << sag << " m, elastic catenary " << catenary.sag << " m, parabola " << parabola << " m; H " << H
              << " N, catenary's " << catenary.H << " N");
  CHECK(std::abs(sag / catenary.sag - 1.0) < 1e-3);
  CHECK(std::abs(H / catenary.H - 1.0) < 1e-3);
  CHECK(std::abs(parabola / catenary.sag - 1.0) > 1e-3);  // the test tells a catenary from a parabola
  // The fall carries the hook: its bottom end W, its top the lead part's tension at the head.
  const FallEnds fall = fallEnds(rope, in, 1);
  CHECK(std::abs(fall.bottom / (500.0 * kGravity) - 1.0) < 1e-9);
}

TEST_CASE("A massive hook block hoisted at v rises at v/n, the books close", "[reeving][massive][dynamics]") {
  // Reeling in 2.8 m at 0.4 m/s (trapezoid, 1 s ramps) from 1.5 s: steady from 2.5 s to 8.5 s.
  const int falls = GENERATE(2, 4);
  const double efficiency = GENERATE(1.0, 0.96);
  const double drawn = 8.0 + 10.0 * falls;
  Scene scene = massiveHook(falls, 6, efficiency,
                            fmt::format("{{type: trapezoid, from: {}, distance: -2.8, t_start: 1.5, duration: 8, t_accel: 1, "
                                        "t_decel: 1}}",
                                        drawn * (1.0 - 1e-3)));
  scene.solver.rtol = 1e-8;
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const DynamicState initial = runInitialState(scene, model, assembler, true);
  struct HookSpeed final : SampleSink {
    HookSpeed(const Model& model, const Assembler& assembler) : model(model), recorder(assembler) {}
    void sample(double t, const double* y, const WorkTerms& work) override {
      recorder.sample(t, y, work);
      if (t < 5.0) return;
      const double hook_speed = y[model.nq + model.nodes[0].v + 2];
      worst = std::max(worst, std::abs(hook_speed));
      least = std::min(least, std::abs(hook_speed));
      ++samples;
    }
    const Model& model;
    ResultsRecorder recorder;
    double worst = 0.0, least = 1e9;
    int samples = 0;
  } sink(model, assembler);
  const SimulationOutcome run = simulate(assembler, initial, sink);
  REQUIRE(run.complete);
  REQUIRE(sink.samples > 20);
  const double expected = 0.4 / falls, strain = kWeight / falls / kEA;
  INFO(falls << " falls, η = " << efficiency << ": hook speed " << sink.least << "…" << sink.worst << " m/s, v/n " << expected
             << " m/s; balance drift " << sink.recorder.relativeBalanceDrift() << " of " << sink.recorder.energyScale()
             << " J; " << run.statistics.steps << " steps");
  CHECK(std::abs(sink.worst / expected - 1.0) < 2.0 * strain);
  CHECK(std::abs(sink.least / expected - 1.0) < 2.0 * strain);
  CHECK(sink.recorder.relativeBalanceDrift() < 1e-6);
}

TEST_CASE("As its density goes to zero the massive rope holds the hook as the massless one", "[reeving][massive][statics]") {
  const int falls = GENERATE(2, 3);
  const auto hookHeight = [&](const std::string& fidelity, double density) {
    const Scene scene = massiveHook(falls, 4, 1.0, "", density, fidelity);
    const Model model = compileModel(scene);
    const StaticResult eq = solveEquilibrium(scene, model, 0.0);
    REQUIRE(eq.converged);
    return eq.q(model.nodes[0].q + 2);
  };
  const double massless = hookHeight("massless", 7800.0);
  double previous = std::abs(hookHeight("massive", 7800.0) - massless);
  for (const double density : {78.0, 0.78, 0.0078}) {
    const double difference = std::abs(hookHeight("massive", density) - massless);
    INFO(falls << " falls, density " << density << " kg/m³: the hook " << difference << " m from the massless rope's");
    CHECK(difference < 0.02 * previous);  // the weight's stretch and sag, ∝ density
    previous = difference;
  }
  CHECK(previous < 1e-9);
}

namespace {

/// The spread blocks' parts as massive chains of three cables each.
const std::string kMassiveParts = "    fidelity: massive\n    elements_per_part: 3\n";

/// A random state about the drawing: coordinates moved by 1e-2, velocities and accelerations 0.1.
struct RandomState {
  VecX q, v, a;
};
RandomState randomState(const Model& model, test::Rng& rng) {
  RandomState s{model.q0, VecX(model.nv), VecX(model.nv)};
  for (int k = 0; k < model.nq; ++k) s.q(k) += 1e-2 * rng();
  for (int k = 0; k < model.nv; ++k) s.v(k) = 0.1 * rng(), s.a(k) = 0.1 * rng();
  return s;
}

}  // namespace

TEST_CASE("Massive reeved rope: Jacobian equals central differences of the residual", "[reeving][massive][jacobian]") {
  const bool capstan = GENERATE(false, true);
  const Model model = test::spreadBlocks(0.96, capstan, kMassiveParts);
  const MassiveReevedRopeElement& rope = massiveRope(model);
  test::Rng rng(11);
  for (int trial = 0; trial < 3; ++trial) {
    const RandomState s = randomState(model, rng);
    const double t = 1.0 + trial, cj = 50.0;
    const int n = rope.size();
    const ElementInput in{s.q.data(), s.v.data(), s.a.data(), t, model.gravity};
    MatX J(n, 2 * n), fd(n, 2 * n), M(n, n);
    rope.jacobian(in, cj, J.data());
    rope.mass(in, M.data());
    const auto residual = [&](const VecX& q, const VecX& v) {
      VecX r(n);
      rope.residual(ElementInput{q.data(), v.data(), s.a.data(), t, model.gravity}, r.data());
      return r;
    };
    for (int c = 0; c < 2 * n; ++c) {
      VecX qp = s.q, qm = s.q, vp = s.v, vm = s.v;
      const double h = 1e-6;
      if (c < n) qp(rope.coordinateIndices()[c]) += h, qm(rope.coordinateIndices()[c]) -= h;
      else vp(rope.velocityIndices()[c - n]) += h, vm(rope.velocityIndices()[c - n]) -= h;
      fd.col(c) = (residual(qp, vp) - residual(qm, vm)) / (2.0 * h);
    }
    fd.rightCols(n) += cj * M;
    const double q_error = (J.leftCols(n) - fd.leftCols(n)).norm() / fd.leftCols(n).norm();
    const double v_error = (J.rightCols(n) - fd.rightCols(n)).norm() / fd.rightCols(n).norm();
    INFO((capstan ? "with a capstan, " : "") << "trial " << trial << ": q columns off by " << q_error << ", dq columns by " << v_error);
    CHECK(q_error < 1e-7);
    CHECK(v_error < 1e-7);
    MatX Jq(n, n);
    rope.coordinateJacobian(in, Jq.data());
    CHECK((Jq - J.leftCols(n)).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("Massive reeved rope keeps the books: dqᵀr = dE/dt − P_winch + P_sheaves + P_damping", "[reeving][massive][energy]") {
  const double efficiency = GENERATE(1.0, 0.96);
  const bool capstan = GENERATE(false, true);
  const Model model = test::spreadBlocks(efficiency, capstan, kMassiveParts);
  const MassiveReevedRopeElement& rope = massiveRope(model);
  const Assembler assembler(model);
  test::Rng rng(5);
  for (int trial = 0; trial < 3; ++trial) {
    const RandomState s = randomState(model, rng);
    const double t = 1.0 + 0.1 * trial;
    const VecX qdot = assembler.coordinateRates(s.q.data(), s.v.data());
    const auto energy = [&](double tau) {  // T + V along q + τ q̇, dq + τ a
      const VecX q = s.q + tau * qdot, v = s.v + tau * s.a;
      const ElementInput at{q.data(), v.data(), nullptr, t + tau, model.gravity};
      return rope.kineticEnergy(at) + rope.potentialEnergy(at);
    };
    const double h = 1e-4;
    const double rate = (8.0 * (energy(h) - energy(-h)) - (energy(2.0 * h) - energy(-2.0 * h))) / (12.0 * h);
    const ElementInput in{s.q.data(), s.v.data(), s.a.data(), t, model.gravity};
    VecX r(rope.size());
    rope.residual(in, r.data());
    double virtual_power = 0.0;
    for (int k = 0; k < rope.size(); ++k) virtual_power += s.v(rope.velocityIndices()[k]) * r(k);
    const double winch = rope.explicitTimePower(in), dissipated = rope.dissipatedPower(in);
    const double scale = std::abs(virtual_power) + std::abs(rate) + std::abs(winch) + dissipated;
    INFO("η = " << efficiency << (capstan ? " and a capstan" : "") << ", trial " << trial << ": dqᵀr " << virtual_power
                << " W, dE/dt " << rate << " W, winch " << winch << " W, dissipated " << dissipated << " W");
    CHECK(std::abs(virtual_power - (rate - winch + dissipated)) < 1e-8 * scale);
    CHECK(dissipated >= 0.0);
    CHECK(winch != 0.0);
  }
}

TEST_CASE("The wind on a massive rope's parts: ½ρ c d U² per metre across them", "[reeving][massive][wind]") {
  // A 40 m lead part and a 10 m fall in the x-z plane, a steady wind of 10 m/s along y: every
  // cable meets it square, 0.5 · 1.25 kg/m³ · 1.2 · 0.02 m · (10 m/s)² = 1.5 N per metre.
  const Model model = test::loadYaml(R"(
name: wind on a massive rope
ground:
  joints:
    - {name: winch, position: [-40, 0, 20]}
    - {name: head, position: [0, 0, 20]}
    - {name: guide, position: [0, 0, 10]}
bodies:
  - name: hook
    mass: 500
    inertia: [10, 10, 10]
    position: [0, 0, 10]
    joints: [{name: sheave, position: [0, 0, 0.5]}]
members:
  - name: hoist
    type: rope
    element: reeved
    path: [ground.winch, {joint: ground.head, radius: 0.3}, hook.sheave]
    fidelity: massive
    elements_per_part: 4
    section: {radius: 0.01}
    material: {density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.3}
    length: 49.4
constraints:
  - {name: guide, type: prismatic, joints: [ground.guide, hook.origin], axis: z}
wind:
  speed: 10
  direction: [0, 1, 0]
  members: [{member: hoist, drag_coefficient: 1.2}]
solver: {t_end: 1}
)");
  REQUIRE(model.wind_parts.size() == 1);
  REQUIRE(model.wind_parts[0].elements.size() == 8);
  const VecX zero = VecX::Zero(model.nv);
  const ElementInput at_rest{model.q0.data(), zero.data(), nullptr, 0.0, model.gravity};
  Vec3 total = Vec3::Zero();
  for (const int e : model.wind_parts[0].elements) total += dynamic_cast<const WindElement&>(*model.elements[e]).resultantForce(at_rest);
  const double expected = 1.5 * (40.0 + 9.5);
  INFO("wind on the rope " << total.transpose() << " N, by hand (0, " << expected << ", 0) N");
  CHECK((total - Vec3(0.0, expected, 0.0)).norm() < 1e-12 * expected);

  // The cable reaching the hook's sheave: its Jacobian against central differences.
  const Element& wind = *model.elements[model.wind_parts[0].elements.back()];
  test::Rng rng(3);
  const RandomState s = randomState(model, rng);
  const int n = wind.size();
  const ElementInput in{s.q.data(), s.v.data(), nullptr, 0.5, model.gravity};
  MatX J(n, 2 * n), fd(n, 2 * n);
  wind.jacobian(in, 0.0, J.data());
  const auto residual = [&](const VecX& q, const VecX& v) {
    VecX r(n);
    wind.residual(ElementInput{q.data(), v.data(), nullptr, 0.5, model.gravity}, r.data());
    return r;
  };
  for (int c = 0; c < 2 * n; ++c) {
    VecX qp = s.q, qm = s.q, vp = s.v, vm = s.v;
    const double h = 1e-6;
    if (c < n) qp(wind.coordinateIndices()[c]) += h, qm(wind.coordinateIndices()[c]) -= h;
    else vp(wind.velocityIndices()[c - n]) += h, vm(wind.velocityIndices()[c - n]) -= h;
    fd.col(c) = (residual(qp, vp) - residual(qm, vm)) / (2.0 * h);
  }
  const double error = (J - fd).norm() / fd.norm();
  INFO("wind Jacobian off by " << error << " of " << fd.norm());
  CHECK(error < 1e-7);
}
