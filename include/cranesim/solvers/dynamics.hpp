#pragma once
// Time integration of the multibody DAE with SUNDIALS IDAS (variable-order BDF) or the
// generalized-α method (solver.integrator), both with the assembler's exact Jacobian and the
// KLU sparse direct solver.
//
// The run restarts the integrator (with freshly solved accelerations and multipliers) at
// every drive breakpoint, where a profile's second derivative jumps, and whenever a rotation
// vector is re-parameterised (DESIGN §4). Work of drives and loads is integrated as
// quadratures for the energy balance.

#include <atomic>
#include <functional>
#include <string>

#include "cranesim/solvers/time_stepper.hpp"

namespace cranesim {

/// Receives the solution at every output time. `y` is the DAE state [q, dq, λ(, μ)].
struct SampleSink {
  virtual ~SampleSink() = default;
  virtual void sample(double t, const double* y, double drive_work, double load_work) = 0;
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
