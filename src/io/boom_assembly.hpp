#pragma once
// A boom assembled from its sections (`booms:`, docs/scene-format.md "Booms assembled from
// sections"): the tool places a foot piece, inserts and a top piece of the scene's truss types
// end to end along the boom axis at the boom angle, carries the head body with its joints along,
// and writes them as the truss members, head body and constraints a scene would draw by hand.
// The scene reader then reads the expanded scene as any other.

#include <yaml-cpp/yaml.h>

namespace cranesim {

/// `root` with every boom under `booms:` expanded into `members` (one truss member per section),
/// `bodies` (its head), `constraints` (the foot pin, the splices, the head) and `trusses` (a type
/// used at another length than its own). `root` is left as it is, so a scene composed on this
/// one still edits its `booms:`; without `booms:` the result is `root`. The expanded items keep
/// the nodes the scene wrote (names, types, the head's fields), so errors found in them later
/// name their lines. Throws SceneError naming the boom's field.
YAML::Node expandBooms(const YAML::Node& root);

}  // namespace cranesim
