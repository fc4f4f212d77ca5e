// Load path planning as a QR optimal control problem (thesis 6.3): the RK4 map, the Ipopt
// solution against the discrete Riccati recursion, the Table 8-2 problem, the receding
// horizon (6-2) and the validation messages.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>

#include "cranesim/planning/qr_trajectory.hpp"

using namespace cranesim;

namespace {

using ControlMatrix = Eigen::Matrix<double, 4, 2>;
using Gain = Eigen::Matrix<double, 2, 4>;

/// Exact zero-order-hold discretisation of the planar double integrator.
void zeroOrderHold(double ts, Eigen::Matrix4d& A, ControlMatrix& B) {
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  A.setZero();
  A.topLeftCorner<2, 2>() = I;
  A.topRightCorner<2, 2>() = ts * I;
  A.bottomRightCorner<2, 2>() = I;
  B.topRows<2>() = 0.5 * ts * ts * I;
  B.bottomRows<2>() = ts * I;
}

/// Finite-horizon discrete Riccati recursion: gains K_0 … K_{N−1} and the cost-to-go P_0.
struct Riccati {
  std::vector<Gain> gains;
  Eigen::Matrix4d P0;
};

Riccati riccati(const QrProblem& problem, int steps) {
  Eigen::Matrix4d A;
  ControlMatrix B;
  zeroOrderHold(problem.sample_time, A, B);
  Riccati result;
  result.gains.resize(steps);
  Eigen::Matrix4d P = problem.P_end;
  for (int k = steps - 1; k >= 0; --k) {
    const Gain K = (problem.R + B.transpose() * P * B).ldlt().solve(B.transpose() * P * A);
    P = problem.Q + A.transpose() * P * (A - B * K);
    result.gains[k] = K;
  }
  result.P0 = P;
  return result;
}

/// Closed loop x_{k+1} = A x_k + B u_k with u_k = −gain(k) (x_k − x_e).
QrTrajectory closedLoop(const QrProblem& problem, const std::function<Gain(int)>& gain) {
  Eigen::Matrix4d A;
  ControlMatrix B;
  zeroOrderHold(problem.sample_time, A, B);
  QrTrajectory trajectory;
  trajectory.states = {problem.start};
  for (int k = 0; k < problem.steps; ++k) {
    const EndState& x = trajectory.states.back();
    trajectory.controls.push_back(-gain(k) * (x - problem.target));
    trajectory.states.push_back(A * x + B * trajectory.controls.back());
  }
  return trajectory;
}

/// max |a_k − b_k| over all entries of two sequences of vectors (states or controls).
template <class Vectors> double maxDifference(const Vectors& a, const Vectors& b) {
  REQUIRE(a.size() == b.size());
  double difference = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) difference = std::max(difference, (a[k] - b[k]).cwiseAbs().maxCoeff());
  return difference;
}

/// Non-trivial weights: symmetric positive definite with off-diagonal coupling.
QrProblem unconstrainedProblem(int steps) {
  QrProblem problem;
  problem.steps = steps;
  problem.sample_time = 0.1;
  problem.start << -10.0, 0.0, 0.3, -0.2;
  problem.target << -12.0, 3.0, 0.0, 0.0;
  problem.Q << 4.0, 1.0, 0.0, 0.5,  //
      1.0, 3.0, 0.2, 0.0,           //
      0.0, 0.2, 1.0, 0.1,           //
      0.5, 0.0, 0.1, 2.0;
  problem.R << 1.5, 0.3, 0.3, 0.8;
  problem.P_end << 20.0, 2.0, 1.0, 0.0,  //
      2.0, 15.0, 0.0, 1.0,               //
      1.0, 0.0, 5.0, 0.5,                //
      0.0, 1.0, 0.5, 4.0;
  return problem;
}

/// Table 8-2.
QrProblem thesisProblem() {
  QrProblem problem;
  problem.start << -10.0, 0.0, 0.0, 0.0;
  problem.target << -35.0, 10.0, 0.0, 0.0;
  problem.state_min << -50.0, 0.0, -1.0, -1.0;
  problem.state_max << -5.0, 30.0, 1.0, 1.0;
  problem.control_min << -0.2, -0.2;
  problem.control_max << 0.2, 0.2;
  problem.Q = 100.0 * Eigen::Matrix4d::Identity();
  problem.R = Eigen::Matrix2d::Identity();
  problem.P_end = 100.0 * Eigen::Matrix4d::Identity();
  problem.steps = 400;
  problem.sample_time = 0.1;
  return problem;
}

void checkWithinBounds(const QrProblem& problem, const QrTrajectory& trajectory) {
  const double slack = 1e-8;
  for (const EndState& x : trajectory.states) {
    CHECK((x.array() >= problem.state_min.array() - slack).all());
    CHECK((x.array() <= problem.state_max.array() + slack).all());
  }
  for (const EndControl& u : trajectory.controls) {
    CHECK((u.array() >= problem.control_min.array() - slack).all());
    CHECK((u.array() <= problem.control_max.array() + slack).all());
  }
}

}  // namespace

TEST_CASE("RK4 step of the double integrator is its exact zero-order-hold map", "[planning][qr]") {
  for (double ts : {0.1, 0.37, 2.0}) {
    Eigen::Matrix4d A, A_exact;
    ControlMatrix B, B_exact;
    rk4DoubleIntegrator(ts, A, B);
    zeroOrderHold(ts, A_exact, B_exact);
    INFO("ts = " << ts);
    CHECK((A - A_exact).cwiseAbs().maxCoeff() <= 1e-14);
    CHECK((B - B_exact).cwiseAbs().maxCoeff() <= 1e-14);
  }
}

TEST_CASE("Minimum rest-to-rest transfer time: triangle and trapezoid velocity profiles", "[planning][qr]") {
  CHECK(minimumTransferTime(25.0, 1.0, 0.2) == Approx(30.0));             // 5 s up, 20 s cruise, 5 s down
  CHECK(minimumTransferTime(-1.0, 1.0, 0.2) == Approx(2.0 * std::sqrt(5.0)));  // peak speed √0.2 < 1
  CHECK(minimumTransferTime(5.0, 1.0, 0.2) == Approx(10.0));              // both profiles meet at d = v²/a
  CHECK(minimumTransferTime(0.0, 0.0, 0.0) == 0.0);
  CHECK(minimumTransferTime(3.0, std::numeric_limits<double>::infinity(), 2.0) == Approx(2.0 * std::sqrt(1.5)));
  CHECK(minimumTransferTime(3.0, 1.5, std::numeric_limits<double>::infinity()) == Approx(2.0));
  CHECK(std::isinf(minimumTransferTime(3.0, 0.0, 1.0)));
}

TEST_CASE("Unconstrained QR problem (6-1) matches the finite-horizon discrete Riccati solution", "[planning][qr]") {
  const QrProblem problem = unconstrainedProblem(50);
  const QrTrajectory solution = solveQrTrajectory(problem);
  const Riccati lqr = riccati(problem, problem.steps);
  const QrTrajectory reference = closedLoop(problem, [&](int k) { return lqr.gains[k]; });

  REQUIRE(solution.t.size() == 51);
  CHECK(solution.t.back() == Approx(5.0));
  CHECK(maxDifference(solution.states, reference.states) <= 1e-6);
  CHECK(maxDifference(solution.controls, reference.controls) <= 1e-6);
  const EndState error = problem.start - problem.target;
  CHECK(solution.cost == Approx(error.dot(lqr.P0 * error)).epsilon(1e-8));
  CHECK(solution.iterations > 0);
}

TEST_CASE("Thesis Table 8-2 problem: bounded, saturating, reaches the target", "[planning][qr]") {
  const QrProblem problem = thesisProblem();
  const QrTrajectory solution = solveQrTrajectory(problem);
  std::printf("QR trajectory, Table 8-2 (N = 400): %.3f s, %d Ipopt iterations, J = %.6g\n", solution.solve_time_s,
              solution.iterations, solution.cost);

  REQUIRE(solution.states.size() == 401);
  REQUIRE(solution.controls.size() == 400);
  checkWithinBounds(problem, solution);
  const EndState& final_state = solution.states.back();
  CHECK((final_state.head<2>() - problem.target.head<2>()).norm() <= 0.05);
  CHECK(final_state.tail<2>().norm() <= 0.02);
  double max_vx = 0.0, max_acceleration = 0.0;
  for (const EndState& x : solution.states) max_vx = std::max(max_vx, std::abs(x[2]));
  for (const EndControl& u : solution.controls) max_acceleration = std::max(max_acceleration, u.cwiseAbs().maxCoeff());
  CHECK(max_vx >= 0.99);
  CHECK(max_acceleration >= 0.2 - 1e-6);
}

TEST_CASE("Receding horizon (6-2)", "[planning][qr]") {
  SECTION("Table 8-2 bounds, shorter move: stays within bounds and reaches the target") {
    // ts = 0.25 s and h = 40 look 10 s ahead like h = 100 at 0.1 s, with fewer windows; the
    // 25 s horizon leaves time to settle after the 20 s minimum transfer along x.
    QrProblem problem = thesisProblem();
    problem.target << -25.0, 5.0, 0.0, 0.0;
    problem.sample_time = 0.25;
    problem.steps = 100;
    problem.receding_horizon = 40;
    const QrTrajectory solution = solveQrTrajectory(problem);
    std::printf("QR trajectory, receding horizon h = 40, N = 100, ts = 0.25 s: %.3f s, %d Ipopt iterations, J = %.6g\n",
                solution.solve_time_s, solution.iterations, solution.cost);
    REQUIRE(solution.states.size() == 101);
    REQUIRE(solution.controls.size() == 100);
    checkWithinBounds(problem, solution);
    CHECK((solution.states.back().head<2>() - problem.target.head<2>()).norm() <= 0.1);
  }

  SECTION("Unconstrained: the closed loop of the first Riccati gain of an h-step horizon") {
    QrProblem problem = unconstrainedProblem(30);
    problem.receding_horizon = 8;
    const QrTrajectory solution = solveQrTrajectory(problem);
    const Gain first_gain = riccati(problem, problem.receding_horizon).gains.front();
    const QrTrajectory reference = closedLoop(problem, [&](int) { return first_gain; });
    CHECK(maxDifference(solution.states, reference.states) <= 1e-6);
    CHECK(maxDifference(solution.controls, reference.controls) <= 1e-6);
  }

  SECTION("h = N: the first control is that of the full problem") {
    QrProblem problem = unconstrainedProblem(20);
    const QrTrajectory full = solveQrTrajectory(problem);
    problem.receding_horizon = problem.steps;
    const QrTrajectory receding = solveQrTrajectory(problem);
    CHECK((receding.controls.front() - full.controls.front()).cwiseAbs().maxCoeff() <= 1e-6);
  }
}

TEST_CASE("QR problem validation names the offending entry", "[planning][qr]") {
  using Catch::Contains;
  QrProblem problem = thesisProblem();

  SECTION("each listed error condition") {
    CHECK_NOTHROW(validate(problem));

    problem.state_min[2] = 1.0;
    problem.state_max[2] = -1.0;
    CHECK_THROWS_WITH(validate(problem), Contains("state_min[2] = 1 > state_max[2] = -1"));

    problem = thesisProblem();
    problem.control_min[1] = 0.3;
    CHECK_THROWS_WITH(validate(problem), Contains("control_min[1] = 0.3 > control_max[1] = 0.2"));

    problem = thesisProblem();
    problem.start[0] = -60.0;
    CHECK_THROWS_WITH(validate(problem), Contains("start x = -60 lies outside the trajectory's state bounds [-50, -5] (state_min, state_max)"));

    problem = thesisProblem();
    problem.target[1] = 40.0;
    CHECK_THROWS_WITH(validate(problem), Contains("target z = 40 lies outside the trajectory's state bounds [0, 30]"));

    problem = unconstrainedProblem(10);
    problem.start[3] = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(validate(problem), Contains("start vz = inf is not finite"));

    problem = thesisProblem();
    problem.Q(0, 1) = 1.0;
    CHECK_THROWS_WITH(validate(problem), Contains("Q is not symmetric positive semi-definite"));
    problem = thesisProblem();
    problem.Q(3, 3) = -1e-3;
    CHECK_THROWS_WITH(validate(problem), Contains("Q is not symmetric positive semi-definite"));
    problem.Q = Eigen::Matrix4d::Zero();
    CHECK_NOTHROW(validate(problem));

    problem = thesisProblem();
    problem.P_end(2, 2) = -1.0;
    CHECK_THROWS_WITH(validate(problem), Contains("P_end is not symmetric positive semi-definite"));

    problem = thesisProblem();
    problem.R = Eigen::Vector2d(1.0, 0.0).asDiagonal();
    CHECK_THROWS_WITH(validate(problem), Contains("R is not positive definite"));

    problem = thesisProblem();
    problem.steps = 0;
    CHECK_THROWS_WITH(validate(problem), Contains("steps must be ≥ 1"));

    problem = thesisProblem();
    problem.sample_time = 0.0;
    CHECK_THROWS_WITH(validate(problem), Contains("sample_time must be > 0"));

    problem = thesisProblem();
    problem.receding_horizon = 500;
    CHECK_THROWS_WITH(validate(problem), Contains("receding horizon h = 500 exceeds steps"));
  }

  SECTION("infeasible horizon: 25 m at 1 m/s and 0.2 m/s² take 30 s, 100 steps give 10 s") {
    problem.steps = 100;
    CHECK_THROWS_WITH(validate(problem), Contains("infeasible horizon") && Contains("30 s") && Contains("10 s"));
    problem.steps = 300;
    CHECK_NOTHROW(validate(problem));
    problem.steps = 299;
    CHECK_THROWS_WITH(validate(problem), Contains("infeasible horizon: x"));
  }

  SECTION("infeasible horizon uses the speed bound in the direction of travel") {
    problem.state_max[2] = 0.5;  // x moves towards −x: only the lower bound −1 limits it
    CHECK_NOTHROW(validate(problem));
    problem.state_min[2] = -0.5;  // 25 m at 0.5 m/s: 52.5 s > 40 s
    CHECK_THROWS_WITH(validate(problem), Contains("infeasible horizon: x needs at least 52.5 s"));
  }

  SECTION("solveQrTrajectory reports Ipopt's status in words") {
    problem.max_iterations = 1;
    CHECK_THROWS_AS(solveQrTrajectory(problem), std::runtime_error);
    CHECK_THROWS_WITH(solveQrTrajectory(problem), Contains("Ipopt: maximum iterations exceeded"));
  }
}
