#pragma once
// Time integration of the multibody DAE with SUNDIALS IDAS (variable-order BDF) and the KLU
// sparse direct solver, with the assembler's exact Jacobian.
//
// The run restarts the integrator (with freshly solved accelerations and multipliers) at
// every drive breakpoint, where a profile's second derivative jumps, and whenever a rotation
// vector is re-parameterised (DESIGN §4). The works of the energy balance (WorkTerms: drives,
// loads, winches, damping) are integrated as IDAS quadratures.

#include <atomic>
#include <functional>
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

/// Receives the solution at every output time. `y` is the DAE state [q, dq, λ(, μ)], `work`
/// the works done since the run's start.
struct SampleSink {
  virtual ~SampleSink() = default;
  virtual void sample(double t, const double* y, const WorkTerms& work) = 0;
};

struct SimulationOutcome {
  bool complete = false;
  double t_reached = 0.0;
  std::string message;  // empty on success: when and why the run stopped otherwise
  SolverStatistics statistics;
};

struct SimulationControl {
  /// Called after each step with the current time; for progress display.
  std::function<void(double)> on_step;
  /// Set from another thread or a signal handler to stop the run (the results stay readable).
  const std::atomic<bool>* stop_requested = nullptr;
};

SimulationOutcome simulate(const Assembler& assembler, const DynamicState& initial, SampleSink& sink,
                           const SimulationControl& control = {});

}  // namespace cranesim
