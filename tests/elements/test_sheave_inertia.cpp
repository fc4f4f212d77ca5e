// A sheave's rotary inertia on a massive reeved rope (elements/massive_reeving.hpp): the Atwood
// machine with a massive pulley — two masses on one rope over one fixed sheave of inertia J and
// radius r accelerate at a = (m1 − m2) g / (m1 + m2 + J/r²) for a rigid rope, and at that to
// within the rope's strain for the model's elastic one (derived below) — its energy books over
// the run, and the sheave's kinetic energy ½ J (σ̇/r)² in the rope's.

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <cmath>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/model/massive_reeved_rope_element.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kHeavy = 120.0, kLight = 80.0, kRadius = 0.3, kGravity = 9.81;
constexpr double kEA = 1.0e11 * 3.14159265358979e-4;  // the rope's E and A (radius 1 cm)

/// The Atwood machine's steady running on the elastic rope, the rope's own mass left out. The
/// material runs towards the heavy mass at w = −σ̇; with constant tensions T_k = EA ε_k each part's
/// chord grows at w (1 + ε_k), so the heavy mass falls at ẇ (1 + ε₀) and the light one rises at
/// ẇ (1 + ε₁). The sheave's equation is (J/r²) ẇ = −∂V/∂σ = T₀ (1 + ε₀/2) − T₁ (1 + ε₁/2) (the
/// strain energy ½ EA L ε² of each part at fixed chord, ∂/∂L = −T (1 + ε/2)); with
/// T₀ = m₁ (g − ẇ (1 + ε₀)) and T₁ = m₂ (g + ẇ (1 + ε₁)), solved by fixed-point iteration. A
/// rigid rope (ε = 0) gives (m1 − m2) g / (m1 + m2 + J/r²); the strains (3e-5) move it by 9e-6.
struct SteadyRunning {
  double w_rate, strain_heavy, strain_light;
  double lightAcceleration() const { return w_rate * (1.0 + strain_light); }
};
SteadyRunning steadyRunning(double inertia) {
  SteadyRunning s{0.0, 0.0, 0.0};
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double e0 = s.strain_heavy, e1 = s.strain_light;
    s.w_rate = kGravity * (kHeavy * (1.0 + 0.5 * e0) - kLight * (1.0 + 0.5 * e1)) /
               (inertia / (kRadius * kRadius) + kHeavy * (1.0 + e0) * (1.0 + 0.5 * e0) + kLight * (1.0 + e1) * (1.0 + 0.5 * e1));
    s.strain_heavy = kHeavy * (kGravity - s.w_rate * (1.0 + e0)) / kEA;
    s.strain_light = kLight * (kGravity + s.w_rate * (1.0 + e1)) / kEA;
  }
  return s;
}

/// The two masses hang on the axis under the sheave (heavy 10 m below it, light 12 m), each guided
/// vertically, the rope between them over the sheave. The rope's density is 1e-3 kg/m³: its
/// 7e-6 kg weigh 3e-8 of the masses, below what the test resolves, so the rope's own mass is left
/// out of the expected acceleration. Its stretch at the mean tension starts it near the running
/// strain, and its damping (5 ms) settles what remains within a tenth of a second.
Scene atwood(double inertia) {
  return parseScene(fmt::format(R"(
name: Atwood machine with a massive pulley
ground:
  joints:
    - {{name: sheave, position: [0, 0, 10]}}
    - {{name: heavy_guide, position: [0, 0, 0]}}
    - {{name: light_guide, position: [0, 0, -2]}}
bodies:
  - name: heavy
    mass: {}
    inertia: [10, 10, 10]
    position: [0, 0, 0]
  - name: light
    mass: {}
    inertia: [10, 10, 10]
    position: [0, 0, -2]
members:
  - name: rope
    type: rope
    element: reeved
    path: [heavy.origin, {{joint: ground.sheave, radius: {}, inertia: {}}}, light.origin]
    fidelity: massive
    elements_per_part: 2
    section: {{radius: 0.01}}
    material: {{density: 1.0e-3, youngs_modulus: 1.0e11, poisson_ratio: 0.3}}
    damping: 0.005
    length: {}
constraints:
  - {{name: heavy_guide, type: prismatic, joints: [ground.heavy_guide, heavy.origin], axis: z}}
  - {{name: light_guide, type: prismatic, joints: [ground.light_guide, light.origin], axis: z}}
solver: {{t_end: 2, rtol: 1.0e-10, atol: 1.0e-12}}
output: {{interval: 0.05}}
)",
                                kHeavy, kLight, kRadius, inertia, 22.0 / (1.0 + 3.0e-5)),
                    "<test>");
}

/// The light mass' upward speed at each sample, with the recorder's books.
struct LightSpeed final : SampleSink {
  LightSpeed(const Model& model, const Assembler& assembler) : model(model), recorder(assembler) {}
  void sample(double t, const double* y, const WorkTerms& work) override {
    recorder.sample(t, y, work);
    time.push_back(t);
    light.push_back(y[model.nq + model.nodes[1].v + 2]);
    heavy.push_back(y[model.nq + model.nodes[0].v + 2]);
  }
  const Model& model;
  ResultsRecorder recorder;
  std::vector<double> time, light, heavy;
};

}  // namespace

TEST_CASE("Atwood machine with a massive pulley: a = (m1 − m2) g / (m1 + m2 + J/r²)", "[reeving][massive][sheave][dynamics]") {
  const double inertia = GENERATE(0.0, 3.6);
  const Scene scene = atwood(inertia);
  const Model model = compileModel(scene);
  REQUIRE(model.nodes[0].name == "heavy");
  REQUIRE(model.nodes[1].name == "light");
  const Assembler assembler(model);
  const DynamicState initial = runInitialState(scene, model, assembler, true);
  LightSpeed sink(model, assembler);
  const SimulationOutcome run = simulate(assembler, initial, sink);
  REQUIRE(run.complete);
  // From 1 s to 2 s, long after the start's stretch has settled: the speed's rise over the time.
  const std::size_t from = 20, to = sink.time.size() - 1;
  REQUIRE(sink.time[from] == Approx(1.0));
  const double a = (sink.light[to] - sink.light[from]) / (sink.time[to] - sink.time[from]);
  const double a_half = (sink.light[to] - sink.light[30]) / (sink.time[to] - sink.time[30]);
  const SteadyRunning steady = steadyRunning(inertia);
  const double expected = steady.lightAcceleration();
  const double rigid = (kHeavy - kLight) * kGravity / (kHeavy + kLight + inertia / (kRadius * kRadius));
  const double speed_ratio = (1.0 + steady.strain_heavy) / (1.0 + steady.strain_light);
  INFO("J = " << inertia << " kg·m²: a " << a << " m/s² (from 1.5 s: " << a_half << "), expected " << expected
              << " (a rigid rope's " << rigid << "); heavy at " << sink.heavy[to] << " m/s, light at " << sink.light[to]
              << " m/s; balance drift " << sink.recorder.relativeBalanceDrift() << " of " << sink.recorder.energyScale()
              << " J; " << run.statistics.steps << " steps");
  CHECK(std::abs(a / expected - 1.0) < 1e-6);
  CHECK(std::abs(a_half / expected - 1.0) < 1e-6);
  CHECK(std::abs(expected / rigid - 1.0) < 2e-5);  // the strain's share: the rigid rope's formula holds to it
  CHECK(std::abs(-sink.heavy[to] / sink.light[to] / speed_ratio - 1.0) < 1e-9);  // the strains differ by 2e-6
  CHECK(sink.recorder.relativeBalanceDrift() < 1e-7);
}

TEST_CASE("A sheave's rotary inertia adds ½ J (σ̇/r)² to the massive rope's kinetic energy", "[reeving][massive][sheave][energy]") {
  const double inertia = 3.6;
  const Model with = compileModel(atwood(inertia)), without = compileModel(atwood(0.0));
  const auto rope = [](const Model& model) -> const MassiveReevedRopeElement& {
    return dynamic_cast<const MassiveReevedRopeElement&>(reevedRope(model, findReevedRope(model, "rope")));
  };
  REQUIRE(with.nodes.back().kind == NodeKind::Material);
  const int sheave = with.nodes.back().v;
  VecX v = VecX::Zero(with.nv);
  for (int k = 0; k < with.nv; ++k) v(k) = 0.1 * (k % 7) - 0.3;
  v(sheave) = 0.7;
  const ElementInput in{with.q0.data(), v.data(), nullptr, 0.5, with.gravity};
  const double difference = rope(with).kineticEnergy(in) - rope(without).kineticEnergy(in);
  const double expected = 0.5 * inertia * std::pow(v(sheave) / kRadius, 2);
  INFO("σ̇ " << v(sheave) << " m/s: kinetic energy " << difference << " J above the sheave without inertia, ½ J (σ̇/r)² " << expected << " J");
  CHECK(std::abs(difference / expected - 1.0) < 1e-12);
}
