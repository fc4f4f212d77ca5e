#pragma once
// A controller in the loop of a run (a scene's `feedback:`): every sample the operator's (or a
// plan's) speed references reach the inputs, directly before `start` and through anti-sway
// feedback on the boom head from then on (control/closed_loop.hpp runs it).

#include <map>
#include <string>

#include "cranesim/math/profile.hpp"
#include "cranesim/model/source_location.hpp"
#include "cranesim/model/sway_sensor_spec.hpp"

namespace cranesim {

struct FeedbackSpec {
  double sample_time = 0.02;  // s
  double start = 0.0;         // s: the feedback holds the boom head's reference path from here
  // The inputs and joints of the anti-sway controller (control/crane_sway.hpp).
  std::string slewing = "slewing", luffing_rope = "luffing_rope", hoist_rope = "hoist_rope";
  std::string hook = "load.origin", sheave = "head.sheave";
  /// s: the references' slewing and luffing speeds shaped for the crane's sway period
  /// (CraneSwaySpec::shaping_period); 0: not shaped.
  double shaping_period = 0.0;
  /// s: the hoist's speed references averaged over the boom's period (CraneSwaySpec::boom_period).
  double boom_period = 0.0;
  /// s: both axes feed back the swing about the angle's steady part (SwayAxisSpec::steady_angle_time); 0: none.
  double steady_angle_time = 0.0;
  /// How the rope's angles reach the controller (late, noisy); exact by default.
  SwaySensorSpec sensor;
  /// Speed references by input name, in the input's unit per second (absent: 0).
  std::map<std::string, Profile> references;
  SourceLocation where;
};

}  // namespace cranesim
