#pragma once
// crane-opt's method minimum_time (docs/planning.md): the minimum-time lift NLP
// (planning/minimum_time_lift.hpp) set up on a target's static map and drive limits, and
// started from the target's flatness plan, or, when that cuts an obstacle, from a lift over and
// around the obstacles.

#include "cranesim/planning/minimum_time_lift.hpp"
#include "cranesim/planning/quasi_static_plan.hpp"

namespace cranesim {

/// The lift from the plan's start to its target on the plan's fitted map and plane, its pendulum
/// the one measured over the map (plan.pendulum_map, which must be set), within the target's
/// drive limits: a drive without an acceleration limit is held to speed / rise_time, and every
/// drive's jerk to its acceleration / rise_time, or to its jerk limit (the luffing rope's through
/// the map at every node), the hoist rope between its lengths at the lift's ends. With obstacles, the crane's body
/// (plan.lift_body) keeps clear of them by the clearance margin plus the minimum_time's clearance
/// allowance.
LiftProblem liftProblem(const TargetSpec& target, const QuasiStaticPlan& plan);

/// The parts the lift keeps clear (planning/lift_clearance.hpp) as the crane stands at an
/// equilibrium q of the map's plane: the boom's chord between the controls' boom foot and head
/// joints, its radius the largest of the lattice sections (truss members) along it
/// (planning/clearance.hpp: craneParts); the hoist rope from its end at the head, its radius the
/// rope's; the load of the target's radius. The rope's samples are set for the hoist rope at its
/// longest in the map, 5 % stretched.
LiftBody liftBody(const TargetSpec& target, const StaticMap& map, const Scene& scene, const Model& model, const VecX& q);

/// Refuses a lift whose boom, rope or load at the start or the target (at rest) lies closer to an
/// obstacle than the lift's margin (SceneError naming the trajectory's start or target).
void checkLiftEndsClear(const TargetSpec& target, const LiftProblem& problem);

/// The flatness plan (plan.path, plan.controls, plan.slewing_angles, plan.load_path) as the
/// lift's nodes: the controls' rates by central differences, the pendulum's angles from where the
/// path's load hangs below the suspension that the controls place.
LiftGuess flatnessGuess(const TargetSpec& target, const QuasiStaticPlan& plan, const LiftProblem& problem);

/// The lift's start: the flatness guess when all its nodes clear the obstacles by the lift's
/// margin; else over and around them: the load lifted at the pick to clear the tops of the
/// obstacles it can clear within the map (by the margin, the load radius and 1 m; at the pick,
/// the set and the nearer of them to the slewing axis), moved in to that nearer one, slewed,
/// moved out over the set and lowered (waypointGuess). The problem's hoist range is widened to
/// hold the start.
struct LiftStart {
  LiftGuess guess;
  std::string from;  // "the flatness plan" or "a lift over and around the obstacles"
};
LiftStart liftStart(const TargetSpec& target, const QuasiStaticPlan& plan, LiftProblem& problem);

}  // namespace cranesim
