// A Simulation advanced in chunks integrates exactly as one advanced to t_end at once: the same
// samples bit for bit and the same solver counters, across drive breakpoints (a velocity jump,
// restarts) and rotation-vector re-parameterisations. `crane-sim run` advances once; a
// step-by-step caller advances by its sampling time and must get the same run.

#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include "cranesim/solvers/scene_equilibrium.hpp"
#include "cranesim/solvers/simulation.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

struct Samples final : SampleSink {
  std::vector<double> t;
  std::vector<std::vector<double>> y;
  std::vector<std::array<double, WorkTerms::kCount>> work;
  std::size_t size = 0;
  void sample(double ts, const double* state, const WorkTerms& w) override {
    t.push_back(ts);
    y.emplace_back(state, state + size);
    w.toArray(work.emplace_back().data());
  }
};

struct Run {
  Samples samples;
  SimulationOutcome outcome;
  std::vector<double> reached;  // time() after each advanceTo
};

/// The scene from its consistent initial state, advanced to each of `stops` in turn.
Run advanced(const Scene& scene, const std::vector<double>& stops) {
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const DynamicState initial = runInitialState(scene, model, assembler, true);  // as crane-sim run starts
  Run run;
  run.samples.size = static_cast<std::size_t>(assembler.size());
  Simulation simulation(assembler, initial, run.samples);
  for (const double t : stops) {
    simulation.advanceTo(t);
    run.reached.push_back(simulation.time());
  }
  run.outcome = simulation.outcome();
  return run;
}

std::vector<double> evenly(double t_end, double dt) {
  std::vector<double> stops;
  for (int k = 1; k * dt < t_end + 1e-12; ++k) stops.push_back(k * dt);
  return stops;
}

void requireSameRun(const Run& chunked, const Run& whole) {
  REQUIRE(chunked.outcome.complete);
  REQUIRE(whole.outcome.complete);
  REQUIRE(chunked.samples.t == whole.samples.t);
  REQUIRE(chunked.samples.y == whole.samples.y);
  REQUIRE(chunked.samples.work == whole.samples.work);
  const SolverStatistics &a = chunked.outcome.statistics, &b = whole.outcome.statistics;
  CHECK(a.steps == b.steps);
  CHECK(a.residual_evaluations == b.residual_evaluations);
  CHECK(a.jacobian_evaluations == b.jacobian_evaluations);
  CHECK(a.error_test_failures == b.error_test_failures);
  CHECK(a.nonlinear_failures == b.nonlinear_failures);
  CHECK(a.restarts == b.restarts);
  CHECK(a.reparameterisations == b.reparameterisations);
  CHECK(a.max_step_constraint_residual == b.max_step_constraint_residual);
  CHECK(chunked.outcome.t_reached == whole.outcome.t_reached);
}

}  // namespace

TEST_CASE("A simulation advanced in chunks is the run advanced at once, across a velocity jump and "
          "re-parameterisations", "[simulation]") {
  // The rod turned by a ramp that starts at 0.5 s (its velocity jumps from 0 to 5 rad/s there) and
  // spins it on: its rotation vector is re-parameterised about every 1.3 s.
  Scene scene = test::drivenRod("{type: ramp, value: 0, rate: 5, t_start: 0.5}");
  scene.solver.t_end = 4.0;
  const Run whole = advanced(scene, {4.0});
  REQUIRE(whole.outcome.statistics.reparameterisations >= 2);
  REQUIRE(whole.outcome.statistics.restarts >= 3);
  REQUIRE(whole.samples.t.size() == 401);

  SECTION("at every output time") { requireSameRun(advanced(scene, evenly(4.0, 0.01)), whole); }
  SECTION("at a controller's sampling time that is no multiple of the output interval") {
    const Run chunked = advanced(scene, evenly(4.0, 0.037));
    requireSameRun(chunked, whole);
    // Each advance gets at least as far as asked.
    for (std::size_t k = 0; k < chunked.reached.size(); ++k) CHECK(chunked.reached[k] >= std::min(0.037 * (k + 1), 4.0));
  }
  SECTION("past t_end and again after it: the run ends there") {
    const Run chunked = advanced(scene, {1.0, 10.0, 20.0});
    requireSameRun(chunked, whole);
    CHECK(chunked.reached.back() == 4.0);
  }
}

TEST_CASE("The thesis crane's combined motion advanced every 20 ms is the run advanced at once",
          "[simulation][crane]") {
  Scene scene = test::loadScene("crane_combined.yaml");
  scene.solver.t_end = 12.0;  // lifting from the start, slewing from 10 s: breakpoints at 0, 5, 10 s
  const Run whole = advanced(scene, {12.0});
  REQUIRE(whole.outcome.statistics.restarts >= 2);
  requireSameRun(advanced(scene, evenly(12.0, 0.02)), whole);
}
