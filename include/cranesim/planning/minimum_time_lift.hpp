#pragma once
// Minimum-time rest-to-rest lift of a load on a spatial pendulum carried by a crane's controls
// through its static map (docs/planning.md), as an NLP solved by Ipopt: trapezoidal direct
// collocation with a free final time, as planning/minimum_time_nlp.hpp does on a line.
//
// The controls are the map's coordinates q = (u, v, φ): boom angle u (°), hoist rope taken in v
// (m), slewing angle φ (rad). They place the point where the load would hang at rest,
// r = plane.place(x(u, v), z(u, v), φ) (planning/slewing_plane.hpp), and the pendulum's lengths
// ℓ_a(u, v) (along the crane's plane and vertically) and ℓ_c(u, v) (across it), fitted over the
// map as its other surfaces (planning/pendulum_map.hpp). The load hangs from the suspension c = r + ℓ_a ẑ on the rope direction n(α, β) =
// (sin α cos β, sin β, −cos α cos β) in the turning plane's axes (along, across, up):
//   p = c + R_z(φ) D n,   D = diag(ℓ_a, ℓ_c, ℓ_a),
// which at rest (n = −ẑ) is r, and is the spherical pendulum p = c + ℓ n when ℓ_a = ℓ_c. The
// rope pulls along n only, so the load's acceleration with gravity has no part in the two
// directions the rope can swing:
//   (p̈ + g ẑ) · R_z(φ) e_α = 0,   (p̈ + g ẑ) · R_z(φ) e_β = 0,
// e_α = ∂n/∂α / cos β, e_β = ∂n/∂β; this is the model flatness inverts (planning/flat_pendulum.hpp:
// restingPoint), so a flatness plan is a feasible start. p̈ is affine in (α̈, β̈), which these
// two equations give. The crane's drives are the luffing rope fl(u, v) (a fitted map surface),
// the hoist rope H₀ − v and the slewing angle φ₀ + φ.
//
// Decision variables per node: q, q̇, q̈, the jerk q⃛ (the control), α, β, α̇, β̇; and t_f. The
// collocation defects of the chain q → q̇ → q̈ → q⃛ and of the pendulum are the equality
// constraints; the drives' speeds and accelerations (exact, through the map) per node, and the
// luffing rope's jerk (its third time derivative through the map, linear in the jerk u⃛, v⃛), are
// ranged constraints; with obstacles, the clearance of the boom, the hoist rope and the load from
// each of them (planning/lift_clearance.hpp) at every node between the ends is at least the
// margin. The Jacobian is exact (forward-mode dual numbers through the map's
// surfaces, nested for the time derivatives); the Hessian is Ipopt's limited-memory (L-BFGS)
// approximation.

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "cranesim/planning/lift_clearance.hpp"
#include "cranesim/planning/obstacle.hpp"
#include "cranesim/planning/slewing_plane.hpp"
#include "cranesim/planning/surface_fit.hpp"

namespace cranesim {

/// How the controls q = (u, v, φ) place the load's pendulum and set the drives.
struct LiftKinematics {
  FittedSurface end_x, end_z;    // the map's resting end point x(u, v), z(u, v), m
  FittedSurface luffing;         // the luffing rope's unstretched length fl(u, v), m
  double hoist_length = 0.0;     // H₀: the hoist rope at v = 0, m
  double slewing_start = 0.0;    // φ₀: the slewing drive at φ = 0, rad
  SlewingPlane plane;            // turns the map's plane by φ
  /// The pendulum's lengths along and across the plane over the map (planning/pendulum_map.hpp).
  FittedSurface along_length, across_length;
  double gravity = 9.81;
  LiftBody body;                 // the parts kept clear of obstacles

  /// ℓ_a and ℓ_c at (u, v) (any scalar type of math/autodiff.hpp).
  template <class S> S along(const S& u, const S& v) const { return along_length.evaluate(u, v); }
  template <class S> S across(const S& u, const S& v) const { return across_length.evaluate(u, v); }
};

/// What a drive (luffing rope, hoist rope, slewing) may be asked: |rate| ≤ speed, |rate'| ≤
/// acceleration. Jerk limits bound the coordinates' jerk q⃛ (LiftProblem::jerk_limit).
struct DriveBounds {
  double speed = std::numeric_limits<double>::infinity();
  double acceleration = std::numeric_limits<double>::infinity();
};

enum LiftDrive { kLuffingDrive, kHoistDrive, kSlewingDrive };

struct LiftProblem {
  LiftKinematics crane;
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();  // q at rest
  Eigen::Vector3d q_min = Eigen::Vector3d::Constant(-1e20), q_max = Eigen::Vector3d::Constant(1e20);
  std::array<DriveBounds, 3> drives;  // indexed by LiftDrive
  Eigen::Vector3d jerk_limit = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());  // |q⃛|
  /// |d³fl/dt³|: the luffing rope's own jerk through the map, at every node.
  double luffing_jerk_limit = std::numeric_limits<double>::infinity();
  /// Obstacles every part (crane.body) clears by `clearance_margin` at every node.
  std::vector<Obstacle> obstacles;
  double clearance_margin = 0.0;
  int intervals = 100;
  double tolerance = 1e-8;
  int max_iterations = 3000;
  int print_level = 0;
};

/// One node's variables, in the NLP's order.
struct LiftNode {
  Eigen::Vector3d q = Eigen::Vector3d::Zero(), rate = Eigen::Vector3d::Zero(), acceleration = Eigen::Vector3d::Zero(),
                  jerk = Eigen::Vector3d::Zero();
  Eigen::Vector4d swing = Eigen::Vector4d::Zero();  // α, β, α̇, β̇
};

/// A start for the solver: t_f and the nodes at t_f · k / N, k = 0 … N.
struct LiftGuess {
  double final_time = 0.0;
  std::vector<LiftNode> nodes;
};

/// The drives' values, speeds, accelerations and jerks at a node.
struct DriveState {
  Eigen::Vector3d value, speed, acceleration, jerk;  // indexed by LiftDrive
};

struct LiftTrajectory {
  double final_time = 0.0;
  std::vector<double> t;
  std::vector<LiftNode> nodes;
  std::vector<Vec3> load;          // the load's position p (world), per node
  std::vector<DriveState> drives;  // per node
  std::vector<double> clearance;   // with obstacles: the smallest of clearanceAt per node, m
  int iterations = 0;
  double solve_time_s = 0.0;       // wall time of the solve
};

/// The load's position and the pendulum's angular accelerations (α̈, β̈) at a node.
struct PendulumState {
  Vec3 load;
  Eigen::Vector2d swing_acceleration;
};
PendulumState pendulumAt(const LiftKinematics& crane, const LiftNode& node);
DriveState drivesAt(const LiftKinematics& crane, const LiftNode& node);

/// The parts' smallest clearance at a node from the problem's obstacles, as the NLP constrains it
/// (planning/lift_clearance.hpp: a lower bound of the exact one within 2 cm), and whose.
struct NodeClearance {
  double clearance = std::numeric_limits<double>::infinity();
  int obstacle = -1;
  LiftPart part = kLoadPart;
};
NodeClearance clearanceAt(const LiftProblem& problem, const LiftNode& node);

/// A start that moves q from `start` to `end` by the rest-to-rest polynomial over `duration`
/// with the pendulum hanging plumb.
LiftGuess restToRestGuess(const LiftProblem& problem, double duration);

/// A start that visits the waypoints (q; the first the start, the last the end) at rest, from
/// each to the next by the rest-to-rest polynomial over the least time in which its drives keep
/// their limits, the pendulum hanging plumb; N + 1 nodes equally spaced in time.
LiftGuess waypointGuess(const LiftProblem& problem, const std::vector<Eigen::Vector3d>& waypoints);

/// The solver failed with its last iterate closer to an obstacle than the margin: most likely
/// no lift within the map and the drive limits clears it.
struct LiftBlocked : std::runtime_error {
  LiftBlocked(const std::string& what, const NodeClearance& closest, double t)
      : std::runtime_error(what), closest(closest), t(t) {}
  NodeClearance closest;
  double t;  // at the node, in the last iterate's time, s
};

/// Solves the problem from `guess` (resampled to the problem's intervals by linear
/// interpolation). Throws std::invalid_argument for fewer than 2 intervals, a guess without
/// nodes, a non-positive limit or obstacles without a boom, LiftBlocked when Ipopt fails with its
/// last iterate within the margin of an obstacle, and std::runtime_error naming Ipopt's status
/// when it fails otherwise.
LiftTrajectory solveMinimumTimeLift(const LiftProblem& problem, const LiftGuess& guess);

}  // namespace cranesim
