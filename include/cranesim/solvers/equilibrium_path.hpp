#pragma once
// The static equilibrium of a scene for its controls at time t, reached along a path from the
// drawn geometry. This is the statics every tool uses: `crane-sim static`,
// `initial_state: equilibrium`, and the start of crane-opt's map.
//
// Newton from the drawn geometry straight to controls far from the drawing fails: a luffing
// rope longer than drawn leaves the boom unsupported at the start (a slack rope has no
// stiffness), a hoist rope paid out leaves the load hanging in the air, a slewing drive at 45°
// starts with the joint 45° off. Ramping gravity from zero (load stepping) does not help a crane:
// without gravity nothing tensions its ropes and the structure is a mechanism. Instead the
// controls — every rope's unstretched length and every drive's value — start where the drawing
// has them (the rope's chord, the joint's measured angle, displacement or distance; driven
// joints that can be posed rigidly are posed first, solvers/drive_posing.hpp), where the
// drawn state is nearly in equilibrium under full gravity, and move along a straight line in a
// path parameter τ ∈ [0, 1] to their values at t:
//   c(τ) = c_drawn + τ (c(t) − c_drawn).
// Applied loads (`loads:`) are controls too: the drawing carries none, so their scale moves from 0
// to its value at t (a slender beam bent far by a tip force or an end moment follows its
// deflection instead of being solved for it in one Newton: the roll-up by an end moment took
// 409–446 iterations, now 89–93). Each path step is predicted along the tangent
// dx/dτ = −J⁻¹ ∂R/∂τ and corrected by damped Newton; a step whose Newton fails is halved, a quick
// one lets the next one double. Gravity acts in full all along (load stepping remains the
// fallback at τ = 0 only).

#include <string>
#include <vector>

#include "cranesim/model/scene.hpp"
#include "cranesim/solvers/statics.hpp"

namespace cranesim {

/// A control moved along the path, for reports and messages.
struct PathControl {
  std::string name;   // "<rope> length", "<constraint> drive" or "<load> load scale"
  double drawn = 0.0;   // value in the drawn geometry (m or rad)
  double target = 0.0;  // value at t
  bool angle = false;   // a revolute's angle (reported in degrees)
};

struct PathOptions {
  StaticOptions newton;           // for the start at τ = 0 (with its load stepping) and each step
  int step_iterations = 12;       // Newton iterations allowed per path step before it is halved
  /// Newton's step tolerance (relative, as StaticOptions::tolerance) at the start and at the
  /// path's intermediate points: they only start the next step, whose predictor errs far more.
  double intermediate_tolerance = 1e-6;
  double min_step = 1.0 / 4096;   // the smallest path step tried before giving up
  /// The smallest path step tried after a corrector that ended with the carriage tipped: past
  /// its tipping point a crane on supports has no equilibrium, and halving further only finds
  /// that point more closely (the outrigger chart's tipped cases took 0.67 s each, 12 Newton
  /// iterations per halving down to min_step).
  double min_step_tipped = 1.0 / 64;
  /// The predictor turns no node by more than this (rad): its error grows like the square of
  /// the turn, and a revolute drive's equation converges within half a turn.
  double max_angle_step = 0.5;
};

/// A rope's unstretched length in the drawing: its chord, less a strain of 1e-3 so that it
/// starts taut, with axial and transverse stiffness, rather than on the tension-only law's kink.
double drawnRopeLength(const MemberSpec& rope);

/// The path's controls: ropes whose unstretched length differs from their drawn one, drives
/// whose value at t differs from the one in the drawn state q_drawn (to 1e-12 relative), loads
/// whose scale at t is not 0.
/// `model` is compileModel(scene).
std::vector<PathControl> pathControls(const Scene& scene, const Model& model, const VecX& q_drawn, double t);

/// The equilibrium of `model` (compiled from `scene`) at time t, solved along the path from
/// the drawn controls. result.load_steps counts the Newton stage at τ = 0 (its load steps);
/// result.path_steps the path's steps. On failure the message names the controls and how far
/// along the path the solution got. The drawing (its drives at their drawn values) is
/// assembled first, within scene.solver.assembly_tolerance (solvers/initial_conditions.hpp).
StaticResult solveEquilibrium(const Scene& scene, const Model& model, double t, const PathOptions& options = {});

}  // namespace cranesim
