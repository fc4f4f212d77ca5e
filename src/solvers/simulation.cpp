#include "cranesim/solvers/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "cranesim/math/rotation.hpp"

namespace cranesim {
namespace {

constexpr double kStallFraction = 1e-12;  // a step shorter than this (relative to t) makes no progress
constexpr long kMaxStalledSteps = 1000;

DynamicState stateOf(const Assembler& assembler, double t, const double* y) {
  const Model& model = assembler.model();
  DynamicState s;
  s.t = t;
  s.q = Eigen::Map<const VecX>(y, model.nq);
  s.v = Eigen::Map<const VecX>(y + assembler.vOffset(), model.nv);
  return s;
}

/// Re-parameterises every rotation vector beyond the threshold; returns how many changed.
int reparameterise(const Model& model, double* q) {
  int changed = 0;
  for (const Node& n : model.nodes) {
    if (!n.hasRotation()) continue;
    Vec3 phi(q + n.q + 3);
    if (cranesim::reparameterise(phi)) {
      std::copy(phi.data(), phi.data() + 3, q + n.q + 3);
      ++changed;
    }
  }
  return changed;
}

/// Times closer than this are the same time to the integrator (IDAS refuses to step shorter).
double roundingOf(double t) { return 1e-12 * std::max(1.0, std::abs(t)); }

}  // namespace

Simulation::Simulation(const Assembler& assembler, const DynamicState& initial, SampleSink& sink)
    : assembler_(assembler), sink_(sink), t_(initial.t), t_start_(initial.t), sample_(assembler.size()) {
  const auto wall_start = std::chrono::steady_clock::now();
  stepper_ = makeTimeStepper(assembler, initial);
  assembler_.forgetMemory();
  assembler_.hold(t_, stepper_->state());
  breakpoints_ = assembler.model().breakpoints();
  stops_at_targets_ = !assembler.model().inputs.empty();
  while (next_break_ < breakpoints_.size() && breakpoints_[next_break_] <= t_) ++next_break_;
  sink_.sample(t_, stepper_->state(), WorkTerms{});
  wall_ += std::chrono::steady_clock::now() - wall_start;
}

Simulation::~Simulation() = default;

bool Simulation::advanceTo(double t, const SimulationControl& control) {
  if (stopped_) return false;
  const auto wall_start = std::chrono::steady_clock::now();
  const double t_end = assembler_.model().solver.t_end;
  const double target = std::min(t, t_end);
  if (stops_at_targets_ && target > t_) limitSteps(target);
  const double from = t_;
  bool going = true;
  long taken = 0;
  double longest = 0.0, last = 0.0;  // longest: of the steps before the last, which lands on t
  // With inputs, a target within rounding of where the run is (a caller's sum of sample times)
  // is reached: no integrator can step that far.
  const auto reached = [&] { return t_ >= target || (stops_at_targets_ && target - t_ <= roundingOf(target)); };
  while (going && !reached()) {
    const double before = t_;
    going = step(target, control);
    ++taken;
    longest = std::max(longest, last);
    last = t_ - before;
  }
  if (stops_at_targets_ && going) countSteps(taken, target - from, longest);
  if (going && (t_ >= t_end || (stops_at_targets_ && target == t_end && reached()))) {
    stopped_ = complete_ = true;
    going = false;
  }
  wall_ += std::chrono::steady_clock::now() - wall_start;
  return going;
}

void Simulation::stateAt(double t, double* y) const {
  std::array<double, WorkTerms::kCount> work{};
  stepper_->interpolate(t, y, work.data());
}

void Simulation::limitSteps(double target) {
  const double span = target - t_;
  sharing_.steps = std::max(sharing_.steps, fewestSteps(span));
  const double h = span / static_cast<double>(sharing_.steps);
  if (std::abs(h - max_step_) > 1e-9 * h) {  // the same limit for advances of the same span
    max_step_ = h;
    stepper_->setMaxStep(h);
  }
}

long Simulation::fewestSteps(double span) const {
  const double limit = assembler_.model().solver.max_step;
  return limit > 0.0 ? std::max(1L, static_cast<long>(std::ceil(span / limit - 1e-9))) : 1L;
}

void Simulation::countSteps(long taken, double span, double longest) {
  constexpr long kFirstWait = 16, kLongestWait = 128, kSettle = 3;
  StepSharing& s = sharing_;
  if (s.settling > 0) {
    --s.settling;
    return;
  }
  if (taken > s.steps) {
    if (s.trial > 1) {  // the integrator is still growing its step towards the trial's
      --s.trial;
      return;
    }
    if (s.trial == 1) {  // the trial failed: back, and wait twice as long for the next
      s.steps = s.before_trial;
      s.wait = std::min(2 * s.wait, kLongestWait);
    } else {  // the integrator shortened its steps (its error, Newton's convergence)
      s.steps = std::max(s.steps, static_cast<long>(std::ceil(span / longest - 1e-9)));
    }
    s.trial = 0;
    s.clean = 0;
    return;
  }
  if (s.trial > 0) s.wait = kFirstWait;
  s.trial = 0;
  if (++s.clean < s.wait) return;
  s.clean = 0;
  const long fewer = fewestSteps(span);
  if (fewer < s.steps) {
    s.before_trial = s.steps;
    s.steps = fewer;
    s.trial = kSettle;
  }
}

void Simulation::restartAt(DynamicState s) {
  solveAccelerations(assembler_, s, Limit::Right);
  stepper_->restart(s);
  sharing_.settling = StepSharing{}.settling;
}

SimulationState Simulation::save() {
  if (stopped_) throw std::logic_error("a run that has stopped cannot be saved");
  if (!restartIfPending()) throw std::runtime_error(message_);
  const Model& model = assembler_.model();
  const DynamicState s = stateOf(assembler_, t_, stepper_->state());
  restartAt(s);
  stepper_->forgetPivots();
  ++counts_.restarts;
  SimulationState saved;
  saved.t = t_;
  saved.q = s.q;
  saved.v = s.v;
  stepper_->work(saved.work.data());
  saved.drive_impulses = drive_impulses_;
  for (const ModelInput& input : model.inputs) saved.inputs.push_back(input.signal->state());
  saved.memory = assembler_.memory();
  saved.next_break = next_break_;
  saved.next_sample = next_sample_;
  saved.sampled_end = sampled_end_;
  saved.sharing = sharing_;
  return saved;
}

void Simulation::restore(const SimulationState& saved) {
  const Model& model = assembler_.model();
  if (saved.q.size() != model.nq || saved.v.size() != model.nv || saved.inputs.size() != model.inputs.size() ||
      saved.next_break > breakpoints_.size())
    throw std::invalid_argument(fmt::format("the saved state ({} coordinates, {} inputs) is not one of this model "
                                            "({} coordinates, {} inputs)",
                                            saved.q.size(), saved.inputs.size(), model.nq, model.inputs.size()));
  for (std::size_t k = 0; k < saved.inputs.size(); ++k) model.inputs[k].signal->restore(saved.inputs[k]);
  assembler_.setMemory(saved.memory);
  DynamicState s;
  s.t = saved.t;
  s.q = saved.q;
  s.v = saved.v;
  restartAt(s);
  stepper_->forgetPivots();
  stepper_->setWork(saved.work.data());
  ++counts_.restarts;
  t_ = saved.t;
  drive_impulses_ = saved.drive_impulses;
  next_break_ = saved.next_break;
  next_sample_ = saved.next_sample;
  sampled_end_ = saved.sampled_end;
  sharing_ = saved.sharing;
  stalled_steps_ = 0;
  restart_ = PendingRestart::None;
  stopped_ = complete_ = false;
  message_.clear();
}

bool Simulation::stop(std::string message) {
  stopped_ = true;
  message_ = std::move(message);
  return false;
}

bool Simulation::step(double target, const SimulationControl& control) {
  if (!restartIfPending()) return false;
  const Model& model = assembler_.model();
  const double t_end = model.solver.t_end, dt_out = model.output.interval;
  const double t_break = next_break_ < breakpoints_.size() ? breakpoints_[next_break_] : t_end;
  const bool to_target = stops_at_targets_ && target < t_break;
  // A breakpoint within rounding of where the run is (reached by a sum of sample times) is passed
  // where the run is: no integrator can step that far.
  const bool on_break = !to_target && t_break - t_ <= roundingOf(t_break);
  StepOutcome step;
  if (on_break)
    step.reached_stop = true;
  else
    step = stepper_->step(to_target ? target : t_break);
  if (!step.failure.empty()) return stop(fmt::format("solver failure at t = {:.6g} s: {}", t_, step.failure));
  const double t_ret = on_break ? t_ : stepper_->time();
  // Samples up to t_ret, interpolated within the step; the last one exactly at t_end.
  std::array<double, WorkTerms::kCount> work{};
  const double eps = 1e-12 * std::max(1.0, std::abs(t_ret));
  while (!sampled_end_) {
    double ts = t_start_ + static_cast<double>(next_sample_) * dt_out;
    if (ts > t_end - eps) ts = t_end;
    if (ts > t_ret + eps) break;
    stepper_->interpolate(std::min(ts, t_ret), sample_.data(), work.data());
    WorkTerms works = WorkTerms::fromArray(work.data());
    works.drive += drive_impulses_;
    sink_.sample(ts, sample_.data(), works);
    ++next_sample_;
    sampled_end_ = ts == t_end;
  }
  // The integrators' step limits do not apply step by step: stop a run whose step size collapsed.
  stalled_steps_ = t_ret - t_ > kStallFraction * std::max(1.0, std::abs(t_ret)) ? 0 : stalled_steps_ + 1;
  if (stalled_steps_ > kMaxStalledSteps) {
    const double collapsed = t_ret - t_;
    t_ = t_ret;
    return stop(fmt::format("solver failure at t = {:.6g} s: the step size collapsed to {:.3g} s for {} steps (a "
                            "locked mechanism or a discontinuity the model cannot follow)",
                            t_, collapsed, kMaxStalledSteps));
  }
  t_ = t_ret;
  double* y = stepper_->state();
  if (!on_break) assembler_.hold(t_, y);
  if (model.m > 0)
    counts_.max_step_constraint_residual =
        std::max(counts_.max_step_constraint_residual, assembler_.constraintResidual(t_, y));
  if (control.on_step) control.on_step(t_);
  if (control.stop_requested && control.stop_requested->load())
    return stop(fmt::format("interrupted at t = {:.6g} s", t_));

  const int changed = reparameterise(model, y);
  const bool at_break = step.reached_stop && !to_target;
  if ((at_break || changed > 0) && t_ < t_end) {
    if (at_break) ++next_break_;
    counts_.reparameterisations += changed;
    // Restarted when the run goes on: until then the step's history interpolates any time within
    // it (an advance's target the step passed on its way to a breakpoint).
    restart_ = at_break ? PendingRestart::AtBreak : PendingRestart::Reparameterised;
  }
  return true;
}

bool Simulation::restartIfPending() {
  if (restart_ == PendingRestart::None) return true;
  const bool at_break = restart_ == PendingRestart::AtBreak;
  restart_ = PendingRestart::None;
  ++counts_.restarts;
  DynamicState s = stateOf(assembler_, t_, stepper_->state());
  try {
    // A drive's velocity may jump at a breakpoint: the masses' response to the impulse, whose
    // work is the drives', then the coming segment's accelerations and multipliers.
    if (at_break && assembler_.model().m > 0) {
      const ConstraintState C = assembler_.constraints(t_, s.q.data(), s.v.data(), Limit::Right);
      if (C.phi_dot.cwiseAbs().maxCoeff() > 0.0) drive_impulses_ += jumpVelocities(assembler_, s, C);
    }
    restartAt(s);
  } catch (const std::exception& e) {
    return stop(e.what());
  }
  return true;
}

SimulationOutcome Simulation::outcome() const {
  SimulationOutcome outcome;
  outcome.complete = complete_;
  outcome.message = message_;
  outcome.t_reached = t_;
  outcome.statistics = stepper_->statistics();
  outcome.statistics.reparameterisations = counts_.reparameterisations;
  outcome.statistics.restarts = counts_.restarts;
  outcome.statistics.max_step_constraint_residual = counts_.max_step_constraint_residual;
  outcome.statistics.wall_time_s = std::chrono::duration<double>(wall_).count();
  return outcome;
}

}  // namespace cranesim
