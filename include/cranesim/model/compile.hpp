#pragma once

#include "cranesim/model/model.hpp"

namespace cranesim {

/// Builds the model of a scene: one frame node and one rigid-body element per body, joints,
/// constraints and loads with resolved references. Throws SceneError naming the offending
/// YAML path (unknown joint, a constraint on a single body, a drive where none is possible).
Model compileModel(const Scene& scene);

}  // namespace cranesim
