#include "cranesim/solvers/relaxation.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>

#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "cranesim/solvers/initial_conditions.hpp"

namespace cranesim {
namespace {

Profile frozen(const Profile& p, double t) { return Profile(ConstantProfile{p(t)}); }

/// The scene with every rope reeled from its drawn length to its length at t over
/// [t, t + reel_time] and every other time-dependent input held at its value at t.
Scene reeledFromDrawing(Scene scene, double t, double reel_time) {
  for (ConstraintSpec& c : scene.constraints)
    if (c.drive) c.drive = frozen(*c.drive, t);
  for (MemberSpec& m : scene.members)
    if (m.length) m.length = Profile(CosineStepProfile{drawnRopeLength(m), (*m.length)(t), t, t + reel_time});
  for (LoadSpec& l : scene.loads) l.scale = frozen(l.scale, t);
  return scene;
}

/// Keeps the latest state and asks the integrator to stop once the motion has died out.
class RelaxationMonitor final : public SampleSink {
 public:
  RelaxationMonitor(const Assembler& assembler, double ratio, double min_time)
      : assembler_(assembler), ratio_(ratio), min_time_(min_time) {}

  void sample(double t, const double* y, const WorkTerms&) override {
    const Model& model = assembler_.model();
    last_.assign(y, y + assembler_.size());
    time_ = t;
    kinetic_ = assembler_.kineticEnergy(t, y, y + model.nq);
    peak_ = std::max(peak_, kinetic_);
    if (t - assembler_.model().solver.t_start >= min_time_ && kinetic_ <= ratio_ * peak_) stop_ = true;
  }

  const std::atomic<bool>& stop() const { return stop_; }
  const std::vector<double>& last() const { return last_; }
  double time() const { return time_; }
  double kineticRatio() const { return peak_ > 0.0 ? kinetic_ / peak_ : 0.0; }

 private:
  const Assembler& assembler_;
  double ratio_, min_time_;
  std::vector<double> last_;
  double time_ = 0.0, kinetic_ = 0.0, peak_ = 0.0;
  std::atomic<bool> stop_{false};
};

}  // namespace

RelaxationResult relaxToEquilibrium(const Scene& scene, const RelaxationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const double t0 = scene.solver.t_start, reel_time = 10.0 / options.damping;
  Scene reeled = reeledFromDrawing(scene, t0, reel_time);
  reeled.solver.t_end = t0 + reel_time + options.duration;
  reeled.output.interval = std::min(0.1 / options.damping, options.duration / 100.0);
  const Model model = compileModel(reeled);
  Assembler assembler(model, Formulation::GGL);
  assembler.setMassDamping(options.damping);

  RelaxationResult result;
  const DynamicState initial =
      assembledInitialState(assembler, t0, model.q0, VecX::Zero(model.nv), model.solver.assembly_tolerance);
  // Motion that starts from rest needs a few damping times to build up before it can die out.
  RelaxationMonitor monitor(assembler, options.kinetic_energy_ratio, reel_time + 2.0 / options.damping);
  SimulationControl control;
  control.stop_requested = &monitor.stop();
  const SimulationOutcome outcome = simulate(assembler, initial, monitor, control);
  result.steps = outcome.statistics.steps;
  result.relaxation_time = monitor.time() - model.solver.t_start;
  result.final_kinetic_ratio = monitor.kineticRatio();
  if (!outcome.complete && !monitor.stop().load()) {
    result.equilibrium.message = fmt::format("relaxation failed: {}", outcome.message);
    return result;
  }
  // Polished with the ropes at their lengths at t_start (the reeled model's are still drawn there).
  const VecX relaxed = Eigen::Map<const VecX>(monitor.last().data(), model.nq);
  result.equilibrium = solveStatics(compileModel(scene), relaxed, t0);
  if (!result.equilibrium.converged)
    result.equilibrium.message = fmt::format("after {:.3g} s of relaxation (kinetic energy at {:.2g} of its peak): {}",
                                             result.relaxation_time, result.final_kinetic_ratio,
                                             result.equilibrium.message);
  result.equilibrium.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace cranesim
