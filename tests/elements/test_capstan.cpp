// Capstan friction on a reeved rope (elements/reeved_rope.hpp): a rope sliding over a sheave
// that does not turn passes the tension ratio e^(μθ) of Euler–Eytelwein by the direction it
// runs. A hook guided vertically under a fixed capstan, hoisted and lowered at a steady speed:
// the ratio across the capstan, the line pull W e^(±μθ), the capstan's dissipation
// (T_tight − T_slack)·w against the energy books; the wrap angle read or taken from the drawing.

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "cranesim/model/reeved_rope_element.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "guided_hook.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kWeight = test::kHookWeight, kFriction = 0.1;

/// The guided hook (guided_hook.hpp) 10 m under a capstan at the head (friction 0.1), so the
/// drawn rope turns 90° over it; `wrap` adds `wrap_deg: <wrap>`. The winch reels `distance` m
/// (trapezoid from 1.5 s over 8 s, 1 s ramps: 0.4 m/s), Kelvin–Voigt damping 0.1 s; 9.5 s.
Scene capstanHook(const std::string& wrap, double distance) {
  return test::guidedHook(
      fmt::format("    path: [ground.winch, {{joint: ground.head, radius: 0.3, friction: {}{}}}, hook.sheaves]\n"
                  "    length: {{type: trapezoid, from: 17.99, distance: {}, t_start: 1.5, duration: 8, t_accel: 1, t_decel: 1}}",
                  kFriction, wrap.empty() ? "" : ", wrap_deg: " + wrap, distance),
      0.1, 9.5);
}

/// Records, in the steady run from `from` to 8.4 s (the winch slows from 8.5 s), the worst
/// relative deviation of T₀/T₁ from `ratio` and of the line pull T₀ from ratio·W, and the
/// dissipated energy and hook height at its ends; forwards every sample to the results recorder (energy books).
struct SteadyCapstan final : SampleSink {
  SteadyCapstan(const Model& model, const Assembler& assembler, double from, double ratio)
      : model(model), rope(test::reevedRopeNamed(model)), recorder(assembler), from(from), ratio(ratio) {}
  void sample(double t, const double* y, const WorkTerms& work) override {
    recorder.sample(t, y, work);
    if (t < from || t > 8.4) return;
    double T[2];
    rope.partTensions(ElementInput{y, y + model.nq, nullptr, t, model.gravity}, T);
    ratio_error = std::max(ratio_error, std::abs(T[0] / T[1] / ratio - 1.0));
    pull_error = std::max(pull_error, std::abs(T[0] / (ratio * kWeight) - 1.0));
    const double height = y[model.nodes[0].q + 2], dissipated = recorder.dissipated().back();
    if (samples++ == 0) first = {t, height, dissipated};
    last = {t, height, dissipated};
  }
  struct Moment {
    double t, height, dissipated;
  };
  const Model& model;
  const ReevedRopeElement& rope;
  ResultsRecorder recorder;
  double from, ratio, ratio_error = 0.0, pull_error = 0.0;
  Moment first{}, last{};
  int samples = 0;
};

}  // namespace

TEST_CASE("A capstan's wrap angle: given in degrees, or the drawn path's turn at its centre", "[reeving][capstan]") {
  const Model drawn = compileModel(capstanHook("", 0.0));
  CHECK(std::abs(test::reevedRopeNamed(drawn).kernel().friction_exponent[0] - kFriction * std::numbers::pi / 2.0) < 1e-15);
  const Model drum = compileModel(capstanHook("450", 0.0));  // a turn and a quarter on a drum
  CHECK(std::abs(test::reevedRopeNamed(drum).kernel().friction_exponent[0] - kFriction * 2.5 * std::numbers::pi) < 1e-15);
}

TEST_CASE("Hoisting and lowering over a slipping capstan: T_tight/T_slack = e^(μθ), its loss in the books",
          "[reeving][capstan][dynamics]") {
  const std::string wrap = GENERATE(as<std::string>{}, "", "450");
  const bool hoisting = GENERATE(true, false);
  const double theta = (wrap.empty() ? 90.0 : 450.0) * std::numbers::pi / 180.0;
  // Hoisting the winch's part is the tight one, lowering the hook's: T₀/T₁ = e^(±μθ), T₁ = W.
  const double ratio = std::exp((hoisting ? 1.0 : -1.0) * kFriction * theta);
  const Scene scene = capstanHook(wrap, hoisting ? -2.8 : 2.8);
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const DynamicState initial = runInitialState(scene, model, assembler, true);
  // The hook's vibration on 18 m of rope (2 Hz, damping ratio 0.65) has died out to 1e-9 by 6 s.
  SteadyCapstan sink(model, assembler, 6.0, ratio);
  const SimulationOutcome run = simulate(assembler, initial, sink);
  REQUIRE(run.complete);
  REQUIRE(sink.samples > 20);
  // The capstan's loss (T_tight − T_slack)·|w|, w the hook's speed (the part beyond it lengthens).
  const double travel = std::abs(sink.last.height - sink.first.height);
  const double loss = std::abs(ratio - 1.0) * kWeight * travel;
  const double booked = sink.last.dissipated - sink.first.dissipated;
  INFO((hoisting ? "hoisting" : "lowering") << ", wrap " << theta << " rad: T₀/T₁ off e^(±μθ) by " << sink.ratio_error
                                            << ", line pull off W e^(±μθ) by " << sink.pull_error << "; capstan's loss "
                                            << loss << " J, booked " << booked << " J; balance drift "
                                            << sink.recorder.relativeBalanceDrift());
  CHECK(sink.ratio_error < 1e-9);
  CHECK(sink.pull_error < 1e-6);
  CHECK(std::abs(booked / loss - 1.0) < 1e-6);
  CHECK(sink.recorder.relativeBalanceDrift() < 1e-6);
  CHECK(travel > 0.4 * 2.3);
}
