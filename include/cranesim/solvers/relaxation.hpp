#pragma once
// Static equilibrium by damped dynamics (the thesis' alternative to Newton, DESIGN §5): the
// scene is frozen at time t (every drive, rope length and load scale held at its value
// there), a mass-proportional damping force α M(q) dq is added, and the equations of motion
// are integrated from rest until the kinetic energy has decayed; Newton then polishes the
// state it reached. Every underdamped mode decays like exp(−αt/2), a mode of angular
// frequency ω < α/2 like exp(−ω²t/α): α ≈ 2ω of the slowest mode relaxes fastest.
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

/// Relaxes `scene` (compiled to a model with the same coordinates) from q_start at its t_start.
RelaxationResult relaxToEquilibrium(const Scene& scene, const VecX& q_start, const RelaxationOptions& options);

}  // namespace cranesim
