#pragma once
// Static equilibrium by damped dynamics (the thesis' alternative to Newton:
// docs/numerics.md#relaxation-and-the-stability-check): from the scene's drawing, posed at its
// drives and assembled, a mass-proportional damping force α M(q) dq is added and the equations of
// motion are integrated until the kinetic energy has decayed; Newton then polishes the state it
// reached. Ropes start at their drawn length (the chord, taut by 1e-3 as on the Newton path,
// equilibrium_path.hpp) and are reeled to their length at t_start by a cosine step over 10/α, as
// winches would; everything else is held at t_start. Released at the target lengths instead, a
// crane's ropes start metres slack or stretched by tens of per cent (3e8 N in the thesis crane's
// hoist rope shortened to 40 m), and the motion that follows is no path to an equilibrium. Every
// underdamped mode decays like exp(−αt/2), a mode of angular frequency ω < α/2 like
// exp(−ω²t/α): α ≈ 2ω of the slowest mode relaxes fastest.
//
// It finds equilibria that Newton started far away does not: a slack rope hanging straight
// between its supports has no transverse stiffness, a mechanism released far from its rest
// position falls into it.

#include "cranesim/model/scene.hpp"
#include "cranesim/solvers/statics.hpp"

namespace cranesim {

struct RelaxationOptions {
  double damping = 1.0;    // α, 1/s
  double duration = 100.0; // pseudo-time limit, s
  /// Relaxed when the kinetic energy has fallen to this fraction of its peak.
  double kinetic_energy_ratio = 1e-12;
};

struct RelaxationResult {
  StaticResult equilibrium;  // after the Newton polish; converged == both stages succeeded
  double relaxation_time = 0.0;  // pseudo-time integrated, s
  long steps = 0;                // integrator steps
  double final_kinetic_ratio = 0.0;
};

/// Relaxes `scene` from its drawing to rest at its t_start. The result's coordinates are those
/// of compileModel(scene).
RelaxationResult relaxToEquilibrium(const Scene& scene, const RelaxationOptions& options);

}  // namespace cranesim
