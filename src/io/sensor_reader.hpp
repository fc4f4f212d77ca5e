#pragma once
// A feedback's `sensor:` — how the rope's angles reach the controller (model/sway_sensor_spec.hpp),
// in a scene's `feedback:` and in a target's feedback cases.

#include "cranesim/model/sway_sensor_spec.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// `{angle_noise: rad, rate_noise: rad/s, delay: s, seed}`, each optional (0).
SwaySensorSpec readSwaySensor(const YamlField& f);

}  // namespace cranesim
