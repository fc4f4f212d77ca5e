#pragma once
// A time integrator of the multibody DAE F(t, y, ẏ) = 0 (assembler.hpp) as `simulate` drives it:
// one step at a time, never past a stop time; the state anywhere within the last step, for the
// output samples; the work quadratures; and a restart from a consistent state at drive
// breakpoints and re-parameterisations (docs/numerics.md#breakpoints-and-velocity-jumps). Two
// implementations: IDAS' variable-order BDF (dynamics.cpp) and the generalized-α method
// (generalized_alpha.hpp), chosen by solver.integrator.

#include <memory>
#include <string>

#include "cranesim/solvers/initial_conditions.hpp"

namespace cranesim {

struct SolverStatistics {
  long steps = 0;
  long residual_evaluations = 0;
  long jacobian_evaluations = 0;
  long linear_setups = 0;
  long nonlinear_iterations = 0;
  long nonlinear_failures = 0;
  long error_test_failures = 0;
  long reparameterisations = 0;
  long restarts = 0;
  /// max |Φ| over the accepted steps: the drift of the formulation itself, free of the
  /// interpolation error that samples between steps carry.
  double max_step_constraint_residual = 0.0;
  double last_step_size = 0.0;
  int last_order = 0;
  double wall_time_s = 0.0;
};

/// A consistent state as the DAE's y = [q, dq, λ, μ = 0] and ẏ = [q̇, d(dq)/dt, 0].
void stateVectors(const Assembler& assembler, const DynamicState& s, double* y, double* yp);

struct StepOutcome {
  bool reached_stop = false;  // the step ended exactly at the stop time
  std::string failure;        // empty unless the integrator gave up: why
};

class TimeStepper {
 public:
  virtual ~TimeStepper() = default;
  /// Advances by one step, ending at or before t_stop.
  virtual StepOutcome step(double t_stop) = 0;
  virtual double time() const = 0;
  /// y = [q, dq, λ(, μ)] at time(); may be changed in place, followed by restart().
  virtual double* state() = 0;
  /// y and the work integrals (WorkTerms, in the order of WorkTerms::toArray) at t within the
  /// last step.
  virtual void interpolate(double t, double* y, double* work) = 0;
  /// The work integrals at time().
  virtual void work(double* work) = 0;
  /// Starts afresh from a consistent state (its accelerations and multipliers solved), keeping
  /// the work integrals and the statistics.
  virtual void restart(const DynamicState& s) = 0;
  /// Right after a restart: the Newton matrix's next factorisation pivots anew, as a new
  /// stepper's does, and not on the pivots of the run before (Simulation::save, restore), so
  /// that a saved state goes on alike in this process and in any other.
  virtual void forgetPivots() = 0;
  /// Replaces the work integrals (in the order of WorkTerms::toArray) right after a restart: a
  /// restored run's.
  virtual void setWork(const double* work) = 0;
  /// Limits the steps to come to h (0: back to solver.max_step, or none).
  virtual void setMaxStep(double h) = 0;
  virtual SolverStatistics statistics() = 0;
};

}  // namespace cranesim
