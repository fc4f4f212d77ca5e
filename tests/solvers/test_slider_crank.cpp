// Slider-crank under a prescribed crank angle: slider position against the closed form.

#include <catch2/catch.hpp>

#include <numbers>

#include "scene_fixtures.hpp"

using namespace cranesim;

TEST_CASE("Slider-crank follows the closed-form kinematics", "[dynamics][drives]") {
  for (const Formulation f : {Formulation::GGL, Formulation::Baumgarte}) {
    Scene scene = test::loadScene("slider_crank.yaml");
    scene.solver.formulation = f;
    scene.solver.baumgarte_alpha = 50.0;
    const test::SimulationRun run(scene);
    REQUIRE(run.outcome.complete);
    const double r = 0.2, L = 0.6;
    const auto& t = run.recorder.time();
    const auto& slider = run.jointPositions("slider.origin");
    double worst = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double theta = 2.0 * std::numbers::pi * t[k];
      const double exact = r * std::cos(theta) + std::sqrt(L * L - r * r * std::sin(theta) * std::sin(theta));
      worst = std::max(worst, std::abs(slider[3 * k] - exact));
    }
    INFO((f == Formulation::GGL ? "GGL" : "Baumgarte") << ": max slider position error " << worst << " m");
    CHECK(worst < 1e-7);
  }
}
