#pragma once
// Which of a scene's ropes hang slack at one of their ends. A rope carries only tension: where a
// light hook load lets the part it holds push instead of pull (the thesis crane's sub-cable
// under its derrick when the hook carries less than about 2.5 t at a steep boom), that part has
// nothing holding it and the statics has no equilibrium to find. Said beside a failed statics,
// this names the cause that a stalled Newton does not.

#include <string>

#include "cranesim/model/model.hpp"
#include "cranesim/model/scene.hpp"

namespace cranesim {

/// The ropes of `scene` (compiled into `model`) without tension at their start or end in q at
/// time t, as "'<rope>' at its start" phrases joined by commas; empty when every rope pulls at
/// both ends. Reeved ropes count their winch's and dead end's parts.
std::string slackRopeEnds(const Scene& scene, const Model& model, const VecX& q, double t);

}  // namespace cranesim
