// Reeved ropes (elements/reeved_rope.hpp): a hook block on n falls under a fixed head sheave,
// guided vertically, against hand formulas — statics (W/n per part), the line pull of a
// reeving with sheave efficiency η while hoisting and lowering, the hook's speed, the energy
// books — and the element's Jacobian against central differences.

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cranesim/model/reeved_rope_element.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "random_states.hpp"
#include "element_jacobian_error.hpp"
#include "guided_hook.hpp"
#include "scene_fixtures.hpp"
#include "spread_blocks.hpp"

using namespace cranesim;

namespace {

using test::kHookMass;
using test::partTensions;
using test::reevedRopeNamed;
constexpr double kGravity = 9.81, kWeight = test::kHookWeight, kRopeArea = test::kHookRopeArea;

/// The guided hook (guided_hook.hpp) on `falls` falls from a head sheave at 20 m, every sheave
/// of efficiency `efficiency`; the rope's length `length` (YAML; empty: the drawn path),
/// Kelvin–Voigt damping 0.05 s; 8 s.
Scene guidedHook(int falls, double efficiency, const std::string& length = "") {
  return test::guidedHook(fmt::format("    falls: {}\n    winch: ground.winch\n    head: {{joint: ground.head, radius: 0.3}}\n"
                                      "    hook: {{joint: hook.sheaves, radius: 0.3}}\n    efficiency: {}{}",
                                      falls, efficiency, length.empty() ? "" : "\n    length: " + length),
                          0.05, 8.0);
}

/// The line pull T₀ at the winch of n falls over n sheaves of efficiency η (each sheave passed
/// multiplies the tension by η hoisting, by 1/η lowering) holding a load W: Σ_{k=1..n} T_k = W.
double linePull(int n, double eta, bool hoisting) {
  if (eta == 1.0) return kWeight / n;
  return hoisting ? kWeight * (1.0 - eta) / (eta * (1.0 - std::pow(eta, n)))
                  : kWeight * std::pow(eta, n) * (1.0 - eta) / (1.0 - std::pow(eta, n));
}

/// Records, after `from`, the worst relative deviation of the line pull from `expected_pull`
/// and of n·(hook speed)/(winch speed) from 1 + ε, ε the rope's strain; forwards every sample
/// to the results recorder (energy books).
struct SteadyHoist final : SampleSink {
  SteadyHoist(const Model& model, const Assembler& assembler, double from, double expected_pull, int falls, double winch_speed)
      : model(model), recorder(assembler), from(from), expected_pull(expected_pull), falls(falls), winch_speed(winch_speed) {}
  void sample(double t, const double* y, const WorkTerms& work) override {
    recorder.sample(t, y, work);
    if (t < from) return;
    const std::vector<double> T = partTensions(model, y, y + model.nq, t);
    pull_error = std::max(pull_error, std::abs(T[0] / expected_pull - 1.0));
    const double strain = T[0] / (1.0e11 * kRopeArea);
    const double hook_speed = y[model.nq + model.nodes[0].v + 2];
    speed_error = std::max(speed_error, std::abs(falls * hook_speed / winch_speed - (1.0 + strain)));
    ++samples;
  }
  const Model& model;
  ResultsRecorder recorder;
  double from, expected_pull;
  int falls;
  double winch_speed, pull_error = 0.0, speed_error = 0.0;
  int samples = 0;
};

}  // namespace

TEST_CASE("A load on n frictionless falls: each part carries W/n, the hook block is in equilibrium", "[reeving][statics]") {
  const int falls = GENERATE(1, 2, 3, 4, 8);
  const double efficiency = GENERATE(1.0, 0.96);  // at rest a sheave's ratio is 1 (middle of its friction band)
  const Scene scene = guidedHook(falls, efficiency);
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const VecX v = VecX::Zero(model.nv);
  const std::vector<double> T = partTensions(model, eq.q.data(), v.data(), 0.0);
  REQUIRE(static_cast<int>(T.size()) == falls + 1);
  double on_hook = 0.0, worst = 0.0;
  for (int k = 0; k <= falls; ++k) worst = std::max(worst, std::abs(T[k] / (kWeight / falls) - 1.0));
  for (int k = 1; k <= falls; ++k) on_hook += T[k];  // every fall ends at the hook block
  INFO(falls << " falls, η = " << efficiency << ": part tension " << T[1] << " N, worst |T/(W/n) − 1| " << worst);
  CHECK(worst < 1e-9);
  CHECK(std::abs(on_hook / kWeight - 1.0) < 1e-9);
}

TEST_CASE("Steady hoisting and lowering: the line pull of n falls over sheaves of efficiency η", "[reeving][dynamics]") {
  // Reeling at 0.4 m/s (trapezoid, 1 s ramps) from 1.5 s: steady from 2.5 s to 8.5 s; the
  // hook's vibration on the falls (3–6 Hz, damping ratio 0.5–0.9) has died out to 1e-11 by 5 s.
  const int falls = GENERATE(2, 4, 5);
  const double efficiency = GENERATE(1.0, 0.98, 0.96);
  const bool hoisting = GENERATE(true, false);
  const double distance = hoisting ? -2.8 : 2.8, drawn = 8.0 + 10.0 * falls;
  const Scene scene = guidedHook(falls, efficiency,
                                 fmt::format("{{type: trapezoid, from: {}, distance: {}, t_start: 1.5, duration: 8, "
                                             "t_accel: 1, t_decel: 1}}", drawn * (1.0 - 1e-3), distance));
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const DynamicState initial = runInitialState(scene, model, assembler, true);
  const double winch_speed = -distance / 7.0;  // −L̇: distance over duration less a ramp
  SteadyHoist sink(model, assembler, 5.0, linePull(falls, efficiency, hoisting), falls, winch_speed);
  const SimulationOutcome run = simulate(assembler, initial, sink);
  REQUIRE(run.complete);
  REQUIRE(sink.samples > 20);
  INFO(falls << " falls, η = " << efficiency << (hoisting ? ", hoisting" : ", lowering") << ": line pull off the formula by "
             << sink.pull_error << ", n·v_hook/v_winch off 1 + ε by " << sink.speed_error << "; balance drift "
             << sink.recorder.relativeBalanceDrift() << " of " << sink.recorder.energyScale() << " J, sheaves and damping "
             << sink.recorder.dissipated().back() << " J; " << run.statistics.steps << " steps");
  CHECK(sink.pull_error < 1e-6);
  CHECK(sink.speed_error < 1e-9);
  CHECK(sink.recorder.relativeBalanceDrift() < 1e-6);
  if (efficiency < 1.0) CHECK(sink.recorder.dissipated().back() > 0.0);
}

TEST_CASE("Reeved rope: Jacobian equals central differences of the residual", "[reeving][jacobian]") {
  // η = 0.96 and a capstan with the drawing's grips (φ = 0: every ratio 1); the held grips'
  // derivatives: test_sheave_grip.cpp.
  const bool capstan = GENERATE(false, true);
  const Model model = test::spreadBlocks(0.96, capstan);
  const ReevedRopeElement& rope = reevedRopeNamed(model);
  test::Rng rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    VecX q = model.q0, v(model.nv);
    for (int k = 0; k < model.nq; ++k) q(k) += 1e-2 * rng();
    for (int k = 0; k < model.nv; ++k) v(k) = 0.1 * rng();
    const double t = 1.0 + trial;
    const int n = rope.size();
    const ElementInput in{q.data(), v.data(), nullptr, t, model.gravity};
    const double error = test::elementJacobianError(rope, q, v, t, model.gravity, 1e-6);
    INFO((capstan ? "with a capstan, " : "") << "trial " << trial << ": max |J − J_fd| / max |J_fd| = " << error);
    CHECK(error < 1e-7);
    Eigen::MatrixXd J(n, 2 * n), Jq(n, n);
    rope.jacobian(in, 0.0, J.data());
    rope.coordinateJacobian(in, Jq.data());
    CHECK((Jq - J.leftCols(n)).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("Reeved rope keeps the books: dqᵀF = dV/dt − P_winch + P_sheaves + P_damping", "[reeving][energy]") {
  const double efficiency = GENERATE(1.0, 0.96);
  const bool capstan = GENERATE(false, true);
  const Model model = test::spreadBlocks(efficiency, capstan);
  const ReevedRopeElement& rope = reevedRopeNamed(model);
  test::Rng rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    VecX q = model.q0, v(model.nv);
    for (int k = 0; k < model.nq; ++k) q(k) += 1e-2 * rng();
    for (int k = 0; k < model.nv; ++k) v(k) = 0.1 * rng();
    const double t = 1.0 + 0.1 * trial;
    // The sheaves' grips held 5 mm away at ±0.9: the sheaves pass unequal tensions.
    VecX held = q;
    for (int k = 0; k < model.nq; ++k) held(k) += 5e-3 * rng();
    rope.hold(ElementInput{held.data(), v.data(), nullptr, t, model.gravity});
    std::vector<double> memory = rope.memory();
    for (std::size_t i = 1; i < memory.size(); i += 3) memory[i] = (i / 3 + trial) % 2 == 0 ? 0.9 : -0.9;
    rope.setMemory(memory.data());
    const Assembler assembler(model);
    const VecX qdot = assembler.coordinateRates(q.data(), v.data());
    const auto energy = [&](double tau) {
      const VecX qt = q + tau * qdot;
      return rope.potentialEnergy(ElementInput{qt.data(), v.data(), nullptr, t + tau, model.gravity});
    };
    const double h = 1e-4;
    const double rate = (8.0 * (energy(h) - energy(-h)) - (energy(2.0 * h) - energy(-2.0 * h))) / (12.0 * h);
    const ElementInput in{q.data(), v.data(), nullptr, t, model.gravity};
    VecX r(rope.size());
    rope.residual(in, r.data());
    double virtual_power = 0.0;
    for (int k = 0; k < rope.size(); ++k) virtual_power += v(rope.velocityIndices()[k]) * r(k);
    const double winch = rope.explicitTimePower(in), dissipated = rope.dissipatedPower(in);
    const double scale = std::abs(virtual_power) + std::abs(rate) + std::abs(winch) + std::abs(dissipated);
    INFO("η = " << efficiency << (capstan ? " and a capstan" : "") << ", trial " << trial << ": dqᵀF " << virtual_power << " W, dV/dt " << rate << " W, winch "
                << winch << " W, dissipated " << dissipated << " W");
    CHECK(std::abs(virtual_power - (rate - winch + dissipated)) < 1e-8 * scale);
    // Without losses only the material damping dissipates; a grip running back gives energy back.
    if (efficiency == 1.0 && !capstan) CHECK(dissipated >= 0.0);
    CHECK(winch != 0.0);
  }
}

TEST_CASE("A hook block on n collinear falls sways with the period of a pendulum from the head sheave",
          "[reeving][dynamics]") {
  // The hook's sheaves at its centre of mass, 10 m under the head sheave in equilibrium: the n
  // falls hold W along their common line, so the lateral stiffness is W/h and the period
  // 2π √(h/g) (1 + θ₀²/16) for the amplitude θ₀, whatever n (the stretch sets h; the rope's
  // axial modes are damped). Released 1 cm aside: θ₀ = 1e-3.
  const int falls = GENERATE(2, 4, 8);
  const double h = 10.0, lead = 8.0, EA = 1.0e11 * kRopeArea;
  const double unstretched = (lead + falls * h) / (1.0 + kWeight / (falls * EA));
  Scene scene = parseScene(fmt::format(R"(
name: swaying hook block
ground:
  joints: [{{name: winch, position: [-8, 0, 20]}}, {{name: head, position: [0, 0, 20]}}]
bodies:
  - name: hook
    mass: {}
    inertia: [1000, 1000, 1000]
    position: [0, 0.01, {}]
    joints: [{{name: sheaves, position: [0, 0, 0]}}]
members:
  - name: hoist
    type: rope
    element: reeved
    falls: {}
    winch: ground.winch
    head: {{joint: ground.head, radius: 0.3}}
    hook: {{joint: hook.sheaves, radius: 0.3}}
    efficiency: 0.96
    section: {{radius: 0.01}}
    material: {{density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.3}}
    damping: 0.05
    length: {:.17g}
solver: {{t_end: 26, rtol: 1.0e-10, atol: 1.0e-12}}
output: {{interval: 0.002}}
)",
                                       kHookMass, 20.0 - std::sqrt(h * h - 1e-4), falls, unstretched),
                           "<test>");
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const std::vector<double>& t = run.recorder.time();
  const std::vector<double>& r = run.jointPositions("hook.origin");
  std::vector<double> crossings;  // downward zero crossings of y, interpolated linearly
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double y0 = r[3 * (i - 1) + 1], y1 = r[3 * i + 1];
    if (y0 > 0.0 && y1 <= 0.0) crossings.push_back(t[i - 1] + (t[i] - t[i - 1]) * y0 / (y0 - y1));
  }
  REQUIRE(crossings.size() >= 4);
  const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double amplitude = 0.01 / h;
  const double expected = 2.0 * std::numbers::pi * std::sqrt(h / kGravity) * (1.0 + amplitude * amplitude / 16.0);
  INFO(falls << " falls: period " << period << " s over " << crossings.size() - 1 << " swings, pendulum " << expected
             << " s, relative " << period / expected - 1.0);
  CHECK(std::abs(period / expected - 1.0) < 1e-8);
}

TEST_CASE("The reeved thesis crane: the falls carry hook block and load, equal parts at rest", "[reeving][crane]") {
  const Scene scene = test::loadScene("crane_reeved.yaml");
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const ReevedRopeElement& rope = reevedRopeNamed(model, "hoist_rope");
  const VecX v = VecX::Zero(model.nv);
  const ElementInput in{eq.q.data(), v.data(), nullptr, 0.0, model.gravity};
  VecX r(rope.size());
  rope.residual(in, r.data());
  const Node& hook = model.nodes[model.joints[model.findJoint("hook_block.origin")].node];
  const auto& at = rope.velocityIndices();
  const int z = static_cast<int>(std::find(at.begin(), at.end(), hook.v + 2) - at.begin());
  REQUIRE(z < rope.size());
  const double carried = (390000.6 + 8000.0) * 9.8;  // load and hook block
  const std::vector<double> T = partTensions(model, eq.q.data(), v.data(), 0.0, "hoist_rope");
  REQUIRE(T.size() == 9);
  const auto [lowest, highest] = std::minmax_element(T.begin(), T.end());
  INFO("rope's lift on the hook block " << -r(z) << " N against " << carried << " N; parts " << *lowest << " … " << *highest
                                        << " N");
  CHECK(std::abs(-r(z) / carried - 1.0) < 1e-9);
  CHECK(*highest / *lowest - 1.0 < 1e-12);
  CHECK(std::abs(T[0] / (carried / 8.0) - 1.0) < 1e-5);  // the falls lean by 0.15 m over 52 m: cos = 1 − 4e-6
  // The luffing rope's 12 parts, equal at rest, hold the ties' joint Q: 13 parts with the lead line.
  const std::vector<double> luffing = partTensions(model, eq.q.data(), v.data(), 0.0, "luffing_rope");
  REQUIRE(luffing.size() == 13);
  const auto [least, most] = std::minmax_element(luffing.begin(), luffing.end());
  INFO("luffing rope's parts " << *least << " … " << *most << " N");
  CHECK(*most / *least - 1.0 < 1e-12);
  CHECK(*least > 0.0);
}
