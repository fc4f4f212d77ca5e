#pragma once
// The starting points every analysis of a scene shares (crane-sim's run, static and modes, and
// the cases of a study): the drawing assembled, the scene's static equilibrium by its
// solver.statics method with its stability checked, and the state a run starts from.

#include <string>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/model/scene.hpp"
#include "cranesim/solvers/initial_conditions.hpp"
#include "cranesim/solvers/statics.hpp"

namespace cranesim {

/// The scene's drawing, posed at its drives and assembled; a move beyond rounding is reported on
/// stderr unless `quiet`.
DynamicState drawnState(const Model& model, const Assembler& assembler, bool quiet);

/// Static equilibrium of the scene at its start time by the scene's method (solver.statics):
/// Newton along the path from the drawn controls, or relaxation from the drawn state. Reported on
/// stderr unless `quiet`. Throws when it is not found.
StaticResult sceneEquilibrium(const Scene& scene, const Model& model, const Assembler& assembler, bool quiet);

/// Models up to this many velocity coordinates get the equilibrium's stability checked (dense
/// modal analysis without the shapes, O(nv³): ~5 ms for the thesis crane's 160, 0.5 s for its
/// full-member model's 1230, a few seconds at 2000).
inline constexpr int kStabilityCheckLimit = 2000;

/// Why the equilibrium is not one the scene stands in — its carriage has tipped
/// (model/carriage_tipping.hpp), or it is unstable (its reduced stiffness has a negative
/// eigenvalue) — or empty; the lowest elastic mode is reported on stderr unless `quiet`.
std::string equilibriumInstability(const Model& model, const StaticResult& eq, bool quiet);

/// The state a run starts from: the assembled drawing, or for `initial_state: equilibrium` the
/// scene's equilibrium at rest. Throws std::runtime_error when that equilibrium is not found or
/// is unstable.
DynamicState runInitialState(const Scene& scene, const Model& model, const Assembler& assembler, bool quiet);

/// The DAE state [q, dq = 0, λ] of an equilibrium, as a results recorder samples it.
VecX equilibriumSample(const Assembler& assembler, const StaticResult& eq);

/// The force a constraint carries (the norm of its x, y, z rows of λ) and the norm of its other
/// rows (moments, or a drive's force or torque). A rope's tension is the force of the constraint
/// at its end.
struct ConstraintLoad {
  double force = 0.0, other = 0.0;
};
ConstraintLoad constraintLoad(const Constraint& constraint, const double* lambda);

}  // namespace cranesim
