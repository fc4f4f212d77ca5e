#pragma once
// Dotted paths into a base scene, as `modify`, `add`, `insert_before`, `insert_after` and
// `remove` name its parts: a mapping's field by its key (`solver.t_end`), a list's item by its
// `name` (`members.hoist_rope`, `bodies.head.joints.sheave`).

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace cranesim {

class YamlField;

/// The parts of a dotted path; fails at `entry` on an empty part (`a..b`, `.a`).
std::vector<std::string> scenePathParts(const YamlField& entry, const std::string& path);

/// The names of a list's items, in order (an item without a scalar `name` counts as "").
std::vector<std::string> itemNames(const YAML::Node& list);

/// The position of the item named `name` in `list`, or -1.
int itemIndex(const YAML::Node& list, const std::string& name);

/// The node at `parts` in `base`; fails at `entry` naming the first part the base lacks, with a
/// "did you mean" for a misspelt item name.
YAML::Node sceneNode(YAML::Node base, const YamlField& entry, const std::vector<std::string>& parts);

/// "the base scene's <list> have no item named 'x' (did you mean 'y'?; known: a, b)".
std::string noItemMessage(const std::string& list, const std::string& name, const YAML::Node& items);

}  // namespace cranesim
