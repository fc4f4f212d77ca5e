#pragma once
// A run of the dynamics that its caller advances in steps of its own choosing: the loop that
// `simulate` (dynamics.hpp) runs in one call, and the object a controller, an operator's
// commands or a learning agent drive a crane through (docs/architecture.md#dynamics).
//
// It owns the time stepper (IDAS' BDF or generalized-α) and the run's bookkeeping: the stop
// times at drive breakpoints, restarts with freshly solved accelerations (after a drive's
// velocity jump, with the impulse's work booked to the drives) and after rotation vectors are
// re-parameterised, output samples at the scene's interval passed to a SampleSink, a step size
// that collapsed, a stop request.
//
// Advancing is chunk-invariant: advanceTo(t) steps the integrator exactly as one call up to
// solver.t_end would (its stop times are the breakpoints and t_end only; it may step past t, as
// a whole run does) and passes on every sample up to the end of its last step, so a run advanced
// to t₁ < t₂ < … < t_end gives the bits of a run advanced to t_end at once.

#include <chrono>
#include <memory>
#include <vector>

#include "cranesim/solvers/dynamics.hpp"

namespace cranesim {

class Simulation {
 public:
  /// Starts from a consistent state (consistentInitialState, or an equilibrium); passes the
  /// sample at initial.t to `sink` at once. The assembler and the sink must outlive it.
  Simulation(const Assembler& assembler, const DynamicState& initial, SampleSink& sink);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Integrates until the integrator's time reaches t (clamped to solver.t_end); returns whether
  /// the run goes on. False when it has stopped: at t_end (outcome().complete), or for the reason
  /// in outcome().message (a solver failure, a collapsed step, `control.stop_requested`); a
  /// stopped run does not advance again.
  bool advanceTo(double t, const SimulationControl& control = {});

  /// The integrator's time: the end of its last step, at or beyond the last advanceTo's t.
  double time() const { return t_; }

  /// The run so far: where it got, whether it reached t_end or why it stopped, the solver's
  /// counters and the wall time spent in advanceTo.
  SimulationOutcome outcome() const;

 private:
  /// One integrator step and what follows it: samples, stall check, restart. False: stopped.
  bool step(const SimulationControl& control);
  bool stop(std::string message);

  const Assembler& assembler_;
  SampleSink& sink_;
  std::unique_ptr<TimeStepper> stepper_;
  std::vector<double> breakpoints_;
  std::size_t next_break_ = 0;
  SolverStatistics counts_;     // what the stepper does not count itself
  double drive_impulses_ = 0.0;  // the drives' work in velocity jumps (jumpVelocities), J
  double t_ = 0.0;
  double t_start_ = 0.0;
  long next_sample_ = 1;
  bool sampled_end_ = false;
  long stalled_steps_ = 0;
  bool stopped_ = false;
  bool complete_ = false;
  std::string message_;
  std::chrono::steady_clock::duration wall_{};
  std::vector<double> sample_;
};

}  // namespace cranesim
