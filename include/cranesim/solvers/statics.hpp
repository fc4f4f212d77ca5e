#pragma once
// Static equilibrium (DESIGN §5): Newton's method on the equilibrium KKT system
//   F(q, 0, t) + Gᵀ(q) λ = 0,   Φ(q, t) = 0
// (internal, gravity and applied forces F; the GGL rows of the assembler at dq = 0), with a
// backtracking line search on ‖residual‖ and load stepping: gravity and loads are ramped
// from 0 to 1, and a step that fails to converge is halved.

#include <string>

#include "cranesim/assembly/assembler.hpp"

namespace cranesim {

struct StaticOptions {
  int max_iterations = 50;       // per load step
  double tolerance = 1e-10;      // on the Newton step, relative to 1 + max|q|
  int initial_load_steps = 1;    // first try: the full load at once
  int max_load_halvings = 12;
};

struct StaticResult {
  bool converged = false;
  double t = 0.0;
  VecX q, lambda;
  int iterations = 0;     // Newton iterations in total
  int load_steps = 0;     // load increments taken
  double force_residual = 0.0;       // max |F + Gᵀλ| at the solution
  double constraint_residual = 0.0;  // max |Φ|
  std::string message;    // why it failed
};

/// Equilibrium near `q_start` at time t (drives and profiles evaluated at t).
StaticResult solveStatics(const Model& model, const VecX& q_start, double t, const StaticOptions& options = {});

}  // namespace cranesim
