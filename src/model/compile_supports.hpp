#pragma once
// The crane's supports on the ground (`ground.supports`) as elements
// (model/support_elements.hpp), listed in model.envelope.supports.

#include "cranesim/model/model.hpp"

namespace cranesim {

/// Adds the support elements of `ground.supports` under its body. The bed is placed where the
/// drawing puts the supports, settled by the mean settlement of the model's weight, so that the
/// drawn crane stands on springs that carry it (statics starts from there). Throws SceneError
/// for a body that is not a free rigid body.
void compileSupports(Model& model, const Scene& scene);

}  // namespace cranesim
