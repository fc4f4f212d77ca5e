#pragma once
// The boom angle at which a crane's static equilibrium meets the figure its scene states
// (`booms: angle_deg: from_equilibrium`, model/stated_equilibrium.hpp): the hook at a radius from
// the slewing axis, or the boom at an angle, with the ropes, ties and sections stretched and bent
// under the load. A secant on the drawn boom angle, each of its steps one static equilibrium.

#include "cranesim/model/scene.hpp"

namespace cranesim {

/// How closely the equilibrium meets the stated figure.
inline constexpr double kStatedRadiusTolerance = 1e-3;    // m
inline constexpr double kStatedBoomAngleTolerance = 1e-4;  // deg

struct StatedEquilibriumSearch {
  double angle_deg = 0.0;  // the boom angle the scene is drawn at
  double figure = 0.0;     // the equilibrium's hook radius (m) or boom angle (deg) there
  int equilibria = 0;      // static equilibria solved
};

/// The drawn boom angle whose equilibrium meets `scene`'s stated figure to the tolerance above.
/// Throws SceneError at the stated figure when the secant leaves the boom's angles (0°, 89.5°)
/// or does not converge, and what the equilibria throw.
StatedEquilibriumSearch searchStatedEquilibrium(const Scene& scene);

/// The scene drawn where its equilibrium meets its stated figure (reported on stderr unless
/// `quiet`); a scene that states none, as it is.
Scene sceneAtStatedEquilibrium(const Scene& scene, bool quiet);

}  // namespace cranesim
