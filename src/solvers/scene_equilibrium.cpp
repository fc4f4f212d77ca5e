#include "cranesim/solvers/scene_equilibrium.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "cranesim/model/carriage_tipping.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "cranesim/solvers/modes.hpp"
#include "cranesim/solvers/relaxation.hpp"

namespace cranesim {

DynamicState drawnState(const Model& model, const Assembler& assembler, bool quiet) {
  AssemblyMove move;
  DynamicState drawn =
      assembledInitialState(assembler, model.solver.t_start, model.q0, model.v0, model.solver.assembly_tolerance, &move);
  if (!quiet && move.visible())
    fmt::print(stderr, "assembled: the drawing closed by moving {}\n", move.describe());
  return drawn;
}

StaticResult sceneEquilibrium(const Scene& scene, const Model& model, const Assembler& assembler, bool quiet) {
  drawnState(model, assembler, quiet);  // reports the assembly move, refuses a drawing that is off
  StaticResult eq;
  if (model.solver.static_method == StaticMethod::Relaxation) {
    RelaxationOptions options;
    options.damping = model.solver.relaxation_damping;
    options.duration = model.solver.relaxation_duration;
    const RelaxationResult r = relaxToEquilibrium(scene, options);
    if (!quiet)
      fmt::print(stderr, "relaxation: {:.4g} s of damped motion (α = {:g}/s) in {} steps, kinetic energy down to {:.2g} of its peak\n",
                 r.relaxation_time, options.damping, r.steps, r.final_kinetic_ratio);
    eq = r.equilibrium;
  } else {
    eq = solveEquilibrium(scene, model, model.solver.t_start);
  }
  if (!eq.converged) throw std::runtime_error(eq.message);
  if (!quiet)
    fmt::print(stderr, "static equilibrium: {} Newton iterations in {} load steps and {} path steps; max |F + Gᵀλ| {:.3g}, "
                       "max |Φ| {:.3g}; in {:.3g} s\n",
               eq.iterations, eq.load_steps, eq.path_steps, eq.force_residual, eq.constraint_residual, eq.seconds);
  return eq;
}

std::string equilibriumInstability(const Model& model, const StaticResult& eq, bool quiet) {
  if (std::string tipped = carriageTipped(model, eq.q, eq.t); !tipped.empty()) return tipped;
  if (model.nv > kStabilityCheckLimit) {
    if (!quiet) fmt::print(stderr, "stability: not checked ({} velocity coordinates, more than {})\n", model.nv, kStabilityCheckLimit);
    return {};
  }
  const ModalResult modal = computeModes(model, eq.q, eq.t, 0, ModeShapes::Skipped);
  if (modal.omega_squared.size() == 0) return {};
  if (modal.omega_squared(0) < -modal.zero_threshold)
    return fmt::format("the equilibrium found is unstable: its lowest mode has ω² = {:.4g} rad²/s² (a perturbation grows "
                       "like e^({:.3g} t)); try solver.statics.method: relaxation, which settles into a stable one",
                       modal.omega_squared(0), std::sqrt(-modal.omega_squared(0)));
  for (Eigen::Index k = 0; k < modal.frequencies.size(); ++k)
    if (!modal.rigid[k]) {
      if (!quiet) fmt::print(stderr, "stability: stable; lowest elastic mode {:.4g} Hz (period {:.4g} s), {} rigid-body mode(s)\n",
                 modal.frequencies(k), 1.0 / modal.frequencies(k), modal.rigid_modes);
      break;
    }
  return {};
}

DynamicState runInitialState(const Scene& scene, const Model& model, const Assembler& assembler, bool quiet) {
  if (!model.solver.start_from_equilibrium) return drawnState(model, assembler, quiet);
  const StaticResult eq = sceneEquilibrium(scene, model, assembler, quiet);
  if (const std::string unstable = equilibriumInstability(model, eq, quiet); !unstable.empty())
    throw std::runtime_error("initial_state: equilibrium: " + unstable);
  return consistentInitialState(assembler, model.solver.t_start, eq.q, VecX::Zero(model.nv), model.solver.assembly_tolerance);
}

VecX equilibriumSample(const Assembler& assembler, const StaticResult& eq) {
  const Model& model = assembler.model();
  VecX y = VecX::Zero(assembler.size());
  y.head(model.nq) = eq.q;
  y.segment(assembler.lambdaOffset(), model.m) = eq.lambda;
  return y;
}

ConstraintLoad constraintLoad(const Constraint& constraint, const double* lambda) {
  ConstraintLoad load;
  for (int k = 0; k < constraint.rows; ++k) {
    const std::string& label = constraint.row_labels[k];
    const std::string axis = label.substr(label.rfind('/') + 1);
    const double value = lambda[constraint.row + k];
    (axis == "x" || axis == "y" || axis == "z" ? load.force : load.other) += value * value;
  }
  load.force = std::sqrt(load.force);
  load.other = std::sqrt(load.other);
  return load;
}

}  // namespace cranesim
