#pragma once
// Time integration of the multibody DAE with SUNDIALS IDAS (variable-order BDF) or the
// generalized-α method (solver.integrator), both with the assembler's exact Jacobian and the
// KLU sparse direct solver.
//
// The run restarts the integrator (with freshly solved accelerations and multipliers) at
// every drive breakpoint, where a profile's second derivative jumps, and whenever a rotation
// vector is re-parameterised (docs/numerics.md#rotation-vector-re-parameterisation). The works of
// the energy balance (WorkTerms: drives, loads, winches, damping) are integrated as quadratures.

#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "cranesim/solvers/time_stepper.hpp"

namespace cranesim {

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

/// Runs the scene from `initial` to solver.t_end in one call (a Simulation advanced to t_end).
SimulationOutcome simulate(const Assembler& assembler, const DynamicState& initial, SampleSink& sink,
                           const SimulationControl& control = {});

/// The integrator that solver.integrator names, started from a consistent state.
std::unique_ptr<TimeStepper> makeTimeStepper(const Assembler& assembler, const DynamicState& initial);

}  // namespace cranesim
