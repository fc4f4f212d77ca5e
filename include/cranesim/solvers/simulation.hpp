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
// A model without inputs advances chunk-invariantly: advanceTo(t) steps the integrator exactly
// as one call up to solver.t_end would (its stop times are the breakpoints and t_end only; it may
// step past t, as a whole run does) and passes on every sample up to the end of its last step, so
// a run advanced to t₁ < t₂ < … < t_end gives the bits of a run advanced to t_end at once.
// A model with inputs (Model::inputs) stops exactly at each t instead, where its caller may set
// new commands; the integrator goes on from there without a restart (its history stays valid:
// the inputs keep the drives' values and speeds continuous).

#include <array>
#include <chrono>
#include <memory>
#include <vector>

#include "cranesim/solvers/dynamics.hpp"

namespace cranesim {

/// How a run with inputs divides each advance into equal steps (Simulation::limitSteps), no
/// longer than solver.max_step: as many as the integrator's own step fits into one when it
/// needed more (not counting the first advances after a restart), and after `wait` advances in
/// a row that needed no more, as few as solver.max_step allows, to find out whether they do; a
/// trial gets a few advances to settle, and one that fails goes back and doubles the wait.
struct StepSharing {
  long steps = 1;
  long clean = 0;         // advances in a row that needed no more than `steps`
  long wait = 16;
  long trial = 0;         // while trying fewer steps: the advances left to settle into them
  long before_trial = 1;  // the steps to go back to if the trial fails
  long settling = 3;      // advances left after a restart, whose short first steps do not count
};

/// All a run needs to go on from a time as it would have gone on (Simulation::save, restore):
/// the state, each input's drive, the works so far, and where the run is in its breakpoints and
/// output samples. Accelerations and multipliers are not kept: they are solved from the state.
struct SimulationState {
  double t = 0.0;
  VecX q, v;
  std::array<double, WorkTerms::kCount> work{};
  double drive_impulses = 0.0;
  std::vector<InputState> inputs;  // in the order of Model::inputs
  std::vector<double> memory;      // the elements' (Assembler::memory)
  std::size_t next_break = 0;
  long next_sample = 1;
  bool sampled_end = false;
  StepSharing sharing;
};

class Simulation {
 public:
  /// Starts from a consistent state (consistentInitialState, or an equilibrium); passes the
  /// sample at initial.t to `sink` at once. The assembler and the sink must outlive it.
  Simulation(const Assembler& assembler, const DynamicState& initial, SampleSink& sink);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Integrates until the integrator's time reaches t (clamped to solver.t_end; exactly t with
  /// inputs); returns whether
  /// the run goes on. False when it has stopped: at t_end (outcome().complete), or for the reason
  /// in outcome().message (a solver failure, a collapsed step, `control.stop_requested`); a
  /// stopped run does not advance again.
  bool advanceTo(double t, const SimulationControl& control = {});

  /// The integrator's time: the end of its last step, at or beyond the last advanceTo's t.
  double time() const { return t_; }

  /// The run's state now. The integrator restarts here (as at a breakpoint: order 1, a small
  /// step), so that the run from now on and every run restored from this state go on alike,
  /// bit for bit. Throws std::logic_error for a run that has stopped.
  SimulationState save();
  /// Goes on from a saved state of a run of the same model (any run of it, in any process);
  /// the solver's counters and wall time go on from this run's.
  void restore(const SimulationState& state);

  /// The DAE state [q, dq, λ(, μ)] at time(), valid until the next advance.
  const double* state() const { return stepper_->state(); }
  /// The DAE state at t within the integrator's last step, interpolated, into y (size()).
  void stateAt(double t, double* y) const;

  /// The run so far: where it got, whether it reached t_end or why it stopped, the solver's
  /// counters and the wall time spent in advanceTo.
  SimulationOutcome outcome() const;

 private:
  /// One integrator step and what follows it: samples, stall check, a restart due. False: stopped.
  bool step(double target, const SimulationControl& control);
  /// Restarts the integrator where a step left one due (a breakpoint: with the drives' velocity
  /// jump; a reparameterised rotation). False: stopped.
  bool restartIfPending();
  bool stop(std::string message);
  /// Restarts the integrator from s with its accelerations and multipliers solved anew.
  void restartAt(DynamicState s);
  /// With inputs, every advance ends on its t: the integrator takes equal steps (StepSharing),
  /// so that no step is cut short to land on t and the Newton matrix keeps its step size.
  void limitSteps(double target);
  /// The steps an advance over `span` needs at least: solver.max_step's.
  long fewestSteps(double span) const;
  /// After an advance over `span` in `taken` steps, the longest but the last `longest` long.
  void countSteps(long taken, double span, double longest);

  const Assembler& assembler_;
  SampleSink& sink_;
  std::unique_ptr<TimeStepper> stepper_;
  std::vector<double> breakpoints_;
  std::size_t next_break_ = 0;
  SolverStatistics counts_;     // what the stepper does not count itself
  double drive_impulses_ = 0.0;  // the drives' work in velocity jumps (jumpVelocities), J
  double t_ = 0.0;
  double t_start_ = 0.0;
  bool stops_at_targets_ = false;  // the model has inputs
  StepSharing sharing_;
  double max_step_ = 0.0;          // the stepper's step limit, as limitSteps last set it
  long next_sample_ = 1;
  bool sampled_end_ = false;
  long stalled_steps_ = 0;
  bool stopped_ = false;
  bool complete_ = false;
  std::string message_;
  std::chrono::steady_clock::duration wall_{};
  std::vector<double> sample_;
  enum class PendingRestart { None, AtBreak, Reparameterised };
  PendingRestart restart_ = PendingRestart::None;
};

}  // namespace cranesim
