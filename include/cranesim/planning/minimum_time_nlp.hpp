#pragma once
// Minimum-time rest-to-rest transfer of a pendulum hanging from a driven suspension point
// (planar: a cart moving horizontally, a rope of constant length), as an NLP solved by Ipopt.
// Trapezoidal direct collocation with a free final time: the states and the drive's
// acceleration at N + 1 nodes and t_f are the decision variables, the collocation defects
// the constraints. Collocation rather than multiple shooting because the pendulum's
// dynamics appear in closed form, so the defects, their Jacobian and the Lagrangian's Hessian
// are exact and sparse (banded in the nodes) without integrating sensitivities.

#include <limits>
#include <vector>

namespace cranesim {

struct MinimumTimeProblem {
  double distance = 0.0;       // travel of the suspension point [m], from rest to rest
  double rope_length = 1.0;    // L [m]
  double gravity = 9.81;       // g [m/s²]
  double speed_limit = std::numeric_limits<double>::infinity();         // |v| ≤ v_max [m/s]
  double acceleration_limit = std::numeric_limits<double>::infinity();  // |a| ≤ a_max [m/s²]
  double jerk_limit = std::numeric_limits<double>::infinity();          // |Δa/Δt| ≤ j_max [m/s³]
  int intervals = 200;         // N collocation intervals
  double tolerance = 1e-9;     // Ipopt tol
  int max_iterations = 1000;   // Ipopt max_iter
  bool exact_hessian = true;   // false: Ipopt's limited-memory (L-BFGS) approximation
  int print_level = 0;         // Ipopt print_level
};

struct MinimumTimeTrajectory {
  double final_time = 0.0;     // t_f [s]
  std::vector<double> t, position, velocity, angle, angular_velocity, acceleration;  // N + 1 nodes
  int iterations = 0;          // Ipopt iterations
  double solve_time_s = 0.0;   // wall time (steady_clock) of the solve
};

/// The pendulum's angle from the vertical θ obeys L θ'' = −g sin θ − a cos θ, a the suspension
/// point's acceleration. Both ends at rest (v = θ = θ' = 0), the acceleration is free at the
/// ends unless a jerk limit is set (then it starts and ends at 0). Throws
/// std::invalid_argument for a non-positive size, length, gravity or limit, and
/// std::runtime_error naming Ipopt's status when the solve fails.
MinimumTimeTrajectory solveMinimumTime(const MinimumTimeProblem& problem);

}  // namespace cranesim
