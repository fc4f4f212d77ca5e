#pragma once
// The load's pendulum over the static map: the lengths ℓ = g (T/2π)² of the pendulums that
// swing with the crane's sway periods T, along its plane (ℓ_a) and across it (ℓ_c), measured at
// a sub-grid of the map's points and fitted over (boom angle u, hoist change v) as the map's
// other surfaces are (planning/surface_fit.hpp). The minimum-time lift carries its load on them
// (planning/minimum_time_lift.hpp), so that its pendulum is the crane's wherever the lift goes,
// not only at the lift's ends: at a fixed hoist rope the hanging length changes with the boom
// angle (the rope's run up to the boom head changes), and the boom head's give with both.

#include <vector>

#include "cranesim/model/model.hpp"
#include "cranesim/planning/static_map.hpp"
#include "cranesim/planning/surface_fit.hpp"

namespace cranesim {

/// The periods of the load's sway about the equilibrium q: the crane's lowest elastic mode in
/// which the end point's node moves mostly along x (in the crane's plane) and, with `across`,
/// mostly along y (across it). They include what the simple pendulum misses: the load's own
/// inertia below the hook, the rope's mass and stretch and the boom's compliance (across the
/// plane the boom head gives sideways: at Table 8-2's start the thesis crane sways 16.8 s across
/// against 15.5 s along). Throws std::runtime_error when no mode sways the end point that way.
struct SwayPeriods {
  double along = 0.0, across = 0.0;  // s; across 0 without `across`
};
SwayPeriods swayPeriods(const Model& model, const VecX& q, double t, const CraneControls& controls, bool across);

/// The length of the pendulum that swings with period T under gravity g: g (T/2π)².
double pendulumLength(double period, double gravity);

/// ℓ_a and ℓ_c at a sub-grid of the map and the surfaces fitted to them.
struct PendulumMap {
  GridData along, across;              // m, at the sub-grid's points (across = along for a planar lift)
  FittedSurface along_fit, across_fit;
  int modal_analyses = 0;
  double time_s = 0.0;
};

/// How many of the map's boom angles and hoist changes the pendulum is measured at (evenly
/// spread over the map's indices, its edges included), and the polynomial orders fitted.
struct PendulumGridSpec {
  int boom_angles = 5, hoist_changes = 3;
  int order_u = 3, order_v = 2;
};

/// Measures the pendulum at the sub-grid's map points (a modal analysis about each point's
/// equilibrium, on `threads` threads) and fits it. With `across` false ℓ_c is ℓ_a. Throws
/// std::runtime_error naming the point when its map point failed or it has no sway mode.
PendulumMap measurePendulumMap(const Scene& scene, const CraneControls& controls, const StaticMap& map, bool across,
                               double gravity, const PendulumGridSpec& spec = {}, int threads = 1);

}  // namespace cranesim
