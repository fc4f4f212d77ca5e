#pragma once
// Differential flatness of a load hanging from the tip of a rigid luffing boom (docs/planning.md; the
// basis of flatness-based anti-sway, Sawodny et al. 2002), in the crane's vertical plane: a
// point load on a massless, inextensible rope of length ℓ from the tip of a boom of length R
// hinged at the foot. The load's path p(t) = (x, z) is a flat output: Newton's law for the load,
// m p̈ = T e − m g ẑ with the rope's direction e (load → tip), gives
//   e = (p̈ + g ẑ) / ‖p̈ + g ẑ‖,
// and the tip s = p + ℓ e lies on the boom's circle ‖s − foot‖ = R, a quadratic in ℓ:
//   ℓ = −d·e + √((d·e)² − ‖d‖² + R²),   d = p − foot   (the root with the tip above the load).
// So the boom angle and the rope length at t follow algebraically from p and p̈ at t, and a path
// whose derivatives up to the fourth vanish at both ends (planning/rest_to_rest_path.hpp) starts and ends
// with the rope plumb and the controls at rest: the load arrives without sway, up to the model.

#include <Eigen/Dense>

#include "cranesim/math/types.hpp"

namespace cranesim {

struct LuffingPendulum {
  Eigen::Vector2d foot = Eigen::Vector2d::Zero();  // boom foot (x, z), m
  double boom_length = 1.0;                        // R, m
  double gravity = 9.81;                           // m/s²
};

struct PendulumControls {
  Eigen::Vector2d tip;     // boom tip (x, z), m
  double boom_angle = 0.0; // elevation of foot → tip above the horizontal, rad
  double rope_length = 0.0;  // ℓ, m
};

/// The boom tip and rope length that carry the load at p with acceleration a (both (x, z)).
/// Throws std::domain_error when no tip on the boom's circle lies on the rope's line above the
/// load (the load beyond the boom's reach, or accelerating downward faster than gravity).
PendulumControls flatPendulumControls(const LuffingPendulum& crane, const Eigen::Vector2d& p, const Eigen::Vector2d& a);

/// Where a load on a rope of length ℓ would hang at rest from the suspension point s = p + ℓ e
/// that carries it at p with acceleration a (world x, y, z; z up): s − ℓ ẑ = p + ℓ (e − ẑ). A
/// crane whose static map gives the controls that hang the load at rest at a point gives, at this
/// point, the controls that carry it along p (for a suspension that moves with the controls as in
/// the statics). In three dimensions e includes the centripetal and Coriolis accelerations of a
/// slewing crane's load (planning/slewing_plane.hpp), and the pendulum may differ by direction (a
/// crane's load sways across the boom on a longer effective pendulum than along it): ℓ =
/// `length_along` along the horizontal unit vector `along` and vertically, `length_across` across it.
Vec3 restingPoint(const Vec3& p, const Vec3& a, double length_along, double length_across, const Vec3& along, double gravity);

}  // namespace cranesim
