#pragma once

#include <string>

#include "cranesim/model/scene.hpp"

namespace cranesim {

/// Reads and validates a scene. Throws SceneError naming the YAML path and line of the
/// first problem: unknown keys, missing fields, wrong types, values out of range, references
/// to unknown bodies or joints.
Scene readScene(const std::string& path);
Scene parseScene(const std::string& text, const std::string& path_for_messages);

}  // namespace cranesim
