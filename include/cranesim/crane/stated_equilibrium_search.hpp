#pragma once
// The drawing of a boom at which a crane's static equilibrium meets the figures its scene states
// (`booms: equilibrium`, model/stated_equilibrium.hpp): the boom angle that holds the hook at a
// radius from the slewing axis or stands the boom at an angle, and the hoist rope's length that
// holds the hook at a height, with the ropes, ties and sections stretched and bent under the
// load. Each step of the search is one static equilibrium: a secant on the drawn boom angle, and
// the hoist rope's length corrected by the hook's miss (the hook moves by the change of the
// rope's length, stretched: by its strain more).

#include "cranesim/model/scene.hpp"

namespace cranesim {

/// How closely the equilibrium meets the stated figures.
inline constexpr double kStatedRadiusTolerance = 1e-3;     // m
inline constexpr double kStatedBoomAngleTolerance = 1e-4;  // deg
inline constexpr double kStatedHookHeightTolerance = 1e-3;  // m

struct StatedEquilibriumSearch {
  BoomDrawing drawing;       // what the scene is drawn at
  double figure = 0.0;       // the equilibrium's hook radius (m) or boom angle (deg) there, if one is stated
  double hook_height = 0.0;  // m: the equilibrium's hook height there
  int equilibria = 0;        // static equilibria solved
};

/// The drawing whose equilibrium meets `scene`'s stated figures to the tolerances above. Throws
/// SceneError at a stated figure when the search leaves the boom's angles (0°, 89.5°), would
/// shorten the hoist rope below 0.1 m, or does not converge; and what the equilibria throw.
StatedEquilibriumSearch searchStatedEquilibrium(const Scene& scene);

/// The scene drawn where its equilibrium meets its stated figures (reported on stderr unless
/// `quiet`); a scene that states none, as it is. Every command that computes a scene draws it so.
Scene sceneAtStatedEquilibrium(const Scene& scene, bool quiet);

}  // namespace cranesim
