#pragma once
// A run with its scene's feedback in the loop (`feedback:`, model/feedback_spec.hpp), as
// `crane-sim run` and a study's run cases perform it: every sample_time the references' speeds
// reach the inputs — set directly before the feedback's start, and from it as the references
// of a CraneSwayController that holds the boom head on their path while it damps the swing.

#include "cranesim/model/feedback_spec.hpp"
#include "cranesim/session/session.hpp"
#include "cranesim/solvers/dynamics.hpp"

namespace cranesim {

/// Runs `session` from where it is to solver.t_end under `feedback`; control.on_step is called
/// after each sample, control.stop_requested ends the run at its next step. SceneError at the
/// feedback's location for a hook or sheave joint the scene does not have.
SimulationOutcome runClosedLoop(Session& session, const FeedbackSpec& feedback, const SimulationControl& control = {});

}  // namespace cranesim
