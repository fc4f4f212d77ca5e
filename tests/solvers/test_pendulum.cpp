// Simple pendulum: the period against the exact elliptic-integral period, at small and
// large amplitude; GGL and Baumgarte.

#include <catch2/catch.hpp>

#include <numbers>

#include "cranesim/math/rotation.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// Complete elliptic integral of the first kind K(m), m = k², by the arithmetic-geometric mean.
double ellipticK(double m) {
  double a = 1.0, b = std::sqrt(1.0 - m);
  for (int k = 0; k < 40; ++k) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return std::numbers::pi / (2.0 * a);
}

/// Mean period from the upward zero crossings of the tip's x coordinate (θ = 0, where the
/// angular acceleration vanishes, so linear interpolation between samples is third-order).
double measuredPeriod(const std::vector<double>& t, const std::vector<double>& tip) {
  std::vector<double> crossings;
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    const double x0 = tip[3 * k], x1 = tip[3 * (k + 1)];
    if (x0 < 0.0 && x1 >= 0.0) crossings.push_back(t[k] - x0 * (t[k + 1] - t[k]) / (x1 - x0));
  }
  REQUIRE(crossings.size() >= 3);
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

double periodError(double amplitude_deg, const std::string& formulation) {
  Scene scene = test::loadScene("pendulum.yaml");
  const double a = amplitude_deg * std::numbers::pi / 180.0;
  RigidBodySpec& rod = scene.bodies[0];
  rod.rotation = axisAngle(Vec3::UnitY(), a);
  rod.position = -rod.rotation * Vec3(0, 0, 0.5);
  scene.solver.formulation = formulation == "ggl" ? Formulation::GGL : Formulation::Baumgarte;
  scene.solver.baumgarte_alpha = 20.0;
  scene.solver.rtol = 1e-10;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-12);
  scene.solver.t_end = 8.5;
  scene.output.interval = 1e-3;
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  // Rod of length L about its end: I_p = m L²/3, restoring moment m g L/2 sin θ.
  const double omega0 = std::sqrt(9.81 * 0.5 / (1.0 / 3.0));
  const double exact = 4.0 / omega0 * ellipticK(std::pow(std::sin(a / 2.0), 2));
  const double measured = measuredPeriod(run.recorder.time(), run.jointPositions("rod.tip"));
  return std::abs(measured - exact) / exact;
}

}  // namespace

TEST_CASE("Pendulum period equals the elliptic-integral period (GGL)", "[dynamics][pendulum]") {
  for (double amplitude : {10.0, 90.0}) {
    const double error = periodError(amplitude, "ggl");
    INFO("amplitude " << amplitude << "°: relative period error " << error);
    CHECK(error < 1e-8);  // the requirement is 1e-6; measured ≈ 5e-10
  }
}

TEST_CASE("Pendulum period equals the elliptic-integral period (Baumgarte)", "[dynamics][pendulum]") {
  const double error = periodError(90.0, "baumgarte");
  INFO("relative period error " << error);
  CHECK(error < 1e-8);
}
