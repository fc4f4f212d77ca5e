// Conservation laws: energy of the free triple jib pendulum, angular momentum of a
// torque-free spinning body through many rotation-vector re-parameterisations.

#include <catch2/catch.hpp>

#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// max |E(t) − E(0)| / max T(t): drift against the energy the motion exchanges.
double relativeEnergyDrift(const test::SimulationRun& run) {
  const auto& b = run.recorder.energyBalance();
  const auto& T = run.recorder.kineticEnergy();
  double drift = 0.0;
  for (double x : b) drift = std::max(drift, std::abs(x - b.front()));
  return drift / *std::max_element(T.begin(), T.end());
}

}  // namespace

TEST_CASE("Free triple jib pendulum conserves energy and keeps its constraints (GGL)", "[dynamics][conservation]") {
  Scene scene = test::loadScene("triple_jib_pendulum.yaml");
  REQUIRE(scene.solver.rtol == 1e-8);
  REQUIRE(scene.solver.t_end == 20.0);
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const double drift = relativeEnergyDrift(run);
  INFO("relative energy drift " << drift << ", max |Φ| at steps " << run.outcome.statistics.max_step_constraint_residual
                                << ", at samples " << run.maxSampleResidual());
  CHECK(drift < 1e-5);
  // Φ = 0 is solved to Newton accuracy, i.e. a fraction of rtol·|q| (|q| ≈ 10 m here).
  CHECK(run.outcome.statistics.max_step_constraint_residual < 1e-8);
  CHECK(run.maxSampleResidual() < 1e-8);
}

TEST_CASE("At rtol 1e-9 the GGL constraint residual stays below 1e-9", "[dynamics][conservation]") {
  Scene scene = test::loadScene("triple_jib_pendulum.yaml");
  scene.solver.rtol = 1e-9;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-11);
  scene.solver.t_end = 10.0;
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  INFO("max |Φ| at steps " << run.outcome.statistics.max_step_constraint_residual);
  CHECK(run.outcome.statistics.max_step_constraint_residual < 1e-9);
}

TEST_CASE("Baumgarte drift on the triple jib pendulum is reported", "[dynamics][conservation]") {
  Scene scene = test::loadScene("triple_jib_pendulum.yaml");
  scene.solver.formulation = Formulation::Baumgarte;
  scene.solver.baumgarte_alpha = 10.0;
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const double drift = relativeEnergyDrift(run);
  WARN("Baumgarte (α = 10, β = 1), rtol 1e-8: relative energy drift " << drift << ", max |Φ| at steps "
                                                                       << run.outcome.statistics.max_step_constraint_residual);
  // Baumgarte only damps the drift: Φ stays small but well above the GGL level.
  CHECK(run.outcome.statistics.max_step_constraint_residual < 1e-5);
  CHECK(drift < 1e-4);
}

TEST_CASE("A torque-free body at 120 rpm conserves angular momentum through re-parameterisations",
          "[dynamics][conservation][rotation]") {
  const test::SimulationRun run(test::loadScene("spinning_body.yaml"));
  REQUIRE(run.outcome.complete);
  const Mat3 inertia = Vec3(1.0, 2.0, 3.0).asDiagonal();
  const auto& R = run.recorder.bodyRotations(0);
  const auto& w = run.recorder.bodyAngularVelocities(0);
  const auto momentum = [&](std::size_t k) {
    const Mat3 Rk = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(&R[9 * k]);
    return Vec3(Rk * inertia * Vec3(&w[3 * k]));
  };
  const Vec3 L0 = momentum(0);
  double worst = 0.0;
  for (std::size_t k = 0; k < run.recorder.samples(); ++k) worst = std::max(worst, (momentum(k) - L0).norm());
  INFO("relative angular momentum error " << worst / L0.norm() << " after "
                                          << run.outcome.statistics.reparameterisations << " re-parameterisations");
  CHECK(worst / L0.norm() < 1e-6);
  CHECK(run.outcome.statistics.reparameterisations > 50);
  CHECK(relativeEnergyDrift(run) < 1e-6);
}
