#include "cranesim/control/closed_loop.hpp"

#include <memory>
#include <stdexcept>

#include "cranesim/control/crane_sway.hpp"

namespace cranesim {

SimulationOutcome runClosedLoop(Session& session, const FeedbackSpec& feedback, const SimulationControl& control) {
  try {
    session.joint(feedback.hook);
    session.joint(feedback.sheave);
  } catch (const std::invalid_argument& e) {
    throw SceneError(feedback.where, e.what());
  }
  // A reference holds over the sample that starts at t: its value just after t.
  const auto reference = [&](const std::string& input, double t) {
    const auto it = feedback.references.find(input);
    return it == feedback.references.end() ? 0.0 : it->second(t, Limit::Right);
  };
  CraneSwaySpec spec;
  spec.slewing = feedback.slewing;
  spec.luffing_rope = feedback.luffing_rope;
  spec.hoist_rope = feedback.hoist_rope;
  spec.hook = feedback.hook;
  spec.sheave = feedback.sheave;
  spec.across.sample_time = spec.along.sample_time = feedback.sample_time;
  spec.shaping_period = feedback.shaping_period;
  spec.boom_period = feedback.boom_period;
  spec.across.steady_angle_time = spec.along.steady_angle_time = feedback.steady_angle_time;
  spec.sensor = feedback.sensor;
  std::unique_ptr<CraneSwayController> controller;

  const double t0 = session.time(), t_end = session.model().solver.t_end;
  bool going = t0 < t_end;
  for (long k = 0; going; ++k) {
    const double t = t0 + static_cast<double>(k) * feedback.sample_time;
    if (t >= feedback.start) {
      if (!controller) controller = std::make_unique<CraneSwayController>(session, spec);
      controller->apply(reference(spec.slewing, t), reference(spec.luffing_rope, t), reference(spec.hoist_rope, t));
    }
    for (const auto& [input, profile] : feedback.references)
      if (!controller || (input != spec.slewing && input != spec.luffing_rope && input != spec.hoist_rope))
        session.setInput(session.input(input), reference(input, t));
    going = session.advanceTo(std::min(t0 + static_cast<double>(k + 1) * feedback.sample_time, t_end), control.stop_requested);
    if (control.on_step) control.on_step(session.time());
  }
  return session.outcome();
}

}  // namespace cranesim
