#pragma once
// crane-opt's method minimum_time (docs/planning.md): the minimum-time lift NLP
// (planning/minimum_time_lift.hpp) set up on a target's static map and drive limits, and
// started from the target's flatness plan.

#include "cranesim/planning/minimum_time_lift.hpp"
#include "cranesim/planning/quasi_static_plan.hpp"

namespace cranesim {

/// The lift from the plan's start to its target on the plan's fitted map and plane, its pendulum
/// the flatness plan's (plan.pendulum_length_*, plan.pendulum_across_*, between the hoist
/// lengths of plan.controls' ends), within the target's drive limits: a drive without an
/// acceleration limit is held to speed / rise_time, and every coordinate's jerk to its drive's
/// acceleration / rise_time, or to the drive's jerk limit (the luffing rope's through the map's
/// steepest slope in the boom angle at the lift's ends).
LiftProblem liftProblem(const TargetSpec& target, const QuasiStaticPlan& plan);

/// The flatness plan (plan.path, plan.controls, plan.slewing_angles, plan.load_path) as the
/// lift's nodes: the controls' rates by central differences, the pendulum's angles from where the
/// path's load hangs below the suspension that the controls place.
LiftGuess flatnessGuess(const TargetSpec& target, const QuasiStaticPlan& plan, const LiftProblem& problem);

}  // namespace cranesim
