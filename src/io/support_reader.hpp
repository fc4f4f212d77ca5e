#pragma once
// The `ground.supports` block of a scene (docs/scene-format.md#supports).

#include "cranesim/model/scene.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// Reads `ground.supports` against the scene's bodies (the supported body and its joints).
GroundSupportsSpec readGroundSupports(const YamlField& f, const Scene& scene);

}  // namespace cranesim
