#include "cranesim/solvers/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

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

}  // namespace

Simulation::Simulation(const Assembler& assembler, const DynamicState& initial, SampleSink& sink)
    : assembler_(assembler), sink_(sink), t_(initial.t), t_start_(initial.t), sample_(assembler.size()) {
  const auto wall_start = std::chrono::steady_clock::now();
  stepper_ = makeTimeStepper(assembler, initial);
  breakpoints_ = assembler.model().breakpoints();
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
  bool going = true;
  while (going && t_ < target) going = step(control);
  if (going && t_ >= t_end) {
    stopped_ = complete_ = true;
    going = false;
  }
  wall_ += std::chrono::steady_clock::now() - wall_start;
  return going;
}

bool Simulation::stop(std::string message) {
  stopped_ = true;
  message_ = std::move(message);
  return false;
}

bool Simulation::step(const SimulationControl& control) {
  const Model& model = assembler_.model();
  const double t_end = model.solver.t_end, dt_out = model.output.interval;
  const double t_stop = next_break_ < breakpoints_.size() ? breakpoints_[next_break_] : t_end;
  const StepOutcome step = stepper_->step(t_stop);
  if (!step.failure.empty()) return stop(fmt::format("solver failure at t = {:.6g} s: {}", t_, step.failure));
  const double t_ret = stepper_->time();
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
  if (model.m > 0)
    counts_.max_step_constraint_residual =
        std::max(counts_.max_step_constraint_residual, assembler_.constraintResidual(t_, y));
  if (control.on_step) control.on_step(t_);
  if (control.stop_requested && control.stop_requested->load())
    return stop(fmt::format("interrupted at t = {:.6g} s", t_));

  const int changed = reparameterise(model, y);
  if ((step.reached_stop || changed > 0) && t_ < t_end) {
    if (step.reached_stop) ++next_break_;
    counts_.reparameterisations += changed;
    ++counts_.restarts;
    DynamicState s = stateOf(assembler_, t_, y);
    try {
      // A drive's velocity may jump at a breakpoint: the masses' response to the impulse, whose
      // work is the drives', then the coming segment's accelerations and multipliers.
      if (step.reached_stop && model.m > 0) {
        const ConstraintState C = assembler_.constraints(t_, s.q.data(), s.v.data(), Limit::Right);
        if (C.phi_dot.cwiseAbs().maxCoeff() > 0.0) drive_impulses_ += jumpVelocities(assembler_, s, C);
      }
      solveAccelerations(assembler_, s, Limit::Right);
    } catch (const std::exception& e) {
      return stop(e.what());
    }
    stepper_->restart(s);
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
