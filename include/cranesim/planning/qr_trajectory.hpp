#pragma once
// Load path planning as a discrete QR optimal control problem of a planar double integrator,
// solved with Ipopt: one NLP over the whole horizon (6-1) or receding horizon (6-2); Table 8-2.

#include <Eigen/Dense>
#include <limits>
#include <vector>

namespace cranesim {

using EndState = Eigen::Vector4d;    // (x, z, vx, vz)
using EndControl = Eigen::Vector2d;  // (ax, az)

struct QrProblem {
  EndState start = EndState::Zero(), target = EndState::Zero();
  EndState state_min = EndState::Constant(-std::numeric_limits<double>::infinity());
  EndState state_max = EndState::Constant(std::numeric_limits<double>::infinity());
  EndControl control_min = EndControl::Constant(-std::numeric_limits<double>::infinity());
  EndControl control_max = EndControl::Constant(std::numeric_limits<double>::infinity());
  Eigen::Matrix4d Q = Eigen::Matrix4d::Identity(), P_end = Eigen::Matrix4d::Identity();
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
  int steps = 400;             // N
  double sample_time = 0.1;    // ts
  int receding_horizon = 0;    // 0: one NLP over all N steps; h > 0: receding horizon of h steps (6-2)
  double tolerance = 1e-10;    // Ipopt tol
  int max_iterations = 3000;   // per Ipopt solve
  int print_level = 0;         // Ipopt print_level
};

struct QrTrajectory {
  std::vector<double> t;               // N + 1 times k·ts
  std::vector<EndState> states;        // N + 1
  std::vector<EndControl> controls;    // N
  double cost = 0.0;                   // J of (6-1) evaluated on the returned trajectory
  int iterations = 0;                  // Ipopt iterations (summed over windows for receding horizon)
  double solve_time_s = 0.0;           // wall time (steady_clock) of the solve(s)
};

/// The exact discrete map of one RK4 step for the double integrator: x+ = A x + B u.
void rk4DoubleIntegrator(double ts, Eigen::Matrix4d& A, Eigen::Matrix<double, 4, 2>& B);

/// Shortest time for one axis of a double integrator with |v| ≤ v_max, |a| ≤ a_max to move by
/// `distance` from rest to rest (trapezoid or triangle velocity profile). Infinite limits are
/// allowed; with a limit ≤ 0 any nonzero distance takes infinitely long.
double minimumTransferTime(double distance, double v_max, double a_max);

/// Throws std::invalid_argument naming the offending entry: inconsistent bounds, start or
/// target outside the state bounds, weights that are not (semi-)definite, non-positive sizes,
/// a receding horizon longer than the problem, and an "infeasible horizon" when an axis that
/// starts and ends at rest cannot cover its distance within steps·sample_time (speed bound in
/// the direction of travel, accelerating and braking bounds; x with vx/ax, z with vz/az).
void validate(const QrProblem& problem);

/// Solves (6-1), or (6-2) when receding_horizon > 0, with Ipopt after validate(). Throws
/// std::runtime_error with Ipopt's status in words ("Ipopt: infeasible problem detected")
/// when a solve neither succeeds nor reaches the acceptable level.
QrTrajectory solveQrTrajectory(const QrProblem& problem);

}  // namespace cranesim
