#pragma once
// What each small-vibration mode of a crane moves, from its shape: the shares of the mode's
// kinetic energy in the load, the boom members and the ropes, split by the boom plane (the
// vertical plane through the boom's foot and head).
//
// A mass-normalised mode φ (φᵀ M φ = 1) has the kinetic energy ½ ω² per unit amplitude, of which
// velocity coordinate i holds the share φ_i (M φ)_i; the shares add up to 1. The load, a rigid
// body, splits exactly into its centre of mass's motion, m v_c², and its turning about it,
// ωᵀ I_c ω; v_c splits into its components across the plane (normal n), vertical and horizontal
// in it. A member's translations split likewise across n and within the plane, its rotations the
// other way round (a turn about n keeps the member in the plane); a consistent mass matrix
// couples a member's nodes, so its split is close to, not exactly, a partition.

#include <string>
#include <vector>

#include "cranesim/model/model.hpp"
#include "cranesim/model/scene.hpp"
#include "cranesim/solvers/modes.hpp"

namespace cranesim {

struct ModeShares {
  double load_sway_in_plane = 0.0;      // the load's centre, horizontally in the boom plane
  double load_sway_out_of_plane = 0.0;  // across it
  double load_vertical = 0.0;           // up and down: bouncing on the hoist rope
  double load_turning = 0.0;            // the load turning about its centre
  double boom_in_plane = 0.0, boom_out_of_plane = 0.0;  // members but ropes and ties
  double ropes = 0.0;                                   // ropes and strut ties
  double rest = 0.0;                                    // other bodies (head, pedestal)

  double load() const { return load_sway_in_plane + load_sway_out_of_plane + load_vertical + load_turning; }
  double boom() const { return boom_in_plane + boom_out_of_plane; }
};

struct ModeLabel {
  ModeShares shares;
  /// The part with the largest share and how it moves: "in-plane sway", "out-of-plane sway",
  /// "load bouncing", "load turning", "boom bending in plane", "boom bending out of plane",
  /// "rope", "rest"; "rigid" for a rigid-body mode.
  std::string label;
};

/// The label of each mode of `modal` (computeModes about the equilibrium `q_eq` at `t`) of a
/// scene with a `crane:` block and its `load`.
std::vector<ModeLabel> labelModes(const Scene& scene, const Model& model, const VecX& q_eq, double t, const ModalResult& modal);

}  // namespace cranesim
