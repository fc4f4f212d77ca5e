// The minimum-time collocation NLP against a case whose optimum is known in closed form: a
// pendulum on a cart with |v| ≤ v_max, |a| ≤ a_max where v_max / a_max is the pendulum's period
// under constant acceleration. No motion can beat the rigid cart's bang-coast-bang time
// D/v_max + v_max/a_max, and that very profile leaves the pendulum at rest: during each constant
// acceleration it swings one full period about the tilted equilibrium atan(a/g) with the
// effective gravity √(g² + a²) and comes back to θ = 0, θ' = 0.

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "cranesim/planning/minimum_time_nlp.hpp"

using namespace cranesim;

namespace {

constexpr double kG = 9.81, kL = 10.0, kAccel = 0.5, kDistance = 40.0;

/// The exact (large-amplitude) period of a pendulum released at rest `amplitude` away from its
/// equilibrium under gravity g: 4 √(L/g) K(sin(amplitude/2)).
double pendulumPeriod(double length, double g, double amplitude) {
  return 4.0 * std::sqrt(length / g) * std::comp_ellint_1(std::sin(0.5 * amplitude));
}

double periodUnderAcceleration(double a) { return pendulumPeriod(kL, std::hypot(kG, a), std::atan(a / kG)); }

MinimumTimeProblem cartPendulum() {
  MinimumTimeProblem problem;
  problem.distance = kDistance;
  problem.rope_length = kL;
  problem.gravity = kG;
  problem.acceleration_limit = kAccel;
  problem.speed_limit = kAccel * periodUnderAcceleration(kAccel);
  problem.intervals = 200;
  return problem;
}

/// The trajectory's acceleration at time t, linear between nodes (as the trapezoidal rule assumes).
double accelerationAt(const MinimumTimeTrajectory& trajectory, double t) {
  const double h = trajectory.t[1];
  const std::size_t k = std::min(static_cast<std::size_t>(t / h), trajectory.t.size() - 2);
  const double s = t / h - static_cast<double>(k);
  return (1.0 - s) * trajectory.acceleration[k] + s * trajectory.acceleration[k + 1];
}

/// The pendulum's (θ, θ') at t_f under the planned acceleration, by RK4 with fine steps.
std::array<double, 2> swingAtArrival(const MinimumTimeTrajectory& trajectory) {
  const auto rate = [&](double t, double theta, double omega) {
    return std::array<double, 2>{omega, -(kG * std::sin(theta) + accelerationAt(trajectory, t) * std::cos(theta)) / kL};
  };
  const int steps = 20000;
  const double dt = trajectory.final_time / steps;
  double theta = 0.0, omega = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double t = i * dt;
    const auto k1 = rate(t, theta, omega);
    const auto k2 = rate(t + dt / 2, theta + dt / 2 * k1[0], omega + dt / 2 * k1[1]);
    const auto k3 = rate(t + dt / 2, theta + dt / 2 * k2[0], omega + dt / 2 * k2[1]);
    const auto k4 = rate(t + dt, theta + dt * k3[0], omega + dt * k3[1]);
    theta += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]);
    omega += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
  }
  return {theta, omega};
}

}  // namespace

TEST_CASE("minimum-time NLP: cart pendulum reaches the bang-coast-bang optimum", "[minimum_time]") {
  const MinimumTimeProblem problem = cartPendulum();
  const double period = periodUnderAcceleration(kAccel);
  const double known_minimum = kDistance / problem.speed_limit + period;  // 18.96 s
  const MinimumTimeTrajectory plan = solveMinimumTime(problem);

  CHECK(plan.final_time == Approx(known_minimum).epsilon(1e-3));

  const int N = problem.intervals;
  SECTION("rest to rest at both ends") {
    for (int k : {0, N}) {
      CHECK(std::abs(plan.velocity[k]) <= 1e-6);
      CHECK(std::abs(plan.angle[k]) <= 1e-6);
      CHECK(std::abs(plan.angular_velocity[k]) <= 1e-6);
    }
    CHECK(std::abs(plan.position[0]) <= 1e-6);
    CHECK(std::abs(plan.position[N] - kDistance) <= 1e-6);
  }
  SECTION("bang-bang: full acceleration, coasting at v_max, full braking") {
    const auto nodeAt = [&](double t) { return static_cast<int>(std::lround(t / plan.final_time * N)); };
    CHECK(plan.acceleration[nodeAt(period / 2)] == Approx(kAccel).epsilon(0.01));
    CHECK(plan.velocity[nodeAt(plan.final_time / 2)] == Approx(problem.speed_limit).epsilon(0.01));
    CHECK(plan.acceleration[nodeAt(plan.final_time - period / 2)] == Approx(-kAccel).epsilon(0.01));
    for (int k = 0; k <= N; ++k) {
      CHECK(std::abs(plan.velocity[k]) <= problem.speed_limit * (1 + 1e-8));
      CHECK(std::abs(plan.acceleration[k]) <= kAccel * (1 + 1e-8));
    }
  }
  SECTION("the planned acceleration, integrated finely, leaves the pendulum nearly at rest") {
    const double static_angle = std::atan(kAccel / kG);  // the sway the acceleration excites
    const auto [theta, omega] = swingAtArrival(plan);
    const double amplitude = std::hypot(theta, omega / std::sqrt(kG / kL));
    CHECK(amplitude <= 0.005 * static_angle);  // measured 0.11 %
  }
}

TEST_CASE("minimum-time NLP: the L-BFGS Hessian reaches the same optimum as the exact one", "[minimum_time]") {
  MinimumTimeProblem problem = cartPendulum();
  problem.intervals = 100;
  const double exact = solveMinimumTime(problem).final_time;
  problem.exact_hessian = false;
  CHECK(solveMinimumTime(problem).final_time == Approx(exact).epsilon(1e-6));
}

TEST_CASE("minimum-time NLP: a jerk limit holds and lengthens the move", "[minimum_time]") {
  MinimumTimeProblem problem = cartPendulum();
  problem.intervals = 100;
  const double free_jerk = solveMinimumTime(problem).final_time;
  problem.jerk_limit = 0.5;
  const MinimumTimeTrajectory plan = solveMinimumTime(problem);
  CHECK(plan.final_time > free_jerk);
  const double h = plan.t[1];
  for (int k = 0; k < problem.intervals; ++k)
    CHECK(std::abs(plan.acceleration[k + 1] - plan.acceleration[k]) <= problem.jerk_limit * h * (1 + 1e-6));
  CHECK(plan.acceleration.front() == 0.0);
  CHECK(plan.acceleration.back() == 0.0);
}

TEST_CASE("minimum-time NLP: bad sizes and limits are refused", "[minimum_time]") {
  MinimumTimeProblem problem = cartPendulum();
  problem.rope_length = 0.0;
  CHECK_THROWS_WITH(solveMinimumTime(problem), Catch::Contains("rope_length must be > 0"));
  problem = cartPendulum();
  problem.acceleration_limit = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(solveMinimumTime(problem), Catch::Contains("acceleration_limit must be finite"));
  problem = cartPendulum();
  problem.intervals = 1;
  CHECK_THROWS_WITH(solveMinimumTime(problem), Catch::Contains("intervals must be ≥ 2"));
}
