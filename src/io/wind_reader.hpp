#pragma once
// The `wind:` block of a scene (docs/scene-format.md#wind).

#include "cranesim/model/scene.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// Reads `wind:` against the scene's gravity (what is horizontal), bodies and members (what may
/// be exposed).
WindSpec readWind(const YamlField& f, const Scene& scene);

}  // namespace cranesim
