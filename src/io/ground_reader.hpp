#pragma once
// The `ground.surface` block of a scene (docs/scene-format.md#ground-surface).

#include "cranesim/model/scene.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// Reads `ground.surface` against the scene's bodies and members (the parts resting on it).
GroundSurfaceSpec readGroundSurface(const YamlField& f, const Scene& scene);

}  // namespace cranesim
