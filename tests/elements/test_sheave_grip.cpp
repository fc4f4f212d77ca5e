// A sheave's grip on a massless reeved rope (elements/reeved_rope.hpp): Dahl's pre-sliding law
// in the rope's travel over the sheave. The kernel against the law's closed form and the
// pre-sliding distance's hand formula; the element's Jacobian with a held grip against central
// differences; a capstan whose winch stops keeps the ratio it slipped at (stick) and its hook
// stays where it stopped, where a rate law lets it creep by (e^(μθ) − 1) W L / EA.

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/model/reeved_rope_element.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "element_jacobian_error.hpp"
#include "guided_hook.hpp"
#include "random_states.hpp"
#include "scene_fixtures.hpp"
#include "spread_blocks.hpp"

using namespace cranesim;

namespace {

constexpr double kGripFriction = 0.1;
constexpr double kGripEA = 1.0e11 * test::kHookRopeArea;

/// The kernel of a winch → capstan → hook path: the winch 8 m beside the capstan, the hook `drop`
/// m under it; unstretched 17.9 m.
struct CapstanKernel {
  ReevedRopeKernel k;
  ReevedRopeKernel::Points<double> x, xd;
  CapstanKernel() {
    k.total_length = Profile(ConstantProfile{17.9});
    k.section.area = test::kHookRopeArea;
    k.material.youngs_modulus = 1.0e11;
    k.points = 3;
    k.friction_exponent[0] = kGripFriction * std::numbers::pi / 2.0;
    for (auto& p : xd) p.setZero();
    at(10.0);
  }
  void at(double drop) { x[0] = Vec3(-8, 0, 20), x[1] = Vec3(0, 0, 20), x[2] = Vec3(0, 0, 20 - drop); }
  /// T₁/T₀ at the hook `drop` m under the capstan.
  double ratio(double drop) {
    at(drop);
    double T[2];
    k.partTensions(x, xd, 0.0, ParameterRates::Left, T);
    return T[1] / T[0];
  }
};

}  // namespace

TEST_CASE("A sheave's grip: Dahl's law in the rope's travel, the pre-sliding distance of the parts' elasticity",
          "[reeving][capstan][grip]") {
  CapstanKernel c;
  const double lambda = c.k.friction_exponent[0];
  // Not yet held, and in statics: the grip of the drawing, φ = 0, equal tensions.
  CHECK(c.ratio(10.3) == 1.0);
  c.at(10.0);
  c.k.hold(c.x, c.xd, 0.0);
  // δ = λ T₀ / (EA (1/ℓ₀ + 1/ℓ₁)), ℓ₀ = 8, ℓ₁ = 10, T₀ = EA (18/17.9 − 1).
  const double T0 = kGripEA * (18.0 / 17.9 - 1.0), delta = lambda * T0 / (kGripEA * (1.0 / 8.0 + 1.0 / 10.0));
  CHECK(std::abs(c.k.grip[0].distance / delta - 1.0) < 1e-12);
  CHECK(c.ratio(10.0) == 1.0);
  // Lowering u: φ = 1 − e^(−u/δ); the tension rises over the capstan towards the hook.
  for (const double u : {0.3 * delta, delta, 3.0 * delta})
    CHECK(std::abs(std::log(c.ratio(10.0 + u)) / lambda - (1.0 - std::exp(-u / delta))) < 1e-12);
  // Slipping from 21 δ on (e^(−21) = 7.6e-10): the ratio within 1e-9 of e^(μθ) …
  CHECK(std::abs(c.ratio(10.0 + 21.0 * delta) / std::exp(lambda) - 1.0) < 1e-9);
  // … and held there: back at rest the ratio stays (stick), the drawing's 1 forgotten.
  c.at(10.0 + 21.0 * delta);
  c.k.hold(c.x, c.xd, 0.0);
  const double phi = c.k.grip[0].state;
  CHECK(std::abs(c.ratio(10.0 + 21.0 * delta) / std::exp(lambda) - 1.0) < 1e-9);
  // Reversed by u: φ = −1 + (1 + φ₀) e^(−u/δ'), δ' of the tensions where it was held; it passes
  // 0 after δ' ln(1 + φ₀), not at once as a rate law's.
  const double delta2 = c.k.grip[0].distance;
  CHECK(delta2 > delta);  // the rope's strain has grown by the hook's 21 δ
  for (const double u : {0.5 * delta2, delta2 * std::log(1.0 + phi), 4.0 * delta2})
    CHECK(std::abs(std::log(c.ratio(10.0 + 21.0 * delta - u)) / lambda - (-1.0 + (1.0 + phi) * std::exp(-u / delta2))) <
          1e-12);
  CHECK(std::abs(std::log(c.ratio(10.0 + 21.0 * delta - delta2 * std::log(1.0 + phi)))) < 1e-12);
  // A scene's own pre-sliding distance replaces the parts' for every sheave.
  CapstanKernel given;
  given.k.pre_sliding = 0.02;
  given.k.hold(given.x, given.xd, 0.0);
  CHECK(given.k.grip[0].distance == 0.02);
  CHECK(std::abs(std::log(given.ratio(10.0 + 0.02)) / lambda - (1.0 - std::exp(-1.0))) < 1e-12);
  // Held rates (statics, modes): the held grip, whatever the travel.
  double T[2];
  c.at(10.2);
  c.k.partTensions(c.x, c.xd, 0.0, ParameterRates::Held, T);
  CHECK(std::abs(std::log(T[1] / T[0]) / lambda - phi) < 1e-12);
}

TEST_CASE("Reeved rope with held grips: Jacobian equals central differences of the residual", "[reeving][jacobian][grip]") {
  const bool capstan = GENERATE(false, true);
  const Model model = test::spreadBlocks(0.96, capstan);
  const ReevedRopeElement& rope = test::reevedRopeNamed(model);
  test::Rng rng(17);
  for (int trial = 0; trial < 5; ++trial) {
    // Held at a state 5 mm from the evaluated one, with a grip φ₀ ∈ (−1, 1) of its own: the
    // sheaves' travels from there span several δ, on either side.
    VecX q = model.q0, v(model.nv), held = model.q0;
    for (int k = 0; k < model.nq; ++k) held(k) += 1e-2 * rng();
    for (int k = 0; k < model.nq; ++k) q(k) = held(k) + 5e-3 * rng();
    for (int k = 0; k < model.nv; ++k) v(k) = 0.1 * rng();
    const double t = 1.0 + trial;
    rope.forgetMemory();
    rope.hold(ElementInput{held.data(), v.data(), nullptr, t, model.gravity});
    std::vector<double> memory = rope.memory();
    for (std::size_t i = 1; i < memory.size(); i += 3) memory[i] = (i / 3 + trial) % 2 == 0 ? 0.9 : -0.9;
    rope.setMemory(memory.data());
    const int n = rope.size();
    const ElementInput in{q.data(), v.data(), nullptr, t, model.gravity};
    const double error = test::elementJacobianError(rope, q, v, t, model.gravity, 1e-7);
    // The grips must matter here: the forces differ from those of the drawing's grip.
    VecX held_forces(n), fresh_forces(n);
    rope.residual(in, held_forces.data());
    rope.forgetMemory();
    rope.residual(in, fresh_forces.data());
    const double grip_effect = (held_forces - fresh_forces).cwiseAbs().maxCoeff() / fresh_forces.cwiseAbs().maxCoeff();
    INFO((capstan ? "with a capstan, " : "") << "trial " << trial << ": max |J − J_fd| / max |J_fd| = " << error
                                             << ", the grips change the forces by " << grip_effect);
    CHECK(error < 1e-6);
    CHECK(grip_effect > 1e-3);
  }
}

namespace {

/// The guided hook under a capstan (friction 0.1, the drawn 90° wrap), hoisted by the winch 2.8 m
/// (0.4 m/s from 1.5 s, stopping at 9.5 s); records the ratio T₀/T₁ and the hook's height.
struct StoppedCapstan final : SampleSink {
  StoppedCapstan(const Model& model, const Assembler& assembler) : model(model), recorder(assembler) {}
  void sample(double t, const double* y, const WorkTerms& work) override {
    recorder.sample(t, y, work);
    double T[2];
    test::reevedRopeNamed(model).partTensions(ElementInput{y, y + model.nq, nullptr, t, model.gravity}, T);
    const double height = y[model.nodes[0].q + 2];
    if (t >= 8.0 && t <= 8.4) slipping = T[0] / T[1];
    if (t >= 13.0 && !rest.seen) rest = {T[0] / T[1], height, true};
    if (t >= 13.0) {
      ratio_drift = std::max(ratio_drift, std::abs(T[0] / T[1] / rest.ratio - 1.0));
      creep = std::max(creep, std::abs(height - rest.height));
    }
  }
  struct Rest {
    double ratio = 0.0, height = 0.0;
    bool seen = false;
  };
  const Model& model;
  ResultsRecorder recorder;
  double slipping = 0.0, ratio_drift = 0.0, creep = 0.0;
  Rest rest;
};

}  // namespace

TEST_CASE("A capstan whose winch stops keeps the ratio it slipped at, its hook does not creep",
          "[reeving][capstan][grip][dynamics]") {
  const Scene scene = test::guidedHook(
      "    path: [ground.winch, {joint: ground.head, radius: 0.3, friction: 0.1}, hook.sheaves]\n"
      "    length: {type: trapezoid, from: 17.99, distance: -2.8, t_start: 1.5, duration: 8, t_accel: 1, t_decel: 1}",
      0.1, 20.0);
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const DynamicState initial = runInitialState(scene, model, assembler, true);
  StoppedCapstan sink(model, assembler);
  const SimulationOutcome run = simulate(assembler, initial, sink);
  REQUIRE(run.complete);
  const double e = std::exp(kGripFriction * std::numbers::pi / 2.0);
  // A rate law would let the ratio fall back to 1 and the strain with it: the hook would rise by
  // (e^(μθ) − 1) W L / EA, L ≈ 15.2 m of rope after 2.8 m reeled in.
  const double rate_law_creep = (e - 1.0) * test::kHookWeight * 15.2 / kGripEA;
  INFO("slipping T₀/T₁ " << sink.slipping << " (e^(μθ) " << e << "), at rest from 13 s " << sink.rest.ratio
                         << ", drifting by " << sink.ratio_drift << "; the hook moves " << sink.creep
                         << " m from 13 s to 20 s against a rate law's creep " << rate_law_creep << " m; balance drift "
                         << sink.recorder.relativeBalanceDrift());
  CHECK(std::abs(sink.slipping / e - 1.0) < 1e-9);
  // At rest the ratio is held within the band: unequal pulls, not the drawing's 1.
  CHECK(sink.rest.ratio > 1.0 + 0.5 * (e - 1.0));
  CHECK(sink.rest.ratio <= e * (1.0 + 1e-12));
  CHECK(sink.ratio_drift < 1e-6);
  CHECK(sink.creep < 1e-3 * rate_law_creep);
  CHECK(sink.recorder.relativeBalanceDrift() < 1e-6);
}
