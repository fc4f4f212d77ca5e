#pragma once
// The `crane:` block of a scene (docs/scene-format.md#crane).

#include "cranesim/model/scene.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// Reads `crane:` against the scene's constraints (slewing and boom_foot: revolute), bodies
/// (load) and members (ropes); its joints are checked when the model is compiled (locateCrane).
CraneSpec readCrane(const YamlField& f, const Scene& scene);

}  // namespace cranesim
