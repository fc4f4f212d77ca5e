#pragma once
// Compilation of a scene's `wind:` into the model's wind field and wind elements.

#include "cranesim/model/model.hpp"

namespace cranesim {

/// Adds the wind field and, for every exposed body and member, its wind elements
/// (model/wind_elements.hpp) and its WindPart.
void compileWind(Model& model, const Scene& scene);

}  // namespace cranesim
