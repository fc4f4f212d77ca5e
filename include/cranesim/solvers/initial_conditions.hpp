#pragma once
// Consistent initial conditions (DESIGN §5): positions on Φ = 0, velocities on Φ̇ = 0, and
// accelerations and multipliers from the saddle-point system (4-3)
//   [M  Gᵀ] [d(dq)/dt]   [−F + Q]
//   [G  0 ] [   λ    ] = [  −Γ  ].

#include "cranesim/assembly/assembler.hpp"

namespace cranesim {

struct DynamicState {
  double t = 0.0;
  VecX q, v, a, lambda, qdot;
};

/// Checks the constraint Jacobian for redundant equations; throws SceneError naming them.
void requireIndependentConstraints(const Assembler& assembler, const VecX& q, double t);

/// Projects (q, v) onto the constraint manifold and solves for a and λ. Throws SceneError
/// naming the constraint when the initial violation exceeds `tolerance`.
DynamicState consistentInitialState(const Assembler& assembler, double t, VecX q, VecX v, double tolerance);

/// The scene's drawn state (q, v) at time t: posed at its drives' values (solvers/drive_posing.hpp),
/// then made consistent as by consistentInitialState.
DynamicState assembledInitialState(const Assembler& assembler, double t, VecX q, VecX v, double tolerance);

/// Recomputes a, λ and q̇ for a state whose q and v are already consistent. `limit`: Right
/// when restarting from a breakpoint, so the accelerations are those of the coming segment.
void solveAccelerations(const Assembler& assembler, DynamicState& state, Limit limit = Limit::Left);
/// The same with the constraint quantities at (state.t, state.q, state.v) already evaluated.
void solveAccelerations(const Assembler& assembler, DynamicState& state, const ConstraintState& constraints,
                        Limit limit = Limit::Left);

}  // namespace cranesim
