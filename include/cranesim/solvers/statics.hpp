#pragma once
// Static equilibrium (docs/numerics.md#newton-on-the-kkt-system): Newton's method on the
// equilibrium KKT system
//   F(q, 0, t) + Gᵀ(q) λ = 0,   Φ(q, t) = 0
// (internal, gravity and applied forces F; the GGL rows of the assembler at dq = 0), with a
// damped Newton step (Armijo on ‖residual‖, or Deuflhard's natural monotonicity test) and
// adaptive load stepping: gravity and loads are ramped from 0 to 1; an increment whose
// Newton iteration stalls is halved, one that converges quickly lets the next one double.

#include <string>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/solvers/equilibrium_system.hpp"

namespace cranesim {

struct StaticOptions {
  int max_iterations = 50;       // per load step
  double tolerance = 1e-10;      // on the Newton step, relative to 1 + max|q|
  /// Converged also when every force residual is below this fraction of the largest constraint
  /// force (rounding floor of the forces; see dampedNewton).
  double force_tolerance = 1e-11;
  int initial_load_steps = 1;    // first try: the full load at once
  int max_load_halvings = 16;
  /// A load step is abandoned (and halved) when the line search cuts the Newton step below
  /// this fraction `stall_iterations` times in a row: far from the solution, Newton crawls
  /// (a rope that starts slack needs several short steps: 10 keeps the catenary test at 21).
  double stall_step = 1.0 / 64.0;
  int stall_iterations = 10;
  int fast_iterations = 6;       // a step converged within this many doubles the next increment
};

struct StaticResult {
  bool converged = false;
  double t = 0.0;
  VecX q, lambda;
  int iterations = 0;     // Newton iterations in total
  int load_steps = 0;     // load increments taken
  int path_steps = 0;     // steps along the path of the controls (solveEquilibrium)
  double path_reached = 0.0;  // how far along that path the solution got, 0…1
  double seconds = 0.0;       // wall time of the solve
  double force_residual = 0.0;       // max |F + Gᵀλ| at the solution
  double constraint_residual = 0.0;  // max |Φ|
  std::string message;    // why it failed
};

/// Damped Newton on `system` from x = [q, λ] at the system's time and load factor: x is the
/// solution on success. Returns the iterations used, or −(iterations + 1) on failure with the
/// reason in `why`. `factorisation`, when given, holds the last Jacobian factorised (that of
/// the last iterate but one; possibly shifted, see statics.cpp) when iterations were used.
int dampedNewton(EquilibriumSystem& system, VecX& x, const StaticOptions& options, std::string& why,
                 Eigen::SparseLU<Eigen::SparseMatrix<double>>* factorisation = nullptr);

/// Records x = [q, λ] in `result` as the equilibrium of `system` at its time (full load), with
/// its residuals, when Newton has declared it converged; accepted (`converged`) only when the
/// force residual max |F + Gᵀλ| is small beside the largest force present, max |F| (statics.cpp,
/// kResidualAcceptance): Newton's own test is on the length of its step, which a step along a
/// direction of large stiffness passes with a residual far from 0.
void acceptEquilibrium(EquilibriumSystem& system, const VecX& x, StaticResult& result);

/// Equilibrium near `q_start` at time t (drives and profiles evaluated at t).
StaticResult solveStatics(const Model& model, const VecX& q_start, double t, const StaticOptions& options = {});

}  // namespace cranesim
